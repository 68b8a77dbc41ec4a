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


def _spec_gloss_albedo(diffuse, specular, glossiness, thetas):
    # KHR_materials_pbrSpecularGlossiness's BRDF (brdf/spec_gloss.h) as the registry's ggx model: Lambert of
    # diffuse (1 - max(specular)) plus GGX with Schlick's Fresnel of F0 = specular and the correlated Smith V.
    c_diff = np.asarray(diffuse) * (1.0 - max(specular))
    alpha = max((1.0 - glossiness) ** 2, 1e-4)
    f = shadelab.Brdf("ggx", kd=list(c_diff), ks=1, alpha=alpha, f="schlick", f0=list(specular), g="smith-correlated",
                      ms="none")
    return np.asarray(f.albedo(thetas))


def test_convert_spec_gloss_on_arrays_beats_pr1719_by_quadrature():
    diffuse = np.array([[0.6, 0.4, 0.2], [0.0, 0.0, 0.0], [0.8, 0.8, 0.8]])
    specular = np.array([[0.04, 0.04, 0.04], [1.0, 0.766, 0.336], [0.2, 0.1, 0.05]])
    glossiness = np.array([0.5, 0.9, 0.3])
    out = shadelab.convert_spec_gloss(diffuse, specular, glossiness)
    assert out["base_color"].shape == (3, 3) and out["roughness"].shape == (3,)
    thetas = [0, 10, 20, 30, 40, 50, 60, 70, 80]
    for i in range(3):
        sg = _spec_gloss_albedo(diffuse[i], specular[i], glossiness[i], thetas)
        # The conversion's ior is 1000 ("infinite"); the registry takes ior up to 10, so the same f0 =
        # ((ior - 1)/(ior + 1))^2 specular_color is given as ior 10 with specular_color scaled to match.
        scale = ((float(out["ior"][i]) - 1) / (float(out["ior"][i]) + 1)) ** 2 / (9 / 11) ** 2
        assert out["ior"][i] == 1000
        ours = shadelab.Brdf("gltf", base_color=list(out["base_color"][i]), metallic=float(out["metallic"][i]),
                             roughness=float(out["roughness"][i]), ior=10, specular=float(out["specular"][i]),
                             specular_color=list(scale * out["specular_color"][i]))
        start = shadelab.Brdf("gltf", base_color=list(diffuse[i]), metallic=0, roughness=1 - glossiness[i], ior=10,
                              specular=1, specular_color=list(scale * specular[i]))
        ours_diff = np.abs(np.asarray(ours.albedo(thetas)) - sg).max()
        start_diff = np.abs(np.asarray(start.albedo(thetas)) - sg).max()
        # The rule's own figure is from its tables (1.2e-5 from the quadrature: docs/conversions.md).
        assert ours_diff == pytest.approx(out["albedo_difference"][i], abs=5e-5)
        assert start_diff == pytest.approx(out["start_albedo_difference"][i], abs=5e-5)
        assert ours_diff <= start_diff + 1e-6
    # The gold metal (black diffuse) converts exactly; the plastic improves on PR #1719 by several times.
    assert out["albedo_difference"][1] < 1e-4
    assert out["albedo_difference"][0] < 0.3 * out["start_albedo_difference"][0]
    # One row broadcasts; a number is a grey.
    one = shadelab.convert_spec_gloss([0.6, 0.4, 0.2], 0.04, 0.5)
    assert one["roughness"][0] == out["roughness"][0]
    with pytest.raises(ValueError, match="glossiness: values must lie in"):
        shadelab.convert_spec_gloss(diffuse, specular, [0.5, 1.5, 0.3])
    with pytest.raises(ValueError, match="specular: 2 rows"):
        shadelab.convert_spec_gloss(diffuse, specular[:2], glossiness)
    with pytest.raises(ValueError, match="method"):
        shadelab.convert_spec_gloss(diffuse, specular, glossiness, method="slow")
