#!/usr/bin/python3
"""Writes scenes/meshes/gltf_extensions/: a glTF 2.0 file of four UV spheres whose materials use the PBR
extensions shadelab's importer reads (docs/scene-format.md, "glTF materials"), its buffer and its PNG textures.
Everything is made here from its own numbers (no download): geometry, texels, factors.

    /usr/bin/python3 scripts/make_gltf_extensions_scene.py [OUT_DIR]

The spheres, left to right (x = -2.25, -0.75, 0.75, 2.25; radius 0.6; centre y = 0.6):
  0 clearcoat   red dielectric under KHR_materials_clearcoat: clearcoatTexture (R, stripes) with
                KHR_texture_transform (scale [4, 1]), clearcoatRoughnessTexture (G)
  1 sheen       dark blue rough dielectric with KHR_materials_sheen: sheenColorTexture (sRGB),
                sheenRoughnessTexture (alpha)
  2 specular    green dielectric with KHR_materials_ior 1.8 and KHR_materials_specular: specularTexture (alpha),
                specularColorTexture (sRGB)
  3 anisotropy  rough metal with KHR_materials_anisotropy: anisotropyTexture (RG direction, B strength), rotation 0.5

The file is deterministic: the same bytes on every run (scripts and tests compare them).
scenes/gltf_extensions.json places it under Blender's forest HDRI; gltf_materials_test.cpp checks that each
sphere's material gets the parameters and textures written here (the numbers below are repeated there).
"""
import json
import math
import os
import struct
import sys
import zlib

LAT = 24  # latitude bands
LON = 48  # longitude segments


def sphere():
    """Unit UV sphere: positions, normals, uvs (u = longitude / 2 pi, v = colatitude / pi: v = 0 at the top,
    as glTF's uvs start at the image's top-left), and counter-clockwise triangles seen from outside."""
    positions, normals, uvs, indices = [], [], [], []
    for i in range(LAT + 1):
        theta = math.pi * i / LAT
        for j in range(LON + 1):
            phi = 2.0 * math.pi * j / LON
            # +Y up; u grows with phi, turning from +Z toward +X (right-handed about +Y seen from above is
            # +Z -> +X), so dp/du points east on the sphere's surface seen from outside.
            n = (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))
            positions.append(n)
            normals.append(n)
            uvs.append((j / LON, i / LAT))
    for i in range(LAT):
        for j in range(LON):
            a = i * (LON + 1) + j
            b = a + LON + 1
            # a (top-left), b (below it), a + 1, b + 1; outward winding
            if i > 0:
                indices += [a, b, a + 1]
            if i < LAT - 1:
                indices += [a + 1, b, b + 1]
    return positions, normals, uvs, indices


def png(width, height, pixels, channels):
    """An 8-bit PNG (colour type 2 RGB or 6 RGBA) of `pixels` (rows of tuples of codes), no filtering."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in pixels)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    colour_type = 2 if channels == 3 else 6
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


# The textures: constant within each of two halves (u < 0.5 and u >= 0.5) or stripes, so that a test can name the
# texel a uv reads. 8 x 8 texels each.
N = 8


def halves(left, right):
    return [[left if x < N // 2 else right for x in range(N)] for _ in range(N)]


TEXTURES = {
    # R: clearcoat weight (stripes along u: 255 and 64); with the transform's scale [4, 1] they repeat 4 times.
    "clearcoat.png": (3, [[(255, 0, 0) if x % 2 == 0 else (64, 0, 0) for x in range(N)] for _ in range(N)]),
    # G: clearcoat roughness (0.25 left, 1.0 right), R and B unused (the same file could hold both: here it does not).
    "clearcoat_roughness.png": (3, halves((0, 64, 0), (0, 255, 0))),
    # sRGB: sheen colour (white left, pink right); alpha: sheen roughness (0.5 left, 1.0 right) in an RGBA file.
    "sheen_color.png": (3, halves((255, 255, 255), (255, 160, 200))),
    "sheen_roughness.png": (4, halves((0, 0, 0, 128), (0, 0, 0, 255))),
    # alpha: specular weight (1 left, 0.25 right); sRGB: specular colour (white left, gold right).
    "specular.png": (4, halves((255, 255, 255, 255), (255, 255, 255, 64))),
    "specular_color.png": (3, halves((255, 255, 255), (255, 200, 100))),
    # anisotropy: direction (R, G) in [-1, 1] and strength B: along the tangent (1, 0) at full strength left,
    # along the bitangent (0, 1) at half strength right.
    "anisotropy.png": (3, halves((255, 128, 255), (128, 255, 128))),
}


def material(name, pbr, extensions):
    m = {"name": name, "pbrMetallicRoughness": pbr}
    if extensions:
        m["extensions"] = extensions
    return m


def info(index, transform=None):
    i = {"index": index}
    if transform is not None:
        i["extensions"] = {"KHR_texture_transform": transform}
    return i


def gltf_document(buffer_length, counts):
    names = list(TEXTURES)
    tex = {name: i for i, name in enumerate(names)}
    materials = [
        material("clearcoat", {"baseColorFactor": [0.6, 0.05, 0.03, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5},
                 {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.4,
                                              "clearcoatTexture": info(tex["clearcoat.png"], {"scale": [4, 1]}),
                                              "clearcoatRoughnessTexture": info(tex["clearcoat_roughness.png"])}}),
        material("sheen", {"baseColorFactor": [0.05, 0.05, 0.25, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.8},
                 {"KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.8, 0.7], "sheenRoughnessFactor": 0.6,
                                          "sheenColorTexture": info(tex["sheen_color.png"]),
                                          "sheenRoughnessTexture": info(tex["sheen_roughness.png"])}}),
        material("specular", {"baseColorFactor": [0.05, 0.3, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.3},
                 {"KHR_materials_ior": {"ior": 1.8},
                  "KHR_materials_specular": {"specularFactor": 0.8, "specularColorFactor": [1.0, 0.9, 0.8],
                                             "specularTexture": info(tex["specular.png"]),
                                             "specularColorTexture": info(tex["specular_color.png"])}}),
        material("anisotropy", {"baseColorFactor": [0.95, 0.93, 0.88, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.35},
                 {"KHR_materials_anisotropy": {"anisotropyStrength": 0.8, "anisotropyRotation": 0.5,
                                               "anisotropyTexture": info(tex["anisotropy.png"])}}),
    ]
    npos, nidx = counts
    return {
        "asset": {"version": "2.0", "generator": "shadelab scripts/make_gltf_extensions_scene.py"},
        "extensionsUsed": ["KHR_materials_anisotropy", "KHR_materials_clearcoat", "KHR_materials_ior",
                           "KHR_materials_sheen", "KHR_materials_specular", "KHR_texture_transform"],
        "extensionsRequired": ["KHR_texture_transform"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [{"name": m["name"], "mesh": i, "translation": [-2.25 + 1.5 * i, 0.6, 0.0], "scale": [0.6, 0.6, 0.6]}
                  for i, m in enumerate(materials)],
        "meshes": [{"name": m["name"], "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                        "indices": 3, "material": i}]}
                   for i, m in enumerate(materials)],
        "materials": materials,
        "textures": [{"source": i} for i in range(len(names))],
        "images": [{"uri": name} for name in names],
        "buffers": [{"uri": "spheres.bin", "byteLength": buffer_length}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": npos * 12, "target": 34962},
            {"buffer": 0, "byteOffset": npos * 12, "byteLength": npos * 12, "target": 34962},
            {"buffer": 0, "byteOffset": npos * 24, "byteLength": npos * 8, "target": 34962},
            {"buffer": 0, "byteOffset": npos * 32, "byteLength": nidx * 2, "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": npos, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
            {"bufferView": 1, "componentType": 5126, "count": npos, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": npos, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": nidx, "type": "SCALAR"},
        ],
    }


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "scenes", "meshes", "gltf_extensions")
    os.makedirs(out, exist_ok=True)
    positions, normals, uvs, indices = sphere()
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    data += b"".join(struct.pack("<3f", *n) for n in normals)
    data += b"".join(struct.pack("<2f", *t) for t in uvs)
    data += struct.pack("<%dH" % len(indices), *indices)
    data += b"\x00" * (-len(data) % 4)
    with open(os.path.join(out, "spheres.bin"), "wb") as f:
        f.write(data)
    for name, (channels, pixels) in TEXTURES.items():
        with open(os.path.join(out, name), "wb") as f:
            f.write(png(N, N, pixels, channels))
    doc = gltf_document(len(data), (len(positions), len(indices)))
    with open(os.path.join(out, "spheres.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print("wrote", out)


if __name__ == "__main__":
    main()
