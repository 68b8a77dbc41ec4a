# Vectorized eval / pdf / sample: the same numbers as the CLI per pair, Lambert's closed form, the sampler's
# own consistency, broadcasting, out=, and bad arrays raising instead of crashing.
import math
import threading

import numpy as np
import pytest

import shadelab

# Directions in the CLI's X,Y,Z form; not unit length, so both sides' normalization is exercised.
PAIRS = [
    ((0.3, 0.0, 1.0), (-0.3, 0.0, 1.0)),     # near the mirror direction
    ((0.2, 0.7, 0.4), (0.5, -0.1, 0.9)),      # off the plane of incidence (anisotropic models differ)
    ((0.9, 0.1, 0.05), (-0.8, 0.3, 0.2)),     # grazing
    ((0.3, 0.1, -1.0), (0.0, 0.0, 1.0)),      # light below the horizon: 0
]
# A non-default parameter set per model where one helps; every registry model is covered either way.
PARAMS = {
    "phong": {"n": 80, "kd": 0.2},
    "ward-anisotropic": {"alpha_x": 0.3, "alpha_y": 0.05},
    "cook-torrance": {"d": "beckmann", "g": "smith", "f": "schlick", "f0": [1.0, 0.78, 0.34], "m": 0.3},
    "wrapped-diffuse": {"w": 0.5},
}


def params_for(model, measured_file):
    """The keyword arguments a test builds `model` with: measured reads the session's MERL file (conftest.py)."""
    params = dict(PARAMS.get(model, {}))
    if model == "measured":
        params["file"] = str(measured_file)
    return params


def cli_params(params):
    out = []
    for k, v in params.items():
        text = ",".join(repr(float(x)) for x in v) if isinstance(v, (list, tuple)) else (
            v if isinstance(v, str) else repr(float(v)))
        out += ["--param", f"{k}={text}"]
    return out


def text(v):
    return ",".join(repr(float(x)) for x in v)


@pytest.mark.parametrize("model", [m["name"] for m in shadelab.models()])
def test_vectorized_eval_equals_cli_per_pair(cli, model, measured_file):
    params = params_for(model, measured_file)
    f = shadelab.Brdf(model, **params)
    wi = np.array([p[0] for p in PAIRS])
    wo = np.array([p[1] for p in PAIRS])
    values = f.eval(wi, wo)
    assert values.shape == (len(PAIRS), 3) and values.dtype == np.float64
    for row, (a, b) in enumerate(PAIRS):
        j = cli.json("brdf", "eval", model, *cli_params(params), "--wi", text(a), "--wo", text(b), "--json")
        assert values[row].tolist() == j["f"], (model, a, b)  # bit for bit
    assert np.all(values[3] == 0.0)


def test_lambert_against_its_closed_form():
    kd = np.array([0.2, 0.5, 0.9])
    f = shadelab.Brdf("lambert", kd=kd)
    rng = np.random.default_rng(1)
    wi = rng.normal(size=(1000, 3))
    wi[:, 2] = np.abs(wi[:, 2])
    wo = np.array([0.1, 0.2, 0.9])
    np.testing.assert_allclose(f.eval(wi, wo), np.broadcast_to(kd / math.pi, (1000, 3)), rtol=1e-15)
    cos_i = wi[:, 2] / np.linalg.norm(wi, axis=1)
    np.testing.assert_allclose(f.pdf(wi, wo), cos_i / math.pi, rtol=1e-12)  # cosine-weighted hemisphere


@pytest.mark.parametrize("model", [m["name"] for m in shadelab.models()])
def test_sample_returns_pdf_and_weight_consistent_with_eval(model, measured_file):
    f = shadelab.Brdf(model, **params_for(model, measured_file))
    rng = np.random.default_rng(7)
    n = 2000
    theta = rng.uniform(0, 1.4, n)
    phi = rng.uniform(0, 2 * math.pi, n)
    wo = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], axis=1)
    u = rng.uniform(0, 1, (n, 3))
    wi, pdf, weight = f.sample(wo, u)
    assert wi.shape == (n, 3) and pdf.shape == (n,) and weight.shape == (n, 3)
    np.testing.assert_allclose(np.linalg.norm(wi, axis=1), 1.0, rtol=1e-12)
    # The contract's tolerance (brdf.h; the check's "sample weights" item): 1e-6 relative.
    np.testing.assert_allclose(pdf, f.pdf(wi, wo), rtol=1e-6)
    up = (pdf > 0) & (wi[:, 2] > 0)
    expected = f.eval(wi[up], wo[up]) * wi[up, 2:3] / pdf[up, None]
    np.testing.assert_allclose(weight[up], expected, rtol=1e-6, atol=1e-300)
    assert np.all(weight[~up] == 0.0)


def test_broadcasting_single_rows_and_out():
    f = shadelab.Brdf("blinn-phong-modified", n=40)
    wi = np.array([[0.1, 0.2, 1.0], [0.5, 0.0, 0.5], [0.0, -0.3, 1.0]])
    wo = np.array([-0.2, 0.1, 1.0])
    full = f.eval(wi, np.tile(wo, (3, 1)))
    assert np.array_equal(f.eval(wi, wo), full)
    assert np.array_equal(f.eval(wi, wo[None, :]), full)
    assert f.eval(wi[0], wo).shape == (3,)
    assert isinstance(f.pdf(wi[0], wo), float)
    out = np.empty((3, 3))
    assert f.eval(wi, wo, out=out) is out and np.array_equal(out, full)
    pout = np.empty(3)
    assert f.pdf(wi, wo, out=pout) is pout
    # Lists and integer arrays convert; an empty batch gives an empty result.
    assert np.array_equal(f.eval(wi.tolist(), [[-0.2, 0.1, 1.0]] * 3), full)
    assert f.eval(np.zeros((0, 3)), wo).shape == (0, 3)
    assert f.eval(np.array([[0, 0, 2]]), np.array([[0, 0, 1]])).shape == (1, 3)


BAD_INPUTS = [
    (np.zeros((4, 2)), "wi: expected shape (N, 3) or (3,), got (4, 2)"),
    (np.zeros((2, 3, 3)), "wi: expected shape (N, 3) or (3,), got (2, 3, 3)"),
    (np.zeros(4), "wi: expected shape (N, 3) or (3,), got (4,)"),
    ("abc", "wi: expected an array of numbers, got str"),
    (None, "wi: expected an array of numbers, got None"),
    ([[0.0, 0.0, 0.0]], "wi: row 0 (0, 0, 0) is not a direction (zero length or not finite)"),
    ([[0.0, 0.0, 1.0], [math.nan, 0.0, 1.0]], "wi: row 1 (nan, 0, 1) is not a direction (zero length or not finite)"),
    ([[math.inf, 0.0, 1.0]], "wi: row 0 (inf, 0, 1) is not a direction (zero length or not finite)"),
    ([[1e300, 1e300, 1e300]], "wi: row 0 (1e+300, 1e+300, 1e+300) is not a direction (zero length or not finite)"),
]


@pytest.mark.parametrize("wi,message", BAD_INPUTS)
def test_bad_arrays_raise_with_the_argument_named(wi, message):
    f = shadelab.Brdf("phong")
    with pytest.raises(ValueError) as e:
        f.eval(wi, [0.0, 0.0, 1.0])
    assert str(e.value) == message
    with pytest.raises(ValueError):
        f.pdf(wi, [0.0, 0.0, 1.0])


def test_other_bad_calls_raise():
    f = shadelab.Brdf("phong")
    with pytest.raises(ValueError, match=r"wi and wo: 2 and 3 rows do not pair"):
        f.eval(np.ones((2, 3)), np.ones((3, 3)))
    with pytest.raises(ValueError, match=r"u: row 0 \(0.5, 1, 0.5\) has a value outside \[0, 1\)"):
        f.sample([0, 0, 1], [[0.5, 1.0, 0.5]])
    with pytest.raises(ValueError, match=r"u: row 1 \(nan, 0, 0\)"):
        f.sample([0, 0, 1], [[0.5, 0.5, 0.5], [math.nan, 0, 0]])
    with pytest.raises(ValueError, match="wo: row 0"):
        f.sample([[0, 0, 0]], [[0.5, 0.5, 0.5]])
    with pytest.raises(ValueError, match=r"out: expected a writable C-contiguous float64 array of shape \(2, 3\)"):
        f.eval(np.ones((2, 3)), [0, 0, 1], out=np.empty((2, 3), dtype=np.float32))
    with pytest.raises(ValueError, match=r"out: expected .* got \(3, 3\)"):
        f.eval(np.ones((2, 3)), [0, 0, 1], out=np.empty((3, 3)))
    read_only = np.empty((2, 3))
    read_only.flags.writeable = False
    with pytest.raises(ValueError, match="out: expected a writable"):
        f.eval(np.ones((2, 3)), [0, 0, 1], out=read_only)


def test_eval_from_several_threads_gives_the_same_numbers():
    f = shadelab.Brdf("cook-torrance")
    rng = np.random.default_rng(3)
    wi = np.abs(rng.normal(size=(100_000, 3)))
    wo = np.abs(rng.normal(size=(100_000, 3)))
    expected = f.eval(wi, wo)
    results = [None] * 4

    def work(k):
        results[k] = f.eval(wi, wo)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        assert np.array_equal(r, expected)


def test_eval_releases_the_gil():
    # While a long eval runs in another thread, this thread keeps running Python code. If the loop held the
    # GIL, this thread would stall for the whole eval: its longest gap between iterations would be about
    # the eval's duration, not a small part of it.
    f = shadelab.Brdf("cook-torrance")
    wi = np.tile([0.3, 0.2, 0.9], (2_000_000, 1))
    wo = np.tile([-0.2, 0.1, 0.8], (2_000_000, 1))
    longest, duration = _longest_gap_while(lambda: f.eval(wi, wo))
    assert longest < 0.5 * duration, (longest, duration)


def _longest_gap_while(call):
    # The longest gap between this thread's iterations while call() runs in another thread, and how long
    # call() takes alone.
    import time

    t0 = time.perf_counter()
    call()
    duration = time.perf_counter() - t0
    started = threading.Event()

    def work():
        started.set()
        call()

    t = threading.Thread(target=work)
    longest = 0.0
    last = time.perf_counter()
    t.start()
    started.wait()
    while t.is_alive():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
    t.join()
    return longest, duration


@pytest.mark.parametrize("method", ["pdf", "sample", "albedo"])
def test_pdf_sample_albedo_release_the_gil(method):
    # As test_eval_releases_the_gil, for the other loops issue 14 names.
    f = shadelab.Brdf("cook-torrance")
    wi = np.tile([0.3, 0.2, 0.9], (2_000_000, 1))
    wo = np.tile([-0.2, 0.1, 0.8], (2_000_000, 1))
    u = np.tile([0.25, 0.5, 0.75], (2_000_000, 1))
    calls = {
        "pdf": lambda: f.pdf(wi, wo),
        "sample": lambda: f.sample(wo, u),
        "albedo": lambda: f.albedo(np.linspace(0.0, 89.0, 40)),
    }
    longest, duration = _longest_gap_while(calls[method])
    assert longest < 0.5 * duration, (longest, duration)


def unit_rows(rng, n):
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2])
    return v / np.linalg.norm(v, axis=1, keepdims=True)


@pytest.mark.parametrize("model", [m["name"] for m in shadelab.models()])
def test_vectorized_eval_equals_per_pair_calls_across_chunks(model, measured_file):
    # 700 pairs are three chunks of the binding's walk (256 each): the first and last are unit directions,
    # used in place by the library's eval_batch; the middle one holds a row to normalize, so the whole
    # chunk is copied and normalized first. Each row must equal eval of that pair alone.
    f = shadelab.Brdf(model, **params_for(model, measured_file))
    rng = np.random.default_rng(11)
    wi = unit_rows(rng, 700)
    wo = unit_rows(rng, 700)
    wi[300] *= 3.0
    wo[[5, 650]] = [[0.3, 0.1, -0.9], [0.2, 0.0, 0.0]]  # below and on the horizon
    values = f.eval(wi, wo)
    for i in range(700):
        assert values[i].tobytes() == f.eval(wi[i], wo[i]).tobytes(), (model, i)
    assert np.all(values[[5, 650]] == 0.0)
    # One wo for every wi (broadcast: copied chunks) equals the tiled rows (in place).
    assert np.array_equal(f.eval(wi, wo[7]), f.eval(wi, np.tile(wo[7], (700, 1))))


def test_eval_into_an_input_or_an_overlapping_view():
    f = shadelab.Brdf("cook-torrance")
    rng = np.random.default_rng(12)
    wi = unit_rows(rng, 600)
    wo = unit_rows(rng, 600)
    expected = f.eval(wi, wo)
    same = wi.copy()
    assert f.eval(same, wo, out=same) is same and np.array_equal(same, expected)
    buf = np.empty((601, 3))
    buf[:-1] = wi
    shifted = buf[1:]  # out one row after wi in the same memory
    f.eval(buf[:-1], wo, out=shifted)
    assert np.array_equal(shifted, expected)


def test_bad_rows_inside_unit_chunks_name_their_row():
    f = shadelab.Brdf("lambert")
    rng = np.random.default_rng(13)
    wi = unit_rows(rng, 600)
    wo = unit_rows(rng, 600)
    for name, arr, row, value in [("wi", wi, 300, math.nan), ("wo", wo, 599, math.inf), ("wo", wo, 0, 0.0)]:
        bad = arr.copy()
        bad[row] = [value, 0.0, 0.0] if value != 0.0 else [0.0, 0.0, 0.0]
        args = (bad, wo) if name == "wi" else (wi, bad)
        with pytest.raises(ValueError) as e:
            f.eval(*args)
        v = "nan" if math.isnan(value) else ("inf" if math.isinf(value) else "0")
        assert str(e.value) == f"{name}: row {row} ({v}, 0, 0) is not a direction (zero length or not finite)"
        with pytest.raises(ValueError, match=f"{name}: row {row} "):
            f.pdf(*args)
    with pytest.raises(ValueError) as e:
        f.eval(wi, wo[:599])
    assert str(e.value) == "wi and wo: 600 and 599 rows do not pair (give the same number of rows, or one row)"
    with pytest.raises(ValueError) as e:
        f.eval(wi[:, :2], wo)
    assert str(e.value) == "wi: expected shape (N, 3) or (3,), got (600, 2)"
