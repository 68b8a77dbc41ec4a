# Issue 40, finding 4: what the Python module does with bad or unusual input. Scene dicts go through one
# bounded converter (scene/value_tree.h): NumPy arrays stay arrays (a number's place then says "expected a
# number"), lengths are checked before any item is read, other types name their JSON pointer. Arrays of any
# layout convert; dtypes that are not real numbers are refused. Renders release the GIL and stop on Ctrl-C.
import decimal
import json
import os
import signal
import threading
import time

import numpy as np
import pytest

import shadelab


def tiny(scenes_dir, width=8, height=6):
    scene = json.loads((scenes_dir / "default.json").read_text())
    scene["camera"].update(width=width, height=height)
    scene["render"].update(spp=1)
    for t in scene.get("textures", {}).values():
        if "size" in t:
            t["size"] = 16
    return scene


def mesh_scene(scenes_dir, rotate_y):
    scene = tiny(scenes_dir)
    scene["shapes"].append({"type": "mesh", "file": str(scenes_dir / "meshes" / "icosahedron.obj"), "material": "lambert",
                            "transform": {"rotate_y": rotate_y}})
    return scene


def raises(scene, message, **kwargs):
    with pytest.raises(ValueError) as e:
        shadelab.render(scene, threads=1, **kwargs)
    assert str(e.value) == message
    return e


def test_a_numpy_array_as_a_number_names_its_pointer(scenes_dir):
    # Was: np.array([45.0]) read as -1 (PyNumber_Index on an array failed, its -1 taken as the value).
    scene = mesh_scene(scenes_dir, np.array([45.0]))
    raises(scene, "scene: /shapes/9/transform/rotate_y: expected a number, got [45.0]")
    scene["shapes"][9]["transform"]["rotate_y"] = np.array([[1, 2]])
    raises(scene, "scene: /shapes/9/transform/rotate_y: expected a number, got [[1,2]]")
    scene["shapes"][9]["transform"]["rotate_y"] = np.array([])
    raises(scene, "scene: /shapes/9/transform/rotate_y: expected a number, got []")
    # numpy.bool_ is a boolean, as True is (it was taken as the integer 1).
    scene["shapes"][9]["transform"]["rotate_y"] = np.bool_(True)
    raises(scene, "scene: /shapes/9/transform/rotate_y: expected a number, got true")


def test_numpy_scalars_and_0d_arrays_of_real_dtypes_are_numbers(scenes_dir):
    expected = shadelab.render(mesh_scene(scenes_dir, 45.0), threads=1)
    for v in (np.float64(45), np.float32(45), np.int64(45), np.uint8(45), np.array(45.0), np.array(45, np.int16), 45):
        assert np.array_equal(shadelab.render(mesh_scene(scenes_dir, v), threads=1), expected), repr(v)
    scene = tiny(scenes_dir)
    scene["camera"]["position"] = np.array(scene["camera"]["position"])  # a 1-D array is a JSON array
    assert np.array_equal(shadelab.render(scene, threads=1), shadelab.render(tiny(scenes_dir), threads=1))


@pytest.mark.parametrize("value,type_name", [
    (1 + 2j, "complex"), (np.array(1 + 2j), "ndarray (dtype complex128)"), (b"45", "bytes"),
    (bytearray(b"4"), "bytearray"), (memoryview(b"4"), "memoryview"), (decimal.Decimal("1.5"), "Decimal"),
    (np.datetime64("2020"), "datetime64 (dtype datetime64[Y])"), ({1, 2}, "set"), (object(), "object"),
    (np.array(object()), "ndarray (dtype object)")])
def test_values_that_are_not_json_name_their_pointer_and_type(scenes_dir, value, type_name):
    scene = tiny(scenes_dir)
    scene["shapes"][2]["radius"] = value
    raises(scene, f"scene: /shapes/2/radius: a value of type {type_name} is not a JSON value (numbers are int, "
                  "float or a NumPy real scalar; arrays are list, tuple, range or a NumPy array; objects are dict)")


@pytest.mark.parametrize("value,what", [
    (range(10 ** 8), "a sequence of 100000000 items"),
    (range(10 ** 30), "a sequence of more than 2^64 - 2 items"),
    (np.broadcast_to(0.0, (10 ** 8,)), "a sequence of 100000000 items"),  # 10^8 items in no memory
    ([0.0] * (40 << 20), "a sequence of 41943040 items"),
])
def test_huge_sequences_are_refused_before_any_item_is_read(scenes_dir, value, what):
    # Was: range(10**8) built 10^8 JSON values and ended the interpreter (SIGABRT, std::bad_alloc thrown
    # during unwinding). A dict is bounded as a scene file is: its JSON at most 64 MiB.
    scene = tiny(scenes_dir)
    scene["camera"]["position"] = value
    t0 = time.perf_counter()
    raises(scene, f"scene: /camera/position: {what}: the scene is more than the 64 MiB of JSON a scene file may hold")
    assert time.perf_counter() - t0 < 1.0


def test_the_bound_counts_the_whole_dict_and_long_strings(scenes_dir):
    scene = tiny(scenes_dir)
    scene["description"] = "x" * (64 << 20)
    raises(scene, "scene: /description: a string of 67108864 characters: the scene is more than the 64 MiB of JSON "
                  "a scene file may hold")
    # Values each within the bound add up: the second of two 40 MiB strings is refused.
    scene = tiny(scenes_dir)
    scene["extra"] = ["x" * (40 << 20), "y" * (40 << 20)]
    raises(scene, "scene: /extra/1: a string of 41943040 characters: the scene is more than the 64 MiB of JSON a "
                  "scene file may hold")
    # Within it, the parser speaks: an unknown key, not a size.
    scene["extra"] = [0] * 1000
    raises(scene, "scene: /extra: unknown key 'extra' (keys of a scene: $schema, description, units, camera, "
                  "render, textures, materials, shapes, lights, environment)")


def test_a_gltf_with_huge_json_arrays_is_one_error(scenes_dir, tmp_path):
    # Was: tinygltf built ~575 bytes per empty node: a file of millions aborted through std::bad_alloc.
    nodes = ",".join(["{}"] * 600_000)
    (tmp_path / "big.gltf").write_text('{"asset": {"version": "2.0"}, "nodes": [' + nodes + "]}")
    scene = tiny(scenes_dir)
    scene["shapes"].append({"type": "mesh", "file": "big.gltf", "material": "lambert"})
    t0 = time.perf_counter()
    with pytest.raises(ValueError) as e:
        shadelab.render(scene, base_dir=tmp_path)
    assert str(e.value) == (f"scene: /shapes/9/file: {tmp_path / 'big.gltf'}: the glTF JSON holds more than "
                            "1000000 values (objects, arrays and their elements), more than a mesh file may")
    assert time.perf_counter() - t0 < 1.0


ROWS = np.array([[0.1, 0.2, 1.0], [0.3, -0.1, 0.9], [0.0, 0.5, 0.7], [0.2, 0.2, 0.6]])


@pytest.mark.parametrize("name,make", [
    ("strided rows", lambda a: np.repeat(a, 2, axis=0)[::2]),
    ("negative stride", lambda a: a[::-1]),
    ("Fortran order", np.asfortranarray),
    ("column view", lambda a: np.hstack([a, a])[:, :3]),
    ("reversed columns", lambda a: a[:, ::-1][:, ::-1]),
    ("float32", lambda a: a.astype(np.float32)),
    ("float16", lambda a: a.astype(np.float16)),
    ("int64", lambda a: (a * 10).astype(np.int64)),
    ("uint8", lambda a: np.abs(a * 10).astype(np.uint8)),
    ("list", lambda a: a.tolist()),
])
def test_arrays_of_any_layout_and_real_dtype_are_read_as_their_float64_copy(name, make):
    f = shadelab.Brdf("cook-torrance")
    wo = np.array([-0.2, 0.1, 1.0])
    given = make(ROWS)
    plain = np.ascontiguousarray(np.asarray(given, dtype=np.float64))
    assert np.array_equal(f.eval(given, wo), f.eval(plain, wo)), name
    assert np.array_equal(f.eval(wo, given), f.eval(wo, plain)), name
    assert np.array_equal(f.pdf(given, wo), f.pdf(plain, wo)), name
    u = np.full((len(plain), 3), 0.25)
    for a, b in zip(f.sample(given, u), f.sample(plain, u)):
        assert np.array_equal(a, b), name
    if name == "negative stride":
        assert np.array_equal(f.eval(given, wo), f.eval(ROWS, wo)[::-1])


@pytest.mark.parametrize("value,message", [
    (ROWS.astype(bool), "wi: expected an array of numbers, got an array of dtype bool"),
    (ROWS.astype(complex), "wi: expected an array of numbers, got an array of dtype complex128"),
    (np.array([["0", "0", "1"]]), "wi: expected an array of numbers, got an array of dtype <U1"),
    ([["0", "0", "1"]], "wi: expected an array of numbers, got list (NumPy reads it as dtype <U1)"),
    (np.array([[0, 0, 1]], dtype=object), "wi: expected an array of numbers, got an array of dtype object"),
    (np.array([[0, 0, 1]], dtype="datetime64[s]"), "wi: expected an array of numbers, got an array of dtype datetime64[s]"),
    (np.ma.masked_array(ROWS, mask=ROWS < 0), "wi: a masked array (its mask would be ignored; give .filled(value) or .compressed())"),
    ([[0, 0, 1], [0, 1]], "wi: expected an array of numbers, got list"),
    (np.array(1.0), "wi: expected shape (N, 3) or (3,), got ()"),
    (b"\x00\x00\x01", "wi: expected an array of numbers, got bytes"),
])
def test_arrays_that_are_not_real_numbers_are_refused(value, message):
    # Was: strings parsed ("1" as 1), True as 1, datetimes as their counts, the mask ignored: silently wrong.
    f = shadelab.Brdf("phong")
    for call in (lambda: f.eval(value, [0, 0, 1]), lambda: f.pdf(value, [0, 0, 1])):
        with pytest.raises(ValueError) as e:
            call()
        assert str(e.value) == message
    with pytest.raises(ValueError) as e:
        f.sample(value, [0.5, 0.5, 0.5])
    assert str(e.value) == message.replace("wi", "wo", 1)


def test_images_refuse_dtypes_that_are_not_real(tmp_path):
    with pytest.raises(ValueError, match=r"^image: expected an image array of shape \(H, W, 3\), got an array of dtype bool$"):
        shadelab.write_image(tmp_path / "a.exr", np.ones((2, 2, 3), bool))
    with pytest.raises(ValueError, match=r"^image: expected an image array .* got an array of dtype <U1$"):
        shadelab.bake_sh(np.full((6, 2, 2, 3), "1"))
    img = np.arange(2 * 4 * 3, dtype=np.float64).reshape(2, 4, 3)[:, ::-1]  # negative stride
    shadelab.write_image(tmp_path / "b.exr", img)
    assert np.array_equal(shadelab.read_image(tmp_path / "b.exr"), img.astype(np.float32))


def test_renders_in_two_threads_run_at_once_and_give_the_serial_bits(scenes_dir):
    # The GIL is released while rendering (both modes): two renders in two Python threads give the bits of
    # the same renders one after the other, and while they run this thread keeps running Python code.
    scene = tiny(scenes_dir, 320, 180)
    serial = {m: shadelab.render(scene, mode=m, threads=1, spp=4) for m in ("reference", "game")}
    results = {}

    def work(mode):
        results[mode] = shadelab.render(scene, mode=mode, threads=1, spp=4)  # about 0.4 s each

    threads = [threading.Thread(target=work, args=(m,)) for m in serial]
    t0 = last = time.perf_counter()
    for t in threads:
        t.start()
    stalled = 0.0  # the time this thread spent in gaps of over 50 ms between its iterations
    while any(t.is_alive() for t in threads):
        now = time.perf_counter()
        stalled += now - last if now - last > 0.05 else 0.0
        last = now
    wall = time.perf_counter() - t0
    for t in threads:
        t.join()
    for m in serial:
        assert np.array_equal(results[m], serial[m]), m
    # With the GIL held by a render this thread would stall for all of it; load from other processes on the
    # two cores makes a few gaps of up to 0.3 s, never most of the time.
    assert stalled < 0.5 * wall, (stalled, wall)


@pytest.mark.parametrize("mode", ["reference", "game"])
def test_ctrl_c_stops_a_render_within_a_tile(scenes_dir, mode):
    # A real SIGINT 0.5 s into a render that takes a minute or more: KeyboardInterrupt within 3 s of it
    # (was: the game renderer ran to the end, the path tracer to the end of its pass, 5 s and more here).
    scene = tiny(scenes_dir, 1920, 1080)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    t0 = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            shadelab.render(scene, mode=mode, spp=256, threads=1)
    finally:
        timer.cancel()
    assert time.perf_counter() - t0 < 3.5
    # The module works on afterwards.
    assert shadelab.render(tiny(scenes_dir), mode=mode).shape == (6, 8, 3)


def test_light_messages_name_the_argument():
    # Was "light: unknown unit 'x'" (the CLI command's name) for either argument, and inf for an overflow.
    with pytest.raises(ValueError) as e:
        shadelab.convert_light(1, "x", "lux")
    assert str(e.value) == "from_unit: unknown unit 'x' (units: light_units())"
    with pytest.raises(ValueError) as e:
        shadelab.convert_light(1, "game", "luxx")
    assert str(e.value) == "to_unit: unknown unit 'luxx' (units: light_units())"
    with pytest.raises(ValueError) as e:
        shadelab.convert_light(1e308, "game", "W/m2")
    assert str(e.value) == ("value: 1e+308 game overflows when converted to W/m2 (the result exceeds the largest "
                            "double, about 1.8e308)")
    assert shadelab.convert_light(1e300, "game", "W/m2") == pytest.approx(1e300 * np.pi)
