# The key proofs re-run through Python, each against an independent computation written here: the zoo
# against Gauss-Legendre quadrature in NumPy and the closed forms, the white-furnace albedo, the
# chi-square test of the samplers through check(), and the SH / irradiance bake of a constant environment.
import math

import numpy as np
import pytest

import shadelab

# Schueler 2011's rows, written here in u = cos(t) (or cos(a)), so I(n) = integral over [0, 1] du:
# (integrand in u, closed-form normalization 1 / (2 pi I(n))).
ZOO = {
    "phong": (lambda u, n: u ** n, lambda n: (n + 1) / (2 * math.pi)),
    "phong-modified": (lambda u, n: u ** (n + 1), lambda n: (n + 2) / (2 * math.pi)),
    "blinn-phong": (lambda u, n: ((1 + u) / 2) ** (n / 2),  # cos(t/2)^2 = (1 + cos t) / 2
                    lambda n: (n + 2) / (4 * math.pi * (2 - 2 ** (-n / 2)))),
    "blinn-phong-modified": (lambda u, n: ((1 + u) / 2) ** (n / 2) * u,
                             lambda n: (n + 2) * (n + 4) / (8 * math.pi * (2 ** (-n / 2) + n))),
    "blinn-phong-ndf": (lambda u, n: u ** n, lambda n: (n + 1) / (2 * math.pi)),
    "blinn-phong-heightfield": (lambda u, n: u ** (n + 1), lambda n: (n + 2) / (2 * math.pi)),
}


def gauss_legendre_01(f, order=20):
    # Composite Gauss-Legendre on [0, 1]: geometric panels toward 0 (u^n with fractional n) and fine
    # uniform panels elsewhere (u^1000 is narrow near 1).
    x, w = np.polynomial.legendre.leggauss(order)
    edges = np.unique(np.concatenate([[0.0], np.geomspace(1e-16, 0.01, 80), np.linspace(0.01, 1.0, 2000)]))
    mid = 0.5 * (edges[1:] + edges[:-1])[:, None]
    half = 0.5 * (edges[1:] - edges[:-1])[:, None]
    return float(np.sum(w * f(mid + half * x) * half))


def test_zoo_rows_against_independent_quadrature_and_closed_forms():
    exponents = [0.0, 0.5, 1.0, 10.0, 100.0, 1000.0]
    rows = shadelab.zoo(exponents)
    assert len(rows) == 6 * len(exponents)
    assert [r["model"] for r in rows[:6]] == list(ZOO)
    for r in rows:
        integrand, closed = ZOO[r["model"]]
        n = r["n"]
        numeric = 1.0 / (2 * math.pi * gauss_legendre_01(lambda u: integrand(u, n)))
        assert r["numeric"] == pytest.approx(numeric, rel=1e-11), r
        assert r["closed_form_value"] == pytest.approx(closed(n), rel=1e-12), r
        assert r["relative_error"] < 1e-10 and r["converged"]
        if r["lower"] is not None:
            assert r["lower"] <= r["closed_form_value"] <= r["upper"]


def test_zoo_bad_exponents_raise_the_cli_line(cli):
    for n in (-1.0, math.nan):
        expected = cli.error("zoo", "--n", repr(n)).replace("--n:", "n:")
        with pytest.raises(ValueError) as e:
            shadelab.zoo(n)
        assert str(e.value) == expected


def test_white_furnace_albedo():
    # A white Lambert surface reflects everything at every angle; the zoo's normalized lobes reflect ks at
    # normal incidence (their normalization is exactly what makes it so).
    np.testing.assert_allclose(shadelab.Brdf("lambert", kd=1).albedo([0, 30, 60, 85, 89]), 1.0, rtol=1e-9)
    for model in ("phong-modified", "blinn-phong-modified"):
        for n in (1, 100, 10000):
            a = shadelab.Brdf(model, kd=0, ks=1, n=n).albedo(0.0)
            np.testing.assert_allclose(a, 1.0, rtol=1e-9, err_msg=f"{model} n={n}")


@pytest.mark.parametrize("model,params", [("ward-anisotropic", {"alpha_x": 0.3, "alpha_y": 0.1}),
                                          ("cook-torrance", {"m": 0.4}),
                                          ("wrapped-diffuse", {"w": 0.3})])
def test_albedo_equals_numpy_quadrature_of_vectorized_eval(model, params):
    # The albedo integral done here on a polar grid with the vectorized eval, against the library's.
    f = shadelab.Brdf(model, **params)
    theta_o = math.radians(40)
    wo = np.array([math.sin(theta_o), 0.0, math.cos(theta_o)])
    xt, wt = np.polynomial.legendre.leggauss(200)
    xp, wp = np.polynomial.legendre.leggauss(400)
    t = 0.25 * math.pi * (xt + 1)           # theta_i in [0, pi/2]
    p = math.pi * (xp + 1)                  # phi_i in [0, 2 pi]
    T, P = np.meshgrid(t, p, indexing="ij")
    wi = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], axis=-1).reshape(-1, 3)
    weights = (np.outer(wt * 0.25 * math.pi, wp * math.pi) * np.sin(T) * np.cos(T)).reshape(-1, 1)
    numeric = np.sum(f.eval(wi, wo) * weights, axis=0)
    np.testing.assert_allclose(f.albedo(40.0), numeric, rtol=2e-4)


def test_check_passes_for_a_good_model_with_its_chi_square_tests():
    report = shadelab.Brdf("blinn-phong-modified", n=30, kd=0.2, ks=0.5).check(samples=200_000)
    assert report["passed"], report
    names = [c["name"] for c in report["checks"]]
    chi = [c for c in report["checks"] if c["name"].startswith("chi-square")]
    assert [c["name"] for c in chi] == [f"chi-square theta={a}" for a in (0, 30, 60, 80)], names
    for c in chi:
        assert c["figure"] >= c["threshold"] > 0  # p-value above the Sidak-corrected level
    assert {"normalization", "energy", "reciprocity", "pdf integral", "sample weights"} <= set(names)


def test_check_reports_a_failure():
    # Unnormalized Blinn-Phong with kd = ks = 1 reflects more than it receives: the energy check fails.
    report = shadelab.Brdf("blinn-phong", kd=1, ks=1, n=1, normalization="none").check(angles_deg=[30], samples=50_000)
    assert not report["passed"]
    energy = next(c for c in report["checks"] if c["name"] == "energy")
    assert not energy["passed"] and energy["figure"] > 1.0


def test_check_angles_are_validated():
    with pytest.raises(ValueError, match=r"angles_deg: 90 is out of range \[0, 90\) degrees"):
        shadelab.Brdf("lambert").check(angles_deg=[0, 90])
    with pytest.raises(ValueError, match="theta_deg: -1 is out of range"):
        shadelab.Brdf("lambert").albedo([-1])
    with pytest.raises(ValueError, match="samples: expected an integer"):
        shadelab.Brdf("lambert").check(samples=1e5)
    with pytest.raises(ValueError, match=r"samples: 10 is out of range \[1000, 1e8\]"):
        shadelab.Brdf("lambert").check(samples=10)
    with pytest.raises(ValueError, match="theta_deg: expected an array of numbers"):
        shadelab.Brdf("lambert").albedo("forty")


def test_sh_of_a_constant_environment():
    y00 = 1.0 / (2.0 * math.sqrt(math.pi))
    env = np.full((64, 128, 3), 0.5, dtype=np.float32)
    game = shadelab.bake_sh(env)
    assert game.shape == (9, 3)
    # E/pi = sum c_i Y_i: only Y00 survives, and a white Lambert surface shows 0.5 (the game convention).
    np.testing.assert_allclose(game[0] * y00, 0.5, rtol=1e-6)
    np.testing.assert_allclose(game[1:], 0.0, atol=1e-6)
    radiometric = shadelab.bake_sh(env, units="radiometric", details=True)
    np.testing.assert_allclose(radiometric["irradiance_coefficients"][0] * y00, math.pi * 0.5, rtol=1e-6)
    # The projected radiance itself: L c0 = 0.5 * integral of Y00 = 0.5 * 4 pi * Y00.
    np.testing.assert_allclose(radiometric["radiance_coefficients"][0], 0.5 * 4 * math.pi * y00, rtol=1e-6)
    assert radiometric["band_factors"] == pytest.approx((math.pi, 2 * math.pi / 3, math.pi / 4))
    faces = np.full((6, 8, 8, 3), 0.5, dtype=np.float32)
    np.testing.assert_allclose(shadelab.bake_sh(faces)[0] * y00, 0.5, rtol=1e-6)


def test_irradiance_of_a_constant_environment():
    env = np.full((64, 128, 3), 0.5, dtype=np.float32)  # 32 x 32 faces
    e = shadelab.bake_irradiance(env, size=8)
    assert e.shape == (6, 8, 8, 3) and e.dtype == np.float32
    # Exact up to the texels the horizon cuts (as in the C++ test: 1e-4 with 32 x 32 input faces).
    np.testing.assert_allclose(e, 0.5, rtol=1e-4)
    np.testing.assert_allclose(shadelab.bake_irradiance(env, size=4, units="radiometric"), math.pi * 0.5, rtol=1e-4)
    assert shadelab.bake_irradiance(env, size=4, layout="hcross").shape == (12, 16, 3)
    assert shadelab.bake_irradiance(env, size=4, layout="latlong").shape == (8, 16, 3)


def test_bake_sh_equals_the_cli_on_a_blender_world(cli, blender_world):
    j = cli.json("bake", "sh", blender_world, "--json")
    d = shadelab.bake_sh(blender_world, details=True)
    assert d["irradiance_coefficients"].tolist() == j["irradiance_coefficients"]
    assert d["radiance_coefficients"].tolist() == j["radiance_coefficients"]
    for key in ("order", "basis", "units", "convention", "window"):
        assert d[key] == j[key], key
    assert list(d["band_factors"]) == j["band_factors"]
    jr = cli.json("bake", "sh", blender_world, "--units", "radiometric", "--window", "hanning", "--json")
    dr = shadelab.bake_sh(blender_world, units="radiometric", window="hanning", details=True)
    assert dr["irradiance_coefficients"].tolist() == jr["irradiance_coefficients"]
    assert dr["convention"] == jr["convention"]


def test_bad_environments_raise():
    with pytest.raises(ValueError, match=r"image: cube cross: a 30 x 20 image is neither"):
        shadelab.bake_sh(np.ones((20, 30, 3)))
    bad = np.full((16, 32, 3), 0.5)
    bad[3, 4, 1] = math.nan
    with pytest.raises(ValueError, match=r"image: pixel \(x 4, y 3\) channel G is nan"):
        shadelab.bake_sh(bad)
    with pytest.raises(ValueError, match="units: 'lux' is not one of game | radiometric"):
        shadelab.bake_sh(np.ones((16, 32, 3)), units="lux")
    with pytest.raises(ValueError, match=r"size: 0 is out of range \[1, 1024\]"):
        shadelab.bake_irradiance(np.ones((16, 32, 3)), size=0)
    with pytest.raises(ValueError, match=r"input_size: 4096 is out of range \[1, 2048\]"):
        shadelab.bake_sh(np.ones((16, 32, 3)), input_size=4096)
    with pytest.raises(ValueError, match="input_size: expected an integer"):
        shadelab.bake_sh(np.ones((16, 32, 3)), input_size=2.5)
    with pytest.raises(ValueError, match=r"image: cube faces need shape \(6, S, S, 3\)"):
        shadelab.bake_sh(np.ones((5, 8, 8, 3)))
