#!/usr/bin/env python3
"""shadelab's prefiltered specular chain against cmft's radiance filter: error per level against a brute-force
lobe sum, and CPU time, on the same input cube.

Issue 15, target 2: `bake specular` >= 2x faster than cmft's radiance filter for the full chain, at equal or
lower mean AND max error than cmft on every level, measured against the brute-force lobe convolution.

Both programs filter the same 6 x SIZE^2 cube (`shadelab bake convert HDRI --size SIZE` as an EXR cross for
shadelab, and that EXR converted to rgba32f KTX 1 for cmft: the same texels) with the same normalized Phong lobes: level i of M has exponent
n_i = 2^(scale (1 - i/(M-1)) + bias) (cmft's --glossScale / --glossBias; shadelab's --gloss-scale /
--gloss-bias, prefilter_exponent in src/shadelab/envmap/specular/prefilter.cpp). Both write rgba32f KTX 1.

The reference (independent of both): for S output texels per level (a fixed random choice, the same for
both), the texel centre r of face f (OpenGL table 8.19, docs/envmap.md) and
    ref(r) = sum_t L_t (r.d_t)^n dOmega_t / sum_t (r.d_t)^n dOmega_t     over every input texel with r.d_t > 0,
in float64 with the exact texel solid angles (atan closed form). Error of a texel: max over R, G, B of
|out - ref| / ref. Per level and program: the mean and the max over the S texels.

CPU time: user + system of each command (the children's rusage), the median of ROUNDS alternating runs.

    CMFT=/path/to/cmftRelease /usr/bin/python3 bench/cmft_compare.py --build build/release

--lobe ggx times shadelab's GGX chain instead (`bake specular --lobe ggx`, the default linear mapping:
level i at perceptual roughness r_i = i/(M-1), alpha = r^2, --ggx-method: its default lobe sum, or sampled with
its default 1024 samples) against the same
cmft Phong run (cmft has no GGX lobe), and measures each program against its own lobe: shadelab's level i
against the brute-force sum of the n = v = r GGX lobe, weight D(h) (R.l) dOmega with
D = alpha^2 / (pi ((R.h)^2 (alpha^2 - 1) + 1)^2) (Walter et al. 2007 eq. 33) and (R.h)^2 = (1 + R.l)/2,
level 0 (r = 0, the delta lobe) against the input texel; cmft's against the Phong sum as above.
"""
import argparse
import os
import resource
import statistics
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

DEFAULT_HDRI = "/usr/share/blender/datafiles/studiolights/world/sunrise.exr"
GL_FLOAT, GL_HALF_FLOAT = 0x1406, 0x140B


def read_ktx1_cube(path):
    """KTX 1 cube map, RGBA float or half: a list of levels, each a (6, N, N, 3) float64 array (face, row, col)."""
    data = Path(path).read_bytes()
    if data[:12] != b"\xabKTX 11\xbb\r\n\x1a\n":
        sys.exit(f"{path}: not a KTX 1 file")
    (endian, gl_type, type_size, gl_format, internal, base, width, height, depth, elements, faces, mips,
     kv_bytes) = struct.unpack_from("<13I", data, 12)
    if endian != 0x04030201 or faces != 6 or gl_type not in (GL_FLOAT, GL_HALF_FLOAT) or gl_format != 0x1908:
        sys.exit(f"{path}: expected a little-endian RGBA float or half cube map (type {gl_type:#x}, format "
                 f"{gl_format:#x}, faces {faces})")
    dtype = np.float32 if gl_type == GL_FLOAT else np.float16
    offset = 64 + kv_bytes
    levels = []
    for level in range(max(1, mips)):
        n = max(1, width >> level)
        (image_size,) = struct.unpack_from("<I", data, offset)
        offset += 4
        face_bytes = n * n * 4 * np.dtype(dtype).itemsize
        if image_size != face_bytes:
            sys.exit(f"{path}: level {level}: imageSize {image_size}, expected {face_bytes}")
        cube = np.empty((6, n, n, 3))
        for f in range(6):
            texels = np.frombuffer(data, dtype=dtype, count=n * n * 4, offset=offset).reshape(n, n, 4)
            cube[f] = texels[:, :, :3].astype(np.float64)
            offset += (face_bytes + 3) // 4 * 4
        levels.append(cube)
    return levels


def face_directions(f, s, t):
    """Unit directions of face f at face coordinates s, t in [0, 1] (the inverse of OpenGL table 8.19)."""
    sc, tc = 2 * s - 1, 2 * t - 1
    one = np.ones_like(sc)
    r = {0: (one, -tc, -sc), 1: (-one, -tc, sc), 2: (sc, one, tc), 3: (sc, -one, -tc), 4: (sc, -tc, one),
         5: (-sc, -tc, -one)}[f]
    v = np.stack(r, axis=-1)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def texel_table(n):
    """Directions (6 n^2, 3) and exact solid angles (6 n^2,) of every texel of an n^2 cube, face-major, row-major."""
    c = (np.arange(n) + 0.5) / n
    s, t = np.meshgrid(c, c)  # s along a row (x), t down the face (y)
    dirs = np.concatenate([face_directions(f, s, t).reshape(-1, 3) for f in range(6)])
    e = np.linspace(-1.0, 1.0, n + 1)
    x, y = np.meshgrid(e, e)
    big_f = np.arctan2(x * y, np.sqrt(x * x + y * y + 1.0))
    omega = big_f[1:, 1:] - big_f[1:, :-1] - big_f[:-1, 1:] + big_f[:-1, :-1]
    return dirs, np.tile(omega.reshape(-1), 6)


def brute_force(radiance, dirs, omega, r, n):
    c = dirs @ r
    keep = c > 0
    w = np.power(c[keep], n) * omega[keep]
    return (radiance[keep] * w[:, None]).sum(axis=0) / w.sum()


def brute_force_ggx(radiance, dirs, omega, r, rough):
    """The n = v = r GGX lobe sum at perceptual roughness rough > 0 (weights D(h) (R.l) dOmega)."""
    c = dirs @ r
    keep = c > 0
    a2 = rough ** 4  # alpha = rough^2
    rh2 = (1.0 + c[keep]) / 2.0
    w = a2 / (np.pi * (rh2 * (a2 - 1.0) + 1.0) ** 2) * c[keep] * omega[keep]
    return (radiance[keep] * w[:, None]).sum(axis=0) / w.sum()


def run_timed(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default="build/release", help="CMake build folder (default build/release)")
    ap.add_argument("--cmft", default=os.environ.get("CMFT"), help="cmft binary (default $CMFT)")
    ap.add_argument("--hdri", default=DEFAULT_HDRI, help=f"input environment (default {DEFAULT_HDRI})")
    ap.add_argument("--size", type=int, default=256, help="input and output face size (default 256)")
    ap.add_argument("--samples", type=int, default=48, help="texels per level checked against the brute force (default 48)")
    ap.add_argument("--rounds", type=int, default=3, help="alternating timed runs of each program (default 3)")
    ap.add_argument("--gloss-scale", type=float, default=10.0)
    ap.add_argument("--gloss-bias", type=float, default=1.0)
    ap.add_argument("--lobe", choices=["phong", "ggx"], default="phong",
                    help="shadelab's chain: phong (cmft's lobe, default) or ggx (see above)")
    ap.add_argument("--ggx-method", choices=["sum", "sampled"], default="sum",
                    help="--lobe ggx: shadelab's --method (default sum, its default)")
    args = ap.parse_args()
    if not args.cmft or not Path(args.cmft).exists():
        print("cmft_compare: cmft not found (set CMFT or --cmft); nothing measured")
        return 0
    shadelab = str(Path(args.build).resolve() / "tools/shadelab/shadelab")
    mips = args.size.bit_length()  # down to 1 x 1
    with tempfile.TemporaryDirectory() as tmp:
        # The cube as an EXR cross (shadelab's input), then that EXR as rgba32f KTX 1 (cmft's): the same texels.
        cross, cube = f"{tmp}/cube.exr", f"{tmp}/cube.ktx"
        subprocess.run([shadelab, "bake", "convert", args.hdri, "--size", str(args.size), "--out", cross], check=True,
                       stdout=subprocess.DEVNULL)
        subprocess.run([shadelab, "bake", "convert", cross, "--size", str(args.size), "--format", "rgba32f", "--out", cube],
                       check=True, stdout=subprocess.DEVNULL)
        ours = [shadelab, "bake", "specular", cross, "--size", str(args.size), "--no-exr-faces", "--format", "rgba32f",
                "--gloss-scale", str(args.gloss_scale), "--gloss-bias", str(args.gloss_bias), "--out", f"{tmp}/ours.ktx"]
        if args.lobe == "ggx":
            ours = [shadelab, "bake", "specular", cross, "--lobe", "ggx", "--size", str(args.size), "--no-exr-faces",
                    "--format", "rgba32f", "--method", args.ggx_method, "--out", f"{tmp}/ours.ktx"]
        theirs = [args.cmft, "--input", cube, "--filter", "radiance", "--srcFaceSize", "0", "--excludeBase", "false",
                  "--mipCount", str(mips), "--glossScale", str(args.gloss_scale), "--glossBias", str(args.gloss_bias),
                  "--lightingModel", "phong", "--dstFaceSize", str(args.size), "--numCpuProcessingThreads", "2",
                  "--useOpenCL", "false", "--edgeFixup", "none", "--generateMipChain", "false", "--outputNum", "1",
                  "--output0", f"{tmp}/cmft", "--output0params", "ktx,rgba32f,cubemap"]
        t_ours, t_theirs = [], []
        for _ in range(args.rounds):
            t_ours.append(run_timed(ours))
            t_theirs.append(run_timed(theirs))
        inp = read_ktx1_cube(cube)[0]
        out = {"shadelab": read_ktx1_cube(f"{tmp}/ours.ktx"), "cmft": read_ktx1_cube(f"{tmp}/cmft.ktx")}
    for name, levels in out.items():
        if len(levels) != mips:
            sys.exit(f"cmft_compare: {name} wrote {len(levels)} levels, expected {mips}")
    dirs, omega = texel_table(args.size)
    radiance = inp.reshape(-1, 3)
    rng = np.random.default_rng(15)
    print(f"cmft_compare: {Path(args.hdri).name}, 6 x {args.size}^2 rgba32f in and out, {mips} levels, "
          f"{args.samples} texels per level against the brute-force lobe sum (float64); shadelab's lobe: {args.lobe}"
          + (f" --method {args.ggx_method}" if args.lobe == "ggx" else ""))
    print(f"{'level':>5} {'face':>5} {'exponent':>9} {'shadelab mean':>14} {'cmft mean':>10} {'shadelab max':>13} "
          f"{'cmft max':>9}  lower")
    all_lower = True
    for i in range(mips):
        size = max(1, args.size >> i)
        n = 2.0 ** (args.gloss_scale * (1.0 - i / (mips - 1)) + args.gloss_bias)
        picks = [(int(rng.integers(6)), int(rng.integers(size)), int(rng.integers(size))) for _ in range(args.samples)]
        errs = {k: [] for k in out}
        for f, y, x in picks:
            r = face_directions(f, np.array((x + 0.5) / size), np.array((y + 0.5) / size)).reshape(3)
            refs = {"cmft": brute_force(radiance, dirs, omega, r, n)}
            if args.lobe == "phong":
                refs["shadelab"] = refs["cmft"]
            elif i == 0:
                refs["shadelab"] = inp[f, y, x]  # r = 0: the delta lobe, the input itself
            else:
                refs["shadelab"] = brute_force_ggx(radiance, dirs, omega, r, i / (mips - 1))
            for k, levels in out.items():
                errs[k].append(float(np.max(np.abs(levels[i][f, y, x] - refs[k]) / refs[k])))
        m = {k: (statistics.fmean(v), max(v)) for k, v in errs.items()}
        lower = m["shadelab"][0] <= m["cmft"][0] and m["shadelab"][1] <= m["cmft"][1]
        all_lower &= lower
        print(f"{i:>5} {size:>5} {n:>9.4g} {m['shadelab'][0]:>14.3e} {m['cmft'][0]:>10.3e} {m['shadelab'][1]:>13.3e} "
              f"{m['cmft'][1]:>9.3e}  {'yes' if lower else 'NO'}")
    mo, mt = statistics.median(t_ours), statistics.median(t_theirs)
    print(f"CPU s, median of {args.rounds} alternating runs: shadelab {mo:.3f}, cmft {mt:.3f}, ratio {mo / mt:.3f} "
          f"(target <= 0.5); error below cmft's on every level (mean and max): {'yes' if all_lower else 'NO'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
