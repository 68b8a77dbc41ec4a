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
  spec_gloss_textured.gltf  material 1 with a diffuseTexture (a 1 x 1 PNG data URI): refused by the converter

    /usr/bin/python3 scripts/make_spec_gloss_gltf.py [OUT_DIR]

Everything is made here from its own numbers; the files are the same bytes on every run.
"""
import base64
import json
import os
import struct
import sys
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


def png_1x1(rgb):
    """A 1 x 1 8-bit RGB PNG."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"\x00" + bytes(rgb)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def document(buffer_uri, buffer_length, textured=False):
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
    if textured:
        uri = "data:image/png;base64," + base64.b64encode(png_1x1((200, 120, 60))).decode("ascii")
        doc["images"] = [{"uri": uri}]
        doc["textures"] = [{"source": 0}]
        doc["materials"][1]["extensions"]["KHR_materials_pbrSpecularGlossiness"]["diffuseTexture"] = {"index": 0}
    return doc


def glb(doc, binary):
    text = json.dumps(doc, indent=1).encode("utf-8")
    text += b" " * (-len(text) % 4)
    binary += b"\x00" * (-len(binary) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    data = geometry()
    uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")
    with open(os.path.join(out, "spec_gloss.gltf"), "w") as f:
        json.dump(document(uri, len(data)), f, indent=1)
    with open(os.path.join(out, "spec_gloss.glb"), "wb") as f:
        f.write(glb(document(None, len(data)), data))
    with open(os.path.join(out, "spec_gloss_textured.gltf"), "w") as f:
        json.dump(document(uri, len(data), textured=True), f, indent=1)


if __name__ == "__main__":
    main()
