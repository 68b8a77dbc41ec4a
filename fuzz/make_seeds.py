#!/usr/bin/python3
"""Writes the seed corpora of the text-format and hand-built harnesses into fuzz/corpus/ (committed).

Run from the repository root with /usr/bin/python3 fuzz/make_seeds.py; the EXR and KTX seeds come from
fuzz/make_seeds.cpp (target shadelab_fuzz_seeds). Every seed is small: libFuzzer mutates from them, and the
ordinary test suite replays them (fuzz.replay.*). File names the seeds use (env.hdr, tex.png, meshes/...)
are the fixture's (fuzz/fixture.h).
"""
import base64
import json
import os
import struct
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORPUS = os.path.join(ROOT, "fuzz", "corpus")
SEP = b"\n#--shadelab-fuzz-next-file--\n"  # fuzz/harness.h file_separator


def put(harness, name, data):
    d = os.path.join(CORPUS, harness)
    os.makedirs(d, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


# ---- scenes ------------------------------------------------------------------------------------------
def scenes():
    for name in sorted(os.listdir(os.path.join(ROOT, "scenes"))):
        if not name.endswith(".json") or name == "scene.schema.json":
            continue
        with open(os.path.join(ROOT, "scenes", name)) as f:
            doc = json.load(f)
        if "environment" in doc and "file" in doc["environment"]:
            doc["environment"]["file"] = "env.exr"  # the fixture's, not Blender's 1k EXR
        for t in doc.get("textures", {}).values():
            if "size" in t:
                t["size"] = min(t["size"], 32)
        doc.get("camera", {}).update({"width": 8, "height": 6})
        put("scene", name, json.dumps(doc, indent=1))
    base = {"camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "width": 4, "height": 3, "fov": 50},
            "render": {"spp": 1, "max_depth": 3, "seed": 7, "threads": 1, "rr_depth": 1}}

    def scene(name, **parts):
        doc = dict(base)
        doc.update(parts)
        put("scene", name, json.dumps(doc))

    models = {
        "lambert": {"model": "lambert", "params": {"kd": [0.5, 0.4, 0.3]}},
        "phong": {"model": "phong", "params": {"kd": 0.2, "ks": 0.5, "n": 20}},
        "blinn": {"model": "blinn-phong-modified", "params": {"kd": 0.1, "ks": 0.3, "n": 50}},
        "ct": {"model": "cook-torrance", "params": {"kd": 0.1, "ks": 1, "d": "beckmann", "g": "smith", "f": "conductor",
                                                     "m": 0.3}},
        "mct": {"model": "minimalist-cook-torrance", "params": {"kd": 0.2, "ks": 0.04, "n": 100}},
        "ward": {"model": "ward-anisotropic", "params": {"kd": 0.1, "ks": 0.4, "alpha_x": 0.2, "alpha_y": 0.05}},
        "laf": {"model": "lafortune", "params": {"kd": 0.2, "ks": 1, "lobes": "-1,-1,1,10;0.5,0.5,0.8,5"}},
        "wrap": {"model": "wrapped-diffuse", "params": {"kd": 0.6, "w": 0.3}},
        "glow": {"emission": [2, 2, 1.5]},
    }
    shapes = [
        {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "lambert"},
        {"type": "quad", "corner": [-2, 0, 2], "u": [4, 0, 0], "v": [0, 0, -4], "material": "ct"},
        {"type": "disk", "center": [1, 1, -1], "radius": 0.3, "normal": [0, -1, 0], "material": "glow"},
        {"type": "mesh", "file": "meshes/icosahedron.obj", "material": "ward",
         "transform": {"translate": [-1, 0.5, 0], "scale": 0.4, "rotate_y": 30}},
        {"type": "mesh", "file": "meshes/box.gltf", "material": "laf",
         "transform": {"translate": [1, 0.3, 0], "rotate": [1, 1, 0, 20], "scale": [0.5, 0.3, 0.4]}},
    ]
    scene("shapes.json", materials=models, shapes=shapes, environment={"uniform": 0.3})
    lights = [
        {"type": "directional", "direction": [0.3, 1, 0.2], "color": [1, 0.9, 0.8], "intensity": 2, "game": "sh"},
        {"type": "point", "position": [0, 2, 1], "color": 1, "intensity": 3},
        {"type": "spot", "position": [1, 2, 1], "direction": [0, -1, 0], "inner_angle": 10, "outer_angle": 30,
         "blender_watts": 50},
        {"type": "sphere", "center": [-1, 2, 0], "radius": 0.2, "radiance": 5},
        {"type": "hemisphere", "sky": [0.2, 0.3, 0.5], "ground": 0.05, "up": [0, 1, 0]},
    ]
    scene("lights_game.json", units="game", materials=models,
          shapes=[dict(s, material=m) for s, m in zip(shapes, ["phong", "blinn", "glow", "mct", "wrap"])],
          lights=lights)
    scene("lights_photometric.json", units="photometric", materials={"m": models["lambert"]},
          shapes=[shapes[0]], lights=[{"type": "point", "position": [0, 2, 1], "power": 800},
                                      {"type": "spot", "position": [1, 2, 1], "direction": [0, -1, 0], "power": 400}],
          environment={"sky": {"sun_direction": [0.2, 0.5, -1], "sun_angular_radius": 0.5, "sun_irradiance": 1000,
                               "zenith": 100, "horizon": [200, 190, 180], "ground": 20}})
    scene("textures.json",
          textures={"wood": {"file": "tex.png"}, "gl": {"file": "tex.png", "data": True},
                    "chk": {"procedural": "checker", "size": 16, "squares": 4, "color_a": 0.9, "color_b": [0.1, 0.2, 0.3]},
                    "asd": {"procedural": "asphalt-diffuse", "size": 16, "seed": 3, "albedo": 0.1},
                    "asg": {"procedural": "asphalt-gloss", "size": 16, "seed": 3, "wet_fraction": 0.5},
                    "nrm": {"file": "env.hdr", "data": True}},
          materials={"a": {"model": "cook-torrance", "params": {"kd": 0.1, "ks": 1, "d": "blinn-phong", "g": "kelemen",
                                                                "f": "schlick", "f0": 0.04, "n": 4},
                           "textures": {"kd": "asd", "gloss": "asg", "normal": "nrm"}, "gloss_range": [2, 4096],
                           "uv_scale": [3, 2]},
                     "b": {"model": "lambert", "textures": {"kd": "wood"}, "uv_scale": 2},
                     "c": {"model": "cook-torrance", "textures": {"ks": "gl", "kd": "chk"}}},
          shapes=[dict(shapes[0], material="a"), dict(shapes[1], material="b"), dict(shapes[4], material="c")],
          environment={"file": "env.hdr", "rotation": 45, "scale": 2})
    scene("env_exr.json", materials={"m": models["ct"]}, shapes=[dict(shapes[0], material="m")],
          environment={"file": "env.exr"})
    scene("env_png.json", units="photometric", materials={"m": models["lambert"]}, shapes=[dict(shapes[0], material="m")],
          environment={"file": "env.png", "scale": 0.5})
    put("scene", "minimal.json", "{}")
    # measured names a data file relative to the scene (a fixture file that is no MERL file: refused by its size
    # before it is read, as any file a mutated scene names)
    scene("measured.json", materials={"m": {"model": "measured", "params": {"file": "env.hdr"}}},
          shapes=[dict(shapes[0], material="m")])


# ---- OBJ ---------------------------------------------------------------------------------------------
def obj():
    with open(os.path.join(ROOT, "scenes", "meshes", "icosahedron.obj"), "rb") as f:
        put("obj", "icosahedron.obj", f.read())
    quad = ("mtllib mesh.mtl\no quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "vn 0 0 1\nusemtl red\nf 1/1/1 2/2/1 3/3/1 4/4/1\n")
    mtl = "newmtl red\nKd 0.8 0.1 0.1\nKs 0.2 0.2 0.2\nNs 50\nmap_Kd tex.png\n"
    put("obj", "quad_mtllib.obj", quad.encode() + SEP + mtl.encode())
    put("obj", "negative_indices.obj",
        "g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\ng b\nv 0 0 1\nv 1 0 1\nv 0 1 1\nvn 0 0 1\nf -3//-1 -2//-1 -1//-1\n")
    put("obj", "pentagon_uv.obj",
        "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 1\nvt 0 1\nf 1/1 2/2 3/3 4/4 5/5\n")


# ---- glTF / GLB --------------------------------------------------------------------------------------
def triangle_buffer():
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    normals = struct.pack("<9f", 0, 0, 1, 0, 0, 1, 0, 0, 1)
    uvs = struct.pack("<6H", 0, 0, 65535, 0, 0, 65535)
    indices = struct.pack("<3B", 0, 1, 2) + b"\0"
    return positions + normals + uvs + indices


def triangle_gltf(uri):
    buf = triangle_buffer()
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"children": [1, 2], "translation": [0, 1, 0], "rotation": [0, 0.3826834, 0, 0.9238795],
                   "scale": [1, 2, 1]},
                  {"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 2, 0, 0, 1]},
                  {"mesh": 0, "scale": [-1, 1, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "mode": 4}]}],
        "buffers": [dict({"byteLength": len(buf)}, **({"uri": uri} if uri is not None else {}))],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 72, "byteLength": 12},
                        {"buffer": 0, "byteOffset": 84, "byteLength": 3}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0],
                       "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "normalized": True, "count": 3, "type": "VEC2"},
                      {"bufferView": 3, "componentType": 5121, "count": 3, "type": "SCALAR"}],
    }


def glb(doc, binary):
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<I4s", len(js), b"JSON") + js
    if binary:
        chunks += struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def gltf():
    with open(os.path.join(ROOT, "scenes", "meshes", "box.gltf"), "rb") as f:
        put("gltf", "box.gltf", f.read())
    buf = triangle_buffer()
    embedded = "data:application/octet-stream;base64," + base64.b64encode(buf).decode()
    put("gltf", "triangle_embedded.gltf", json.dumps(triangle_gltf(embedded)))
    put("gltf", "triangle_external.gltf", json.dumps(triangle_gltf("buffer.bin")).encode() + SEP + buf)
    doc = triangle_gltf(embedded)
    del doc["meshes"][0]["primitives"][0]["indices"]
    doc["accessors"][0]["count"] = 3
    doc["scene"] = 0
    put("gltf", "no_indices_no_scene.gltf", json.dumps({k: v for k, v in doc.items() if k not in ("scene", "scenes")}))
    bin_doc = triangle_gltf(None)
    put("glb", "triangle.glb", glb(bin_doc, buf))
    put("glb", "triangle_external.glb", glb(triangle_gltf("buffer.bin"), b"") + SEP + buf)
    with open(os.path.join(ROOT, "scenes", "meshes", "box.gltf")) as f:
        box = json.load(f)
    uri = box["buffers"][0].get("uri", "")
    if uri.startswith("data:"):
        data = base64.b64decode(uri.split(",", 1)[1])
        del box["buffers"][0]["uri"]
        put("glb", "box.glb", glb(box, data))


# ---- HDR ---------------------------------------------------------------------------------------------
def rgbe(r, g, b):
    import math
    v = max(r, g, b)
    if v < 1e-32:
        return bytes(4)
    m, e = math.frexp(v)
    s = m * 256.0 / v
    return bytes([int(r * s), int(g * s), int(b * s), e + 128])


def hdr():
    w, h = 8, 4
    pix = [[rgbe(0.1 * x + 0.05, 0.2 * y + 0.1, 0.5) for x in range(w)] for y in range(h)]
    head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1.0\n\n"
    flat = b"".join(b"".join(row) for row in pix)
    put("hdr", "flat.hdr", head + b"-Y %d +X %d\n" % (h, w) + flat)
    put("hdr", "flat_flipped.hdr", b"#?RGBE\n\n+Y %d -X %d\n" % (h, w) + flat)
    put("hdr", "rotated.hdr", head + b"+X %d -Y %d\n" % (w, h) + flat)
    # New RLE scan lines (width 8..32767): 2 2 hi lo, then each component run-length coded.
    w2 = 16
    rows = []
    for y in range(2):
        line = [rgbe(0.3, 0.2 + 0.1 * y, 0.1 * x) for x in range(w2)]
        out = bytes([2, 2, w2 >> 8, w2 & 255])
        for c in range(4):
            comp = bytes(p[c] for p in line)
            out += bytes([128 + 8, comp[0]]) + bytes([8]) + comp[8:16]  # a run of 8, then 8 literals
        rows.append(out)
    put("hdr", "rle.hdr", head + b"-Y 2 +X %d\n" % w2 + b"".join(rows))
    # The original RLE: a pixel 1 1 1 n repeats the previous pixel n times (shifted for consecutive runs).
    old = rgbe(1, 0.5, 0.25) + bytes([1, 1, 1, 7])
    put("hdr", "old_rle.hdr", b"#?RADIANCE\n\n-Y 1 +X 8\n" + old)


# ---- PNG ---------------------------------------------------------------------------------------------
def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png(w, h, depth, colour, rows, extra=b"", interlace=0):
    raw = b"".join(b"\0" + r for r in rows)
    ihdr = struct.pack(">IIBBBBB", w, h, depth, colour, 0, 0, interlace)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + extra + png_chunk(b"IDAT", zlib.compress(raw)) +
            png_chunk(b"IEND", b""))


def pngs():
    w, h = 4, 3
    put("png", "rgb8.png", png(w, h, 8, 2, [b"".join(bytes([x * 60, y * 80, 128]) for x in range(w))
                                            for y in range(h)]))
    put("png", "rgba8.png", png(w, h, 8, 6, [b"".join(bytes([x * 60, y * 80, 128, 200]) for x in range(w))
                                             for y in range(h)]))
    put("png", "grey8.png", png(w, h, 8, 0, [bytes(x * 60 + y for x in range(w)) for y in range(h)]))
    put("png", "grey_alpha8.png", png(w, h, 8, 4, [b"".join(bytes([x * 60, 255 - y]) for x in range(w))
                                                   for y in range(h)]))
    put("png", "rgb16.png", png(w, h, 16, 2, [b"".join(struct.pack(">3H", x * 9000, y * 20000, 40000) for x in range(w))
                                              for y in range(h)]))
    put("png", "grey16.png", png(w, h, 16, 0, [b"".join(struct.pack(">H", x * 9000 + y) for x in range(w))
                                               for y in range(h)], extra=png_chunk(b"gAMA", struct.pack(">I", 45455))))
    plte = png_chunk(b"PLTE", bytes([255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128]))
    trns = png_chunk(b"tRNS", bytes([255, 128]))
    put("png", "palette8.png", png(w, h, 8, 3, [bytes((x + y) % 4 for x in range(w)) for y in range(h)], extra=plte + trns))
    put("png", "palette2.png", png(w, h, 2, 3, [bytes([0b00011011]) for y in range(h)], extra=plte))
    put("png", "grey1.png", png(w, h, 1, 0, [bytes([0b10100000]) for y in range(h)]))
    # Adam7 interlaced 2 x 2 grey: passes 1 (0,0), 6 (1,0), 7 (row 1).
    raw = b"\0\x10" + b"\0\x20" + b"\0\x30\x40"
    ihdr = struct.pack(">IIBBBBB", 2, 2, 8, 0, 0, 0, 1)
    put("png", "interlaced.png", b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + png_chunk(b"IDAT", zlib.compress(raw)) +
        png_chunk(b"IEND", b""))


# ---- MERL 100 (fuzz_merl.cpp) ------------------------------------------------------------------------
def merl():
    dims = struct.pack("<3i", 90, 90, 180)
    put("merl", "empty.binary", b"")
    put("merl", "header_only.binary", dims)
    put("merl", "short_header.binary", dims[:7])
    put("merl", "wrong_dims.binary", struct.pack("<3i", 90, 90, 360) + struct.pack("<4d", 1, 2, 3, 4))
    put("merl", "truncated.binary", dims + struct.pack("<8d", 0.5, -1, 0, 1e300, 2, 3, 4, 5))
    # "MERLFULL" + a 4-byte offset: values written into a full-size file at that byte offset of its planes
    put("merl", "full_zero.binary", b"MERLFULL" + struct.pack("<I", 0))
    put("merl", "full_values.binary", b"MERLFULL" + struct.pack("<I", 8 * 1458000) + struct.pack("<4d", 0.25, -1, 1e3, 7))
    put("merl", "full_nan.binary", b"MERLFULL" + struct.pack("<I", 8 * (2 * 1458000 + 16200 + 181)) +
        struct.pack("<2d", 1.0, float("nan")))
    put("merl", "full_inf_straddling.binary", b"MERLFULL" + struct.pack("<I", 8 * 1000 + 3) + struct.pack("<d", float("inf")))


# ---- CLI ---------------------------------------------------------------------------------------------
def cli():
    lines = [
        "render small.json --spp 2 --out r.exr",
        "render small.json --mode game --ambient irradiance --out g.exr --png g.png --json",
        "render small.json --seed 18446744073709551615 --threads 0 --max-depth 3 --aov --filmic --exposure 1",
        "render small.json --mode game --sh-lights --no-shadows --no-specular-ambient --drop-pi --out x.exr",
        "render --sampling light --no-png",
        "zoo --n 0.5 --n 10000 --json",
        "brdf list --json",
        "brdf eval blinn-phong --param n=64 --param kd=0 --wi 0.3,0,1 --wo -0.3,0,1 --json",
        "brdf eval lafortune --param lobes=-1,-1,1,10;0.5,0.5,0.8,5 --wi 0,0,1 --wo 0.1,0,1",
        "brdf albedo phong --param kd=0 --param ks=1 --param n=100 --theta 0 --theta 60",
        "brdf check ward-anisotropic --param alpha_x=0.3 --param alpha_y=0.05",
        "fresnel --ior 1.5 --theta 60",
        "fresnel --ior 0.2,3.1 --theta 10 --json",
        "fresnel --material gold --theta 0 --json",
        "fresnel --list",
        "light 1 --from game --to lux",
        "light 1,0,0 --from W/m2 --to lux --json",
        "light --list",
        "bake irradiance env.hdr --size 8 --units game --out irradiance.exr",
        "bake sh env.exr --json --window hanning --light 0,1,0:2 --light-normalization delta",
        "bake sh env.png --out sh.json --units radiometric",
        "bake specular env.hdr --size 8 --mips 3 --gloss-scale 8 --gloss-bias 1 --out specular.ktx --no-exr-faces",
        "bake convert cross.exr --out c.ktx",
        "bake convert env.hdr --out c.png --layout vcross --size 4 --input-size 8",
        "compare env.exr env.hdr --heatmap diff.png --json --heatmap-metric relative --epsilon 0.01",
        "compare env.png env.exr --side-by-side s.png --exposure 1 --scale 0.5 --ignore-alpha",
        "report small.json --out report --spp 1 --width 16",
        "plot lobe phong blinn-phong --theta-in 45 --out lobe.svg --log --cos --csv lobe.csv",
        "plot albedo phong --param phong:n=10 --theta 0 --theta 45 --out a.png --size 200x100",
        "plot fv --f0 0.04 --f0 1 --max-angle 80 --samples 10 --linear --out fv.svg",
        "plot zoo --n-min 1 --n-max 1000 --row phong --relative --out zoo.svg",
        "sheet phong-modified --vary n=10,100,1000 --out sheet.png --cell 16 --spp 1",
        "sheet lambert ward --hdri env.hdr --hdri-rotation 90 --light none --out s.png --exr s.exr",
        "--help",
        "render --help",
        "--version",
        # later commands and options (2026-12-06), after the first 36 so that those keep their names
        "ibl-error env.hdr --out e --roughness 0.5 --bins 2 --size 16 --spp 1 --correction filtered --taps 8",
        "render small.json --mode game --ggx-specular split-sum --split-sum-lookup filtered --split-sum-taps 4",
        "bake dfg --size 8 --multiscatter --out d.exr --json",
        "bake specular env.hdr --lobe ggx --size 8 --levels 3 --out s.ktx2",
        "bake ibl env.hdr --out-dir ibl --container dds",
    ]
    for i, line in enumerate(lines):
        put("cli", "%02d_%s" % (i, line.split()[0].strip("-")), "\0".join(line.split()))


# ---- dictionaries (libFuzzer -dict) ------------------------------------------------------------------
def dicts():
    import re
    d = os.path.join(ROOT, "fuzz", "dict")
    os.makedirs(d, exist_ok=True)

    def escape(c):
        if c in '\\"':
            return "\\" + c
        return c if " " <= c <= "~" else "\\x%02x" % ord(c)

    def write(name, words):
        with open(os.path.join(d, name + ".dict"), "w") as f:
            f.write("# libFuzzer dictionary, written by fuzz/make_seeds.py\n")
            for i, w in enumerate(sorted(set(words))):
                f.write('w%d="%s"\n' % (i, "".join(escape(c) for c in w)))

    with open(os.path.join(ROOT, "scenes", "scene.schema.json")) as f:
        schema = json.load(f)
    words = set()

    def walk(node):
        if isinstance(node, dict):
            for k, v in node.items():
                if k == "properties" and isinstance(v, dict):
                    words.update('"%s"' % key for key in v)
                if k in ("enum", "const"):
                    for e in (v if isinstance(v, list) else [v]):
                        if isinstance(e, str):
                            words.add('"%s"' % e)
                walk(v)
        elif isinstance(node, list):
            for v in node:
                walk(v)

    walk(schema)
    write("scene", list(words) + ["1e308", "-0", "1e-300", "[0, 0, 0]", "NaN", "null", "true", "{}", "[]"])
    # The scene-dict converter's tree (fuzz_scene_dict.cpp): the scene's words and the special strings.
    write("scene_dict", list(words) + ["1e308", "-0", "[0, 0, 0]", "null", "true", "{}", "[]", "\"@huge:", "\"@huge:100000000\"",
                                       "\"@other:complex\"", "\"@bigint\"", "\"@nan\"", "\"@inf\""])
    gltf_words = ["asset", "version", "2.0", "scene", "scenes", "nodes", "children", "mesh", "meshes", "primitives",
                  "attributes", "POSITION", "NORMAL", "TEXCOORD_0", "indices", "mode", "accessors", "bufferView",
                  "byteOffset", "byteLength", "byteStride", "componentType", "count", "type", "SCALAR", "VEC2", "VEC3",
                  "VEC4", "MAT4", "normalized", "sparse", "buffers", "bufferViews", "uri", "buffer.bin", "matrix",
                  "translation", "rotation", "scale", "extensionsRequired", "extensionsUsed", "extras", "images",
                  "textures", "materials", "5120", "5121", "5122", "5123", "5125", "5126", "data:application/octet-stream;base64,"]
    write("gltf", ['"%s"' % w for w in gltf_words])
    write("glb", ['"%s"' % w for w in gltf_words] + ["glTF", "JSON", "BIN\0"])
    write("obj", ["v ", "vt ", "vn ", "f ", "o ", "g ", "s 1", "usemtl ", "mtllib ", "mtllib mesh.mtl", "newmtl ", "Kd ",
                  "map_Kd ", "/", "//", "-1", "1e38", "nan", "\\\n"])
    with open(os.path.join(ROOT, "docs", "cli.md")) as f:
        cli_text = f.read()
    options = set(re.findall(r"--[a-z][a-z0-9-]*", cli_text))
    commands = ["render", "zoo", "brdf", "list", "eval", "albedo", "check", "fresnel", "light", "bake", "irradiance",
                "sh", "specular", "convert", "compare", "report", "plot", "lobe", "fv", "sheet", "small.json",
                "env.hdr", "env.exr", "env.png", "tex.png", "cross.exr", "x.exr", "x.png", "x.ktx", "x.json",
                "ibl-error", "dfg", "ibl", "merge", "explore", "shader", "verify", "split-sum", "filtered", "lobes",
                "dominant", "mirror", "ggx", "x.ktx2", "x.dds"]
    write("cli", ["\0" + w for w in sorted(options) + commands])
    write("merl", ["MERLFULL", "Z\0\0\0", "\xb4\0\0\0", "\x00\x00\x00\x00\x00\x00\xf8\x7f",
                   "\x00\x00\x00\x00\x00\x00\xf0\x7f", "\x00\x00\x00\x00\x00\x00\xf0\xbf"])


if __name__ == "__main__":
    dicts()
    scenes()
    obj()
    gltf()
    hdr()
    pngs()
    cli()
    merl()
