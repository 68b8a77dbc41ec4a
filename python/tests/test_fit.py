# The fitter and the shininess conversion from Python: data made on fit_grid by a Brdf of known parameters are
# fitted back; the conversion gives the CLI's numbers; bad arrays raise ValueError.
import json
import os
import subprocess

import numpy as np
import pytest

import shadelab


def test_fit_grid_weights_measure_pairs_of_upper_directions():
    g = shadelab.fit_grid(theta_d_stride=2, phi_d_stride=2, max_theta_deg=90.0)
    assert g["wi"].shape == g["wo"].shape and g["wi"].shape[1] == 3
    assert g["weight"].shape == (g["wi"].shape[0],)
    # (2 pi)^2: the measure of pairs of upper-hemisphere directions (docs/fitting.md)
    assert abs(g["weight"].sum() / (4 * np.pi ** 2) - 1) < 0.01


def test_fit_recovers_known_parameters_from_arrays():
    g = shadelab.fit_grid(theta_d_stride=6, phi_d_stride=12)
    truth = shadelab.Brdf("ggx", alpha=0.3, f0=0.04, kd=[0.5, 0.3, 0.1])
    values = truth.eval(g["wi"], g["wo"])
    r = shadelab.fit("ggx", g["wi"], g["wo"], values, g["weight"], metric="log", starts=2)
    assert r["fitted"] == ["kd", "alpha", "f0"]
    assert r["params"]["alpha"] == pytest.approx(0.3, rel=1e-3)
    assert r["params"]["kd"] == pytest.approx((0.5, 0.3, 0.1), rel=1e-3)
    assert r["params"]["f0"] == pytest.approx((0.04, 0.04, 0.04), rel=1e-3)
    assert r["residual"] < 1e-6
    rebuilt = shadelab.Brdf("ggx", **dict(r["assignments"]))
    assert np.allclose(rebuilt.eval(g["wi"], g["wo"]), values, rtol=1e-3, atol=1e-6)


def test_fit_fixes_and_frees_by_name():
    g = shadelab.fit_grid(theta_d_stride=6, phi_d_stride=12)
    values = shadelab.Brdf("ward", kd=0.2, ks=0.3, alpha=0.1).eval(g["wi"], g["wo"])
    r = shadelab.fit("ward", g["wi"], g["wo"], values[:, 0], fix={"kd": 0.2}, free=["alpha", "ks"], starts=1)
    assert r["fitted"] == ["ks", "alpha"]
    assert r["params"]["alpha"] == pytest.approx(0.1, rel=1e-3)


def test_convert_shininess_gives_the_clis_numbers():
    rows = shadelab.convert_shininess("blinn-phong", "ggx", [10, 100])
    assert [r["n"] for r in rows] == [10, 100]
    exe = os.environ.get("SHADELAB_EXE")
    if exe:
        cli = json.loads(subprocess.run([exe, "convert", "shininess", "--from", "blinn-phong", "--to", "ggx", "--n", "100", "--json"],
                                        check=True, capture_output=True, text=True).stdout)
        assert rows[1]["alpha"] == cli["alpha"]
        assert rows[1]["mappings"][0]["alpha"] == cli["mappings"][0]["alpha"]
    assert rows[1]["mappings"][0]["alpha"] == pytest.approx(np.sqrt(2 / 102), rel=1e-12)
    assert rows[0]["alpha"] > rows[1]["alpha"]


@pytest.mark.parametrize("call, message", [
    (lambda g, v: shadelab.fit("ggx", g["wi"], g["wo"][:5], v), "wo: 5 rows"),
    (lambda g, v: shadelab.fit("ggx", g["wi"], g["wo"], v[:5]), "values: expected"),
    (lambda g, v: shadelab.fit("ggx", g["wi"], g["wo"], v, metric="l1"), "cosine-l2, cube-root, log"),
    (lambda g, v: shadelab.fit("nope", g["wi"], g["wo"], v), "unknown model 'nope'"),
    (lambda g, v: shadelab.fit("ggx", g["wi"], g["wo"], v, free=["nope"]), "'nope'"),
    (lambda g, v: shadelab.fit("ggx", g["wi"], g["wo"], np.full_like(v, np.nan)), "not finite"),
    (lambda g, v: shadelab.convert_shininess("ward", "ggx", 10), "--from"),
    (lambda g, v: shadelab.fit_grid(theta_d_stride=0), "theta_d_stride"),
])
def test_bad_input_raises_value_error(call, message):
    g = shadelab.fit_grid(theta_d_stride=30, phi_d_stride=60)
    v = np.ones((g["wi"].shape[0], 3))
    with pytest.raises(ValueError, match=message):
        call(g, v)


def test_merl_data_reads_a_file_and_refuses_a_bad_one(tmp_path):
    exe = os.environ.get("SHADELAB_EXE")
    if not exe:
        pytest.skip("SHADELAB_EXE not set (CTest sets it)")
    path = tmp_path / "lambert.binary"
    subprocess.run([exe, "measure", "lambert", "--param", "kd=0.5", "--out", str(path)], check=True)
    d = shadelab.merl_data(str(path), theta_d_stride=30, phi_d_stride=60)
    assert np.allclose(d["values"], 0.5 / np.pi, rtol=1e-12)
    bad = tmp_path / "short.binary"
    bad.write_bytes(b"0123")
    with pytest.raises(ValueError, match="short.binary"):
        shadelab.merl_data(str(bad))
