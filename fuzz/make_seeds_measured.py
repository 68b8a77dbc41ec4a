#!/usr/bin/env python3
"""Writes the seed corpora of the measured-BRDF harnesses: fuzz/corpus/rgl (RGL/EPFL tensor .bsdf files: an
isotropic and an anisotropic RGB BRDF, a spectral one the reader refuses, a container with one field of every
dtype, a truncated file) and fuzz/corpus/utia (a valid UTIA .bin file of a constant and a truncated one).
The layouts are written here from their descriptions (brdf/rgl.h, brdf/utia.h), independently of the C++ writer.
Run from the repository root:  python3 fuzz/make_seeds_measured.py
"""
import math
import os
import struct

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")

# dtype codes of the tensor container: 1 uint8 ... 10 float32, 11 float64
DTYPES = {"u8": (1, "B"), "i8": (2, "b"), "u16": (3, "H"), "i16": (4, "h"), "u32": (5, "I"), "i32": (6, "i"),
          "u64": (7, "Q"), "i64": (8, "q"), "f16": (9, "e"), "f32": (10, "f"), "f64": (11, "d")}


def tensor(fields):
    """fields: (name, dtype key, shape, flat values) -> the file's bytes."""
    header = b"tensor_file\0" + bytes([1, 0]) + struct.pack("<I", len(fields))
    size = len(header) + sum(2 + len(n) + 2 + 1 + 8 + 8 * len(s) for n, _, s, _ in fields)
    heads, datas = b"", b""
    for name, key, shape, values in fields:
        code, fmt = DTYPES[key]
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        heads += struct.pack("<H", len(name)) + name.encode() + struct.pack("<HBQ", len(shape), code, size + len(datas))
        heads += b"".join(struct.pack("<Q", s) for s in shape)
        datas += data
    return header + heads + datas


def brdf(phi_i, theta_i, n, spectral=False):
    np_, nt = len(phi_i), len(theta_i)
    vndf, lum, rgb = [], [], []
    for s in range(np_ * nt):
        for y in range(n):
            for x in range(n):
                u, v = x / (n - 1), y / (n - 1)
                vndf.append(math.exp(-6 * u * u) * (1.1 + math.cos(2 * math.pi * v)) + 0.01 * s)
                lum.append(0.2 + u * v)
        for c in range(3):
            rgb += [0.1 + 0.1 * c + 0.01 * k for k in range(n * n)]
    fields = [("theta_i", "f32", [nt], theta_i), ("phi_i", "f32", [np_], phi_i),
              ("ndf", "f32", [3, 3], [1.0 + 0.1 * k for k in range(9)]), ("sigma", "f32", [3, 3], [0.5] * 9),
              ("vndf", "f32", [np_, nt, n, n], vndf), ("luminance", "f32", [np_, nt, n, n], lum),
              ("spectra" if spectral else "rgb", "f32", [np_, nt, 3, n, n], rgb),
              ("description", "u8", [5], list(b"seed\n")), ("jacobian", "u8", [1], [1])]
    return tensor(fields)


def write(folder, name, data):
    os.makedirs(os.path.join(ROOT, folder), exist_ok=True)
    with open(os.path.join(ROOT, folder, name), "wb") as f:
        f.write(data)


def main():
    iso = brdf([0.0], [0.0, 0.4, 0.8, 1.2], 4)
    write("rgl", "isotropic.bsdf", iso)
    write("rgl", "anisotropic.bsdf", brdf([-math.pi, 0.0, math.pi], [0.0, 0.7], 3))
    write("rgl", "spectral.bsdf", brdf([0.0], [0.0, 1.0], 3, spectral=True))
    write("rgl", "every_dtype.bsdf", tensor([("f" + k, k, [2], [1, 2]) for k in DTYPES]))
    write("rgl", "truncated.bsdf", iso[:-40])
    # UTIA: 3 planes of 6 x 48 x 6 x 48 float64 (theta_i, phi_i, theta_v, phi_v; phi_v fastest).
    plane = 6 * 48 * 6 * 48
    write("utia", "constant.bin", struct.pack("<%dd" % (3 * plane), *([0.3] * plane + [0.2] * plane + [0.1] * plane)))
    write("utia", "truncated.bin", struct.pack("<4d", 0.3, 0.3, 0.3, 0.3))


if __name__ == "__main__":
    main()
