# Images as float32 (H, W, 3) arrays: exact round trips, the CLI's file errors, compare's figures.
import math
import os

import numpy as np
import pytest

import shadelab


def ramp(h=24, w=40):
    y, x = np.mgrid[0:h, 0:w]
    return np.stack([x / w, y / h, 0.25 + 0.5 * (x + y) / (w + h)], axis=-1).astype(np.float32) * 3.0


def test_exr_round_trip_is_exact_and_png_is_srgb(tmp_path):
    img = ramp()
    shadelab.write_image(tmp_path / "a.exr", img)
    back = shadelab.read_image(tmp_path / "a.exr")
    assert back.dtype == np.float32 and back.shape == img.shape and np.array_equal(back, img)
    back, info = shadelab.read_image(str(tmp_path / "a.exr"), info=True)
    assert info["format"] == "exr" and info["sample_type"] == "float" and info["channels"] == 3
    shadelab.write_image(tmp_path / "h.exr", img, pixel_type="half")
    np.testing.assert_allclose(shadelab.read_image(tmp_path / "h.exr"), img, rtol=1e-3)
    grey = np.linspace(0, 1, 256, dtype=np.float32).reshape(16, 16)
    shadelab.write_image(tmp_path / "g.png", grey)
    png = shadelab.read_image(tmp_path / "g.png")
    # The exact sRGB curve (IEC 61966-2-1) applied to the 8-bit codes, written here independently.
    codes = np.round(np.where(grey <= 0.0031308, 12.92 * grey, 1.055 * grey ** (1 / 2.4) - 0.055) * 255) / 255
    decoded = np.where(codes <= 0.04045, codes / 12.92, ((codes + 0.055) / 1.055) ** 2.4)
    np.testing.assert_allclose(png[..., 0], decoded, atol=1e-6)
    assert np.array_equal(png[..., 0], png[..., 2])
    shadelab.write_image(tmp_path / "r.hdr", img)
    # RGBE keeps 8 bits of mantissa under the pixel's largest channel's exponent (Ward 1991).
    err = np.abs(shadelab.read_image(tmp_path / "r.hdr") - img)
    assert np.all(err <= img.max(axis=-1, keepdims=True) / 128)


def test_read_errors_are_the_cli_lines(cli, tmp_path):
    missing = tmp_path / "missing.exr"
    truncated = tmp_path / "truncated.exr"
    shadelab.write_image(truncated, ramp())
    truncated.write_bytes(truncated.read_bytes()[:100])
    for path in (missing, truncated, tmp_path / "x.tiff"):
        expected = cli.error("compare", path, path)
        with pytest.raises(ValueError) as e:
            shadelab.read_image(path)
        assert str(e.value) == expected


def test_write_errors_and_bad_arrays_raise(tmp_path):
    with pytest.raises(ValueError, match="nope"):
        shadelab.write_image(tmp_path / "nope" / "a.exr", ramp())
    with pytest.raises(ValueError, match="x.bmp"):
        shadelab.write_image(tmp_path / "x.bmp", ramp())
    with pytest.raises(ValueError, match=r"image: expected shape \(H, W, 3\), \(H, W, 1\) or \(H, W\), got \(4, 4, 4\)"):
        shadelab.write_image(tmp_path / "a.exr", np.zeros((4, 4, 4)))
    with pytest.raises(ValueError, match=r"image: the image is empty"):
        shadelab.write_image(tmp_path / "a.exr", np.zeros((0, 4, 3)))
    with pytest.raises(ValueError, match="image: expected an image array"):
        shadelab.write_image(tmp_path / "a.exr", "not an image")
    with pytest.raises(ValueError, match="pixel_type: 'double' is not one of float32 | half"):
        shadelab.write_image(tmp_path / "a.exr", ramp(), pixel_type="double")
    assert not os.listdir(tmp_path)  # nothing half-written


def test_compare_equals_the_cli(cli, tmp_path):
    a = ramp()
    b = a * np.float32(0.9) + np.float32(0.01)
    shadelab.write_image(tmp_path / "a.exr", a)
    shadelab.write_image(tmp_path / "b.exr", b)
    j = cli.json("compare", tmp_path / "a.exr", tmp_path / "b.exr", "--json")
    d = shadelab.compare(a, b)
    for key in ("width", "height", "mse", "rmse", "relative_mse", "max_error", "max_error_channel",
                "mean_luminance_a", "mean_luminance_b", "mean_luminance_ratio", "ssim", "ssim_windows"):
        assert d[key] == j[key], key
    assert list(d["max_error_at"]) == j["max_error_at"]
    assert shadelab.compare(tmp_path / "a.exr", str(tmp_path / "b.exr"))["mse"] == j["mse"]
    # Independent: the MSE by NumPy, in double.
    assert d["mse"] == pytest.approx(np.mean((a.astype(np.float64) - b) ** 2), rel=1e-12)
    same = shadelab.compare(a, a, heatmap=True)
    assert same["mse"] == 0.0 and same["ssim"] == pytest.approx(1.0) and same["heatmap"].shape == a.shape


def test_compare_bad_input_raises():
    a = ramp()
    with pytest.raises(ValueError, match="the images must have the same size"):
        shadelab.compare(a, a[:10])
    bad = a.copy()
    bad[2, 3, 0] = math.inf
    with pytest.raises(ValueError, match="not finite|non-finite|inf"):
        shadelab.compare(bad, a)
    with pytest.raises(ValueError, match="epsilon: 0 must be a finite number > 0"):
        shadelab.compare(a, a, epsilon=0)
    with pytest.raises(ValueError, match="heatmap_metric: 'fancy' is not one of absolute | relative"):
        shadelab.compare(a, a, heatmap_metric="fancy")
