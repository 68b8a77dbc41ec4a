#!/usr/bin/python3
"""Writes the test files of `shadelab convert gltf` (docs/conversions.md) into OUT_DIR (default: the current folder):

  spec_gloss.gltf           one triangle per material, its buffer embedded as a data URI; materials:
                              0 gold      KHR_materials_pbrSpecularGlossiness, the extension README's gold example:
                                          diffuse 0 (alpha 1), specular (1, 0.766, 0.336), glossiness 0.9
                              1 plastic   diffuse (0.6, 0.4, 0.2, 0.5), specular 0.04, glossiness 0.5
                              2 tinted    diffuse (0.3, 0.5, 0.7), specular (0.2, 0.3, 0.1), glossiness 0.3
                              3 defaults  the extension with no factors (diffuse 1, specular 1, glossiness 1)
                              4 plain     metallic-roughness only (left as it is)
                            extensionsUsed and extensionsRequired name KHR_materials_pbrSpecularGlossiness.
  spec_gloss.glb            the same glTF as a GLB (JSON chunk + BIN chunk)
  spec_gloss_textured.gltf  textured spec-gloss (8 x 8 PNG files beside it, every texel distinct):
                              0 textured  diffuseTexture sg_diffuse.png and specularGlossinessTexture sg_specgloss.png,
                                          both with texCoord 0 and the same KHR_texture_transform and sampler;
                                          factors diffuse (0.9, 1, 1, 1), specular (1, 1, 1), glossiness 0.95.
                                          Rows 0-1: metals (black diffuse; gold, silver, copper, iron specular),
                                          rows 2-5: plastics (specular 0.04, coloured diffuse), rows 6-7: a tinted
                                          specular (0.2, 0.3, 0.1) over a mid diffuse; glossiness rises along x.
                                          Diffuse alpha 128 in column 7, 255 elsewhere.
                              1 diffuse   diffuseTexture sg_diffuse.png only; specular 0.04, glossiness 0.6
                              2 plain     metallic-roughness only (left as it is)
  spec_gloss_textured.glb   the same with the two PNGs in its BIN chunk
  sg_diffuse.png, sg_specgloss.png   the 8 x 8 RGBA textures

    /usr/bin/python3 scripts/make_spec_gloss_gltf.py [-h] [OUT_DIR]

Everything is made here from its own numbers; the files are the same bytes on every run.
"""
import argparse
import base64
import json
import os
import struct
import zlib

MATERIALS = [
    ("gold", {"diffuseFactor": [0.0, 0.0, 0.0, 1.0], "specularFactor": [1.0, 0.766, 0.336], "glossinessFactor": 0.9}),
    ("plastic", {"diffuseFactor": [0.6, 0.4, 0.2, 0.5], "specularFactor": [0.04, 0.04, 0.04], "glossinessFactor": 0.5}),
    ("tinted", {"diffuseFactor": [0.3, 0.5, 0.7, 1.0], "specularFactor": [0.2, 0.3, 0.1], "glossinessFactor": 0.3}),
    ("defaults", {}),
]


def geometry():
    """One triangle: three float32 positions (36 bytes) and three uint16 indices (6 bytes, padded to 8)."""
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    indices = struct.pack("<3H", 0, 1, 2) + b"\x00\x00"
    return positions + indices


def png_rgba(width, height, pixels):
    """An 8-bit RGBA PNG (colour type 6) of `pixels`, rows of (r, g, b, a) tuples, top row first."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in pixels)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def srgb8(linear):
    """The 8-bit sRGB code of a linear value (IEC 61966-2-1)."""
    v = 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055
    return int(round(min(max(v, 0.0), 1.0) * 255))


METALS = [(1.0, 0.766, 0.336), (0.972, 0.960, 0.915), (0.955, 0.638, 0.538), (0.56, 0.57, 0.58)]  # the README's gold; silver, copper, iron
SIZE = 8


def textures():
    """The 8 x 8 diffuse (RGBA, sRGB) and specular-glossiness (sRGB RGB, linear A) texels, row y, column x."""
    diffuse, specgloss = [], []
    for y in range(SIZE):
        drow, srow = [], []
        for x in range(SIZE):
            gloss = 40 + 30 * x + y  # codes 40 .. 257 - 8: distinct per texel, glossiness 0.16 .. 0.98
            if y < 2:  # metals: black diffuse
                d = (0.0, 0.0, 0.0)
                spec = METALS[(x + 4 * y) % 4]
            elif y < 6:  # plastics
                d = (0.1 + 0.1 * x, 0.8 - 0.1 * (y - 2), 0.05 + 0.1 * (y - 2))
                spec = (0.04, 0.04, 0.04)
            else:  # a tinted specular over a mid diffuse
                d = (0.3 + 0.05 * x, 0.5, 0.7 - 0.05 * (y - 6))
                spec = (0.2, 0.3, 0.1)
            alpha = 128 if x == SIZE - 1 else 255
            drow.append(tuple(srgb8(c) for c in d) + (alpha,))
            srow.append(tuple(srgb8(c) for c in spec) + (min(gloss, 255),))
        diffuse.append(drow)
        specgloss.append(srow)
    return diffuse, specgloss


def document(buffer_uri, buffer_length):
    materials = [{"name": name, "extensions": {"KHR_materials_pbrSpecularGlossiness": dict(ext)}}
                 for name, ext in MATERIALS]
    materials.append({"name": "plain", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0],
                                                                "metallicFactor": 0.0, "roughnessFactor": 0.5}})
    doc = {
        "asset": {"version": "2.0", "generator": "shadelab scripts/make_spec_gloss_gltf.py"},
        "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
        "extensionsRequired": ["KHR_materials_pbrSpecularGlossiness"],
        "scene": 0,
        "scenes": [{"nodes": list(range(len(materials)))}],
        "nodes": [{"mesh": i, "translation": [1.5 * i, 0, 0]} for i in range(len(materials))],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": i}]}
                   for i in range(len(materials))],
        "materials": materials,
        "buffers": [{"byteLength": buffer_length}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36, "target": 34962},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 6, "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }
    if buffer_uri is not None:
        doc["buffers"][0]["uri"] = buffer_uri
    return doc


def textured_document(buffer_uri, buffer_length, images):
    """The textured file: `images` are the two image entries (uris or bufferViews)."""
    transform = {"offset": [0.25, 0.0], "scale": [2.0, 2.0]}
    info = {"texCoord": 0, "extensions": {"KHR_texture_transform": transform}}
    materials = [
        {"name": "textured", "extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "diffuseFactor": [0.9, 1.0, 1.0, 1.0], "specularFactor": [1.0, 1.0, 1.0], "glossinessFactor": 0.95,
            "diffuseTexture": dict(info, index=0), "specularGlossinessTexture": dict(info, index=1)}}},
        {"name": "diffuse", "extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "specularFactor": [0.04, 0.04, 0.04], "glossinessFactor": 0.6, "diffuseTexture": {"index": 0}}}},
        {"name": "plain", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0,
                                                   "roughnessFactor": 0.5}},
    ]
    doc = document(buffer_uri, buffer_length)
    doc["materials"] = materials
    doc["scenes"] = [{"nodes": [0, 1, 2]}]
    doc["nodes"] = doc["nodes"][:3]
    doc["meshes"] = doc["meshes"][:3]
    doc["extensionsUsed"] = ["KHR_materials_pbrSpecularGlossiness", "KHR_texture_transform"]
    doc["samplers"] = [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}]
    doc["images"] = images
    doc["textures"] = [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}]
    return doc


def glb(doc, binary):
    text = json.dumps(doc, indent=1).encode("utf-8")
    text += b" " * (-len(text) % 4)
    binary += b"\x00" * (-len(binary) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def main():
    parser = argparse.ArgumentParser(description="Writes the test files of `shadelab convert gltf` (docs/conversions.md).")
    parser.add_argument("out_dir", nargs="?", default=".", metavar="OUT_DIR", help="the folder to write into (made if absent)")
    out = parser.parse_args().out_dir
    os.makedirs(out, exist_ok=True)
    data = geometry()
    uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")
    with open(os.path.join(out, "spec_gloss.gltf"), "w") as f:
        json.dump(document(uri, len(data)), f, indent=1)
    with open(os.path.join(out, "spec_gloss.glb"), "wb") as f:
        f.write(glb(document(None, len(data)), data))
    diffuse, specgloss = textures()
    pngs = [png_rgba(SIZE, SIZE, diffuse), png_rgba(SIZE, SIZE, specgloss)]
    for name, png in zip(("sg_diffuse.png", "sg_specgloss.png"), pngs):
        with open(os.path.join(out, name), "wb") as f:
            f.write(png)
    with open(os.path.join(out, "spec_gloss_textured.gltf"), "w") as f:
        json.dump(textured_document(uri, len(data), [{"uri": "sg_diffuse.png"}, {"uri": "sg_specgloss.png"}]), f, indent=1)
    # The .glb: geometry (44 bytes), then each PNG at a 4-byte aligned offset.
    binary = bytearray(data)
    views = []
    for png in pngs:
        binary += b"\x00" * (-len(binary) % 4)
        views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(png)})
        binary += png
    binary += b"\x00" * (-len(binary) % 4)
    doc = textured_document(None, len(binary), [{"bufferView": 2, "mimeType": "image/png"},
                                                 {"bufferView": 3, "mimeType": "image/png"}])
    doc["bufferViews"] += views
    with open(os.path.join(out, "spec_gloss_textured.glb"), "wb") as f:
        f.write(glb(doc, bytes(binary)))


if __name__ == "__main__":
    main()
