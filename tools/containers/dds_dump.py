#!/usr/bin/python3
"""Reads a DDS cube map with the DX10 header (an independent reader: struct + numpy, written from
Microsoft's DDS_HEADER / DDS_HEADER_DXT10 documentation and the D3D11 format definitions) and prints what a
test checks as JSON: header fields, problems with the layout, and the texels asked for.

    /usr/bin/python3 dds_dump.py FILE [LEVEL:FACE:X:Y ...]
"""
import json
import struct
import sys

import numpy as np

FORMATS = {  # DXGI_FORMAT -> (name, bytes per texel)
    2: ("DXGI_FORMAT_R32G32B32A32_FLOAT", 16),
    10: ("DXGI_FORMAT_R16G16B16A16_FLOAT", 8),
    26: ("DXGI_FORMAT_R11G11B10_FLOAT", 4),
    67: ("DXGI_FORMAT_R9G9B9E5_SHAREDEXP", 4),
}


def small_float(bits, mbits):
    """Unsigned float with 5 exponent bits (bias 15) and mbits mantissa bits (D3D11 3.1: float11 / float10)."""
    e, m = bits >> mbits, bits & ((1 << mbits) - 1)
    if e == 31:
        return float("nan") if m else float("inf")
    if e == 0:
        return m / 2.0**mbits * 2.0**-14
    return (1.0 + m / 2.0**mbits) * 2.0 ** (e - 15)


def decode(raw, fmt):
    if fmt == 10:
        return [float(v) for v in np.frombuffer(raw, dtype="<f2")]
    if fmt == 2:
        return [float(v) for v in np.frombuffer(raw, dtype="<f4")]
    (p,) = struct.unpack("<I", raw)
    if fmt == 26:  # R bits 0..10, G 11..21, B 22..31
        return [small_float(p & 0x7FF, 6), small_float((p >> 11) & 0x7FF, 6), small_float(p >> 22, 5)]
    scale = 2.0 ** ((p >> 27) - 15 - 9)  # R9G9B9E5: mantissas 0..8, 9..17, 18..26, exponent 27..31
    return [(p & 511) * scale, ((p >> 9) & 511) * scale, ((p >> 18) & 511) * scale]


def main():
    path, queries = sys.argv[1], sys.argv[2:]
    data = open(path, "rb").read()
    problems = []
    if data[:4] != b"DDS ":
        print(json.dumps({"problems": ["no DDS magic"]}))
        return
    h = struct.unpack_from("<31I", data, 4)  # DDS_HEADER: 31 uint32
    size, flags, height, width, pitch, depth, mips = h[0:7]
    pf_size, pf_flags, fourcc = h[18], h[19], struct.pack("<I", h[20])
    caps, caps2 = h[26], h[27]
    dxgi, dimension, misc, array_size, misc2 = struct.unpack_from("<5I", data, 128)
    if size != 124 or pf_size != 32:
        problems.append("header sizes")
    if not pf_flags & 0x4 or fourcc != b"DX10":
        problems.append("no DX10 fourCC")
    if dxgi not in FORMATS:
        problems.append("DXGI format %d not supported" % dxgi)
        print(json.dumps({"problems": problems}))
        return
    name, texel = FORMATS[dxgi]
    if pitch != width * texel or not flags & 0x8:
        problems.append("pitch %d, expected %d" % (pitch, width * texel))
    if not flags & 0x20000 or not caps & 0x400000:
        problems.append("mip count or MIPMAP cap missing")
    if caps2 & 0xFE00 != 0xFE00 or not misc & 0x4:
        problems.append("not a cube map with all six faces")
    count = mips if mips > 0 else 1
    sizes = [max(1, width >> i) for i in range(count)]
    face_bytes = sum(n * n * texel for n in sizes)
    expected = 148 + 6 * array_size * face_bytes
    if len(data) != expected:
        problems.append("file is %d bytes, expected %d" % (len(data), expected))
    texels = []
    for q in queries:
        level, face, x, y = (int(v) for v in q.split(":"))
        n = sizes[level]
        offset = 148 + face * face_bytes + sum(m * m * texel for m in sizes[:level]) + (y * n + x) * texel
        value = decode(data[offset : offset + texel], dxgi)
        texels.append({"level": level, "face": face, "x": x, "y": y,
                       "value": [v if np.isfinite(v) else str(v) for v in value]})
    print(json.dumps({
        "reader": "dds_dump.py", "width": width, "height": height, "depth": depth, "mipMapCount": mips,
        "dxgiFormat": dxgi, "dxgiFormatName": name, "resourceDimension": dimension, "miscFlag": misc,
        "arraySize": array_size, "caps2": caps2, "problems": problems, "texels": texels}))


if __name__ == "__main__":
    main()
