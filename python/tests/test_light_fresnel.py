# Fresnel and light units: closed forms and the CLI's numbers and messages.
import math

import numpy as np
import pytest

import shadelab


def test_fresnel_at_normal_incidence_is_the_closed_form():
    for n in (1.33, 1.5, 2.4):
        assert shadelab.fresnel(ior=n) == pytest.approx(((n - 1) / (n + 1)) ** 2, rel=1e-14)
    n, k = 0.2, 3.0
    assert shadelab.fresnel(ior=n, k=k) == pytest.approx(((n - 1) ** 2 + k ** 2) / ((n + 1) ** 2 + k ** 2), rel=1e-14)
    assert shadelab.fresnel(ior=1.5, theta_deg=90.0) == pytest.approx(1.0)
    assert shadelab.fresnel(ior=1 / 1.5, theta_deg=60.0) == 1.0  # total internal reflection
    curve = shadelab.fresnel(ior=1.5, theta_deg=np.linspace(0, 90, 7))
    assert curve.shape == (7,) and np.all(np.diff(curve) > 0)


def test_fresnel_equals_the_cli(cli):
    j = cli.json("fresnel", "--ior", "1.5", "--theta", "60", "--json")
    assert shadelab.fresnel(ior=1.5, theta_deg=60.0) == j["F"]
    j = cli.json("fresnel", "--ior", "0.27,2.78", "--theta", "45", "--json")
    assert shadelab.fresnel(ior=0.27, k=2.78, theta_deg=45.0) == j["F"]
    j = cli.json("fresnel", "--material", "gold", "--theta", "30", "--json")
    assert shadelab.fresnel(material="gold", theta_deg=30.0).tolist() == j["F"]
    names = [m["name"] for m in cli.json("fresnel", "--list", "--json")["materials"]]
    assert [m["name"] for m in shadelab.fresnel_materials()] == names


def test_fresnel_bad_input_raises():
    with pytest.raises(ValueError, match=r"theta_deg: 95 is out of range \[0, 90\] degrees"):
        shadelab.fresnel(ior=1.5, theta_deg=95)
    with pytest.raises(ValueError, match="ior: N = -1 must be positive"):
        shadelab.fresnel(ior=-1)
    with pytest.raises(ValueError, match="ior: N = nan must be positive"):
        shadelab.fresnel(ior=math.nan)
    with pytest.raises(ValueError, match="k: K = -0.5 must not be negative"):
        shadelab.fresnel(ior=1.5, k=-0.5)
    with pytest.raises(ValueError, match="material: unknown material 'unobtainium'"):
        shadelab.fresnel(material="unobtainium")
    with pytest.raises(ValueError, match="not both"):
        shadelab.fresnel(ior=1.5, material="gold")
    with pytest.raises(ValueError, match="give ior=N"):
        shadelab.fresnel()


def test_light_units_game_to_radiometric_and_photometric(cli):
    # A game colour of 1 is the exit radiance of a white Lambert surface facing the light: E = pi W/m^2.
    assert shadelab.convert_light(1.0, "game", "W/m2") == pytest.approx(math.pi, rel=1e-15)
    assert shadelab.convert_light(1.0, "game", "lux") == pytest.approx(683 * math.pi, rel=1e-15)
    rgb = shadelab.convert_light([1.0, 0.5, 0.25], "game-point", "W/sr")
    np.testing.assert_allclose(rgb, math.pi * np.array([1.0, 0.5, 0.25]), rtol=1e-15)
    for args in (("1", "game", "lux"), ("2,1,0.5", "W", "cd"), ("100", "lm", "W/sr")):
        j = cli.json("light", args[0], "--from", args[1], "--to", args[2], "--json")
        value = [float(x) for x in args[0].split(",")]
        got = shadelab.convert_light(value if len(value) == 3 else value[0], args[1], args[2])
        assert np.atleast_1d(got).tolist() == (j["value"] if len(value) == 3 else j["value"][:1])
    assert [u["name"] for u in shadelab.light_units()] == [u["name"] for u in cli.json("light", "--list", "--json")["units"]]


def test_light_bad_input_raises_the_cli_line(cli):
    # An unknown unit is named by its argument, as the CLI names its option (issue 40, finding 8).
    assert cli.error("light", "1", "--from", "game", "--to", "furlongs") == \
        "--to: unknown unit 'furlongs' (units: shadelab light --list)"
    with pytest.raises(ValueError) as e:
        shadelab.convert_light(1.0, "game", "furlongs")
    assert str(e.value) == "to_unit: unknown unit 'furlongs' (units: light_units())"
    expected = cli.error("light", "1", "--from", "lux", "--to", "cd")  # different quantities
    with pytest.raises(ValueError) as e:
        shadelab.convert_light(1.0, "lux", "cd")
    assert str(e.value) == expected
    with pytest.raises(ValueError, match="value: -1 is negative"):
        shadelab.convert_light(-1.0, "game", "lux")
    with pytest.raises(ValueError, match="value: 'nan' is not finite"):
        shadelab.convert_light(math.nan, "game", "lux")
    with pytest.raises(ValueError, match="value: expected a number or r,g,b, got 2 numbers"):
        shadelab.convert_light([1.0, 2.0], "game", "lux")
    with pytest.raises(ValueError, match=r"cone_deg: 0 is out of range \(0, 180\] degrees"):
        shadelab.convert_light(1.0, "W", "cd", cone_deg=0)
