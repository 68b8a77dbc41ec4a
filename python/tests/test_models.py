# The model list comes from the registry, parameters validate as in the CLI, and bad input raises
# ValueError with the CLI's own line.
import math

import numpy as np
import pytest

import shadelab


def test_models_are_the_registry_the_cli_lists(cli):
    listed = cli.json("brdf", "list", "--json")["models"]
    models = shadelab.models()
    assert [m["name"] for m in models] == [m["name"] for m in listed]
    for m, c in zip(models, listed):
        assert m["summary"] == c["formula"] and m["source"] == c["source"]
        assert [p["name"] for p in m["params"]] == [p["name"] for p in c["params"]]
        for p, q in zip(m["params"], c["params"]):
            assert (p["kind"], p["default_text"], p["description"]) == (q["kind"], q["default"], q["description"])
            if p["kind"] == "choice":
                assert p["choices"] == q["choices"] and p["default"] in p["choices"]
            elif p["kind"] == "file":  # a path, no range; measured's is required (no default)
                assert p["required"] == q["required"] and p["default"] == (None if p["required"] else p["default_text"])
            else:
                assert (p["min"], p["max"]) == (q["min"], q["max"])


def test_every_model_builds_with_its_defaults_and_reports_them(cli):
    for m in shadelab.models():
        if any(p.get("required") for p in m["params"]):
            # measured: no default file; refused with the CLI's line
            with pytest.raises(ValueError) as e:
                shadelab.Brdf(m["name"])
            assert str(e.value) == cli.error("brdf", "eval", m["name"], "--wi", "0,0,1", "--wo", "0,0,1")
            assert "parameter 'file' is required" in str(e.value)
            continue
        f = shadelab.Brdf(m["name"])
        assert f.name == m["name"]
        assert list(f.params) == [p["name"] for p in m["params"]]
        for p in m["params"]:
            got = f.params[p["name"]]
            want = p["default"]
            if p["kind"] == "color" and not isinstance(want, tuple):
                want = (want,) * 3
            assert got == (tuple(want) if isinstance(want, tuple) else want), (m["name"], p["name"])


def test_parameters_take_numbers_colours_words_and_lobes():
    f = shadelab.Brdf("cook-torrance", kd=[0.1, 0.2, 0.3], ks=np.float32(0.5), d="beckmann", m=np.array(0.25))
    assert f.params["kd"] == (0.1, 0.2, 0.3)
    assert f.params["ks"] == (0.5, 0.5, 0.5)
    assert f.params["d"] == "beckmann" and f.params["m"] == 0.25
    lf = shadelab.Brdf("lafortune", lobes=[[-1, -1, 1, 20], [0, 0, 1, 5]])
    assert lf.params["lobes"] == [[-1.0, -1.0, 1.0, 20.0], [0.0, 0.0, 1.0, 5.0]]
    assert shadelab.Brdf("lafortune", lobes="-1,-1,1,20;0,0,1,5").params["lobes"] == lf.params["lobes"]
    # Numbers pass exactly (shortest round-trip text), so 0.1 is the double 0.1.
    assert shadelab.Brdf("phong", n=0.1 + 0.2).params["n"] == 0.1 + 0.2
    assert "n=100" in repr(shadelab.Brdf("phong", n=100))


# (model, Python keyword arguments, the same as CLI --param texts)
BAD = [
    ("no-such-model", {}, []),
    ("phong", {"q": 1}, ["q=1"]),
    ("phong", {"n": -1}, ["n=-1"]),
    ("phong", {"n": math.nan}, ["n=nan"]),
    ("phong", {"n": math.inf}, ["n=inf"]),
    ("phong", {"n": [1, 2]}, ["n=1,2"]),
    ("phong", {"kd": [0.1, 0.2]}, ["kd=0.1,0.2"]),
    ("phong", {"normalization": "sometimes"}, ["normalization=sometimes"]),
    ("phong", {"n": "ten"}, ["n=ten"]),
    ("cook-torrance", {"kd": 2000}, ["kd=2000"]),
    ("lafortune", {"lobes": [[1, 2, 3]]}, ["lobes=1,2,3"]),
]


@pytest.mark.parametrize("model,kwargs,params", BAD)
def test_bad_models_and_parameters_raise_the_cli_line(cli, model, kwargs, params):
    args = ["brdf", "eval", model]
    for p in params:
        args += ["--param", p]
    expected = cli.error(*args, "--wi", "0,0,1", "--wo", "0,0,1")
    with pytest.raises(ValueError) as e:
        shadelab.Brdf(model, **kwargs)
    assert str(e.value) == expected


def test_measured_reads_a_file_given_as_str_or_path(cli, measured_file, tmp_path):
    kinds = {p["name"]: p["kind"] for m in shadelab.models() if m["name"] == "measured" for p in m["params"]}
    assert kinds == {"file": "file"}
    a = shadelab.Brdf("measured", file=str(measured_file))
    b = shadelab.Brdf("measured", file=measured_file)  # a pathlib.Path
    assert a.params["file"] == b.params["file"] == str(measured_file)
    wi, wo = np.array([0.3, 0.1, 0.9]), np.array([-0.2, 0.0, 1.0])
    assert a.eval(wi, wo).tolist() == b.eval(wi, wo).tolist()
    j = cli.json("brdf", "eval", "measured", "--param", f"file={measured_file}", "--wi", "0.3,0.1,0.9", "--wo", "-0.2,0,1",
                 "--json")
    assert a.eval(wi, wo).tolist() == j["f"]
    for bad in (tmp_path / "missing.binary", tmp_path):
        with pytest.raises(ValueError) as e:
            shadelab.Brdf("measured", file=bad)
        assert str(e.value) == cli.error("brdf", "eval", "measured", "--param", f"file={bad}", "--wi", "0,0,1", "--wo", "0,0,1")
        assert str(bad) in str(e.value)


def test_wrong_types_never_crash():
    for value in (None, object(), {"a": 1}, b"1", True, [[1], 2], [], np.zeros((2, 2, 2))):
        with pytest.raises(ValueError):
            shadelab.Brdf("phong", n=value)
    with pytest.raises(TypeError):
        shadelab.Brdf(3)
