# render(): scene files and dicts, the same image as the CLI, any thread count, the white furnace, and
# scene errors with the parser's JSON pointers.
import json
import math

import numpy as np
import pytest

import shadelab


def small_default(scenes_dir, width=48, height=27, spp=2):
    scene = json.loads((scenes_dir / "default.json").read_text())
    scene["camera"].update(width=width, height=height)
    scene["render"].update(spp=spp)
    for t in scene.get("textures", {}).values():
        if "size" in t:
            t["size"] = 64  # smaller procedural textures keep the test quick
    return scene


def test_render_a_dict_equals_the_cli_and_is_the_same_for_any_thread_count(cli, scenes_dir, tmp_path):
    scene = small_default(scenes_dir)
    (tmp_path / "s.json").write_text(json.dumps(scene))
    img = shadelab.render(scene, seed=7, threads=1)
    assert img.shape == (27, 48, 3) and img.dtype == np.float32
    assert np.all(np.isfinite(img)) and img.mean() > 0
    assert np.array_equal(shadelab.render(scene, seed=7, threads=2), img)
    assert np.array_equal(shadelab.render(tmp_path / "s.json", seed=7), img)
    cli("render", tmp_path / "s.json", "--seed", "7", "--out", tmp_path / "cli.exr", "--no-png")
    assert np.array_equal(shadelab.read_image(tmp_path / "cli.exr"), img)
    assert not np.array_equal(shadelab.render(scene, seed=8), img)


def test_white_furnace(scenes_dir):
    scene = json.loads((scenes_dir / "furnace.json").read_text())
    scene["camera"].update(width=24, height=24)
    img = shadelab.render(scene, spp=16)
    # The white sphere disappears: radiance 1 everywhere, up to Monte Carlo noise. The three channels carry
    # the same samples (a grey scene), so the independent estimates are the pixels, not the 3 x 576 values.
    g = img[..., 1]
    assert abs(g.mean() - 1.0) < 4 * g.std() / math.sqrt(g.size) + 1e-6
    np.testing.assert_allclose(img.mean(axis=(0, 1)), 1.0, atol=0.02)


def test_game_mode_and_aovs(scenes_dir):
    scene = small_default(scenes_dir, width=16, height=9, spp=1)
    game = shadelab.render(scene, mode="game")
    assert game.shape == (9, 16, 3) and np.all(np.isfinite(game))
    out = shadelab.render(scene, aov=True)
    assert set(out) >= {"beauty", "albedo", "normal", "depth", "spp", "rays"}
    assert out["spp"] == 1 and out["normal"].shape == (9, 16, 3)


def test_scene_errors_name_the_field(cli, scenes_dir, tmp_path):
    scene = small_default(scenes_dir)
    scene["shapes"][1]["radius"] = -2
    (tmp_path / "bad.json").write_text(json.dumps(scene))
    cli_line = cli.error("render", tmp_path / "bad.json", "--out", tmp_path / "x.exr")
    with pytest.raises(ValueError) as e:
        shadelab.render(tmp_path / "bad.json")
    assert str(e.value) == cli_line
    with pytest.raises(ValueError) as e:
        shadelab.render(scene)
    assert str(e.value) == cli_line.replace(str(tmp_path / "bad.json"), "scene")
    assert "/shapes/1/radius" in str(e.value)
    scene["shapes"][1]["radius"] = math.nan
    with pytest.raises(ValueError, match="scene: /shapes/1/radius: nan is not a finite number"):
        shadelab.render(scene)
    with pytest.raises(ValueError, match=r"scene: /: the key 1 is not a string"):
        shadelab.render({1: 2})
    loop = []
    loop.append(loop)
    with pytest.raises(ValueError, match="nested deeper than"):
        shadelab.render({"shapes": loop})
    missing = tmp_path / "missing.json"
    with pytest.raises(ValueError) as e:
        shadelab.render(missing)
    assert str(e.value) == cli.error("render", missing, "--out", tmp_path / "x.exr")


def test_render_arguments_are_validated(scenes_dir):
    scene = small_default(scenes_dir, 8, 8, 1)
    for kwargs, message in (({"spp": 0}, "spp: 0 must be >= 1"), ({"threads": -1}, "threads: -1 must be >= 0"),
                            ({"max_depth": 0}, "max_depth: 0 must be >= 1"), ({"seed": -3}, "seed: -3 must be >= 0"),
                            ({"seed": 2 ** 64}, "seed: 18446744073709551616 is larger than 2^64 - 1"),
                            ({"mode": "fast"}, "mode: 'fast' is not one of reference | game"),
                            ({"sampling": "x"}, "sampling: 'x' is not one of mis | brdf | light"),
                            ({"spp": 1.5}, "spp: expected an integer")):
        with pytest.raises(ValueError) as e:
            shadelab.render(scene, **kwargs)
        assert str(e.value) == message
    with pytest.raises(ValueError, match="scene: expected a path, a dict"):
        shadelab.render(42)
