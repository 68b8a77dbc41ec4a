#!/usr/bin/python3
"""Writes share/ocio/shadelab.ocio and its LUTs: an OpenColorIO 2 config whose sRGB display has the views of
kernels/display.sl (Standard, Filmic, PBR Neutral, AgX, ACES) and whose colour spaces are the working spaces
(Linear Rec.709, the reference; ACEScg). Written from the published formulas with numpy, independently of the
C++/shader kernels, so that OCIO running this config is a second implementation of every view (docs/color.md;
the test render/view_ocio_test.cpp compares them).

Run: /usr/bin/python3 scripts/make_ocio_config.py [OUT_DIR]   (default share/ocio; the committed files are its
output, byte for byte).

Per view (scene-linear Rec.709 in, sRGB display code values out):
  Standard     clamp to [0, 1], the sRGB encoding (IEC 61966-2-1) as OCIO's ExponentWithLinearTransform.
  Filmic       a log2 shaper, then a 1D LUT of sRGB(Narkowicz 2015) per channel.
  ACES         Hill's ACESInputMat (MatrixTransform), a log2 shaper + 1D LUT of his RRT+ODT rational fit, ACESOutputMat,
               clamp, sRGB.
  AgX          Rec.709 -> Rec.2020 (derived here from the ITU-R primaries) and Filament's inset (one MatrixTransform),
               log2 over [-12.47393, 4.026069] (LogAffineTransform), clamp, a 1D LUT of Wrensch's sigmoid polynomial,
               Filament's outset, the 2.2 power (ExponentTransform), Rec.2020 -> Rec.709, clamp, sRGB.
  PBR Neutral  not per channel (it reads min and max of R, G, B, which OCIO 2.1's transforms cannot), so a 3D LUT
               (tetrahedral) of the Khronos specification's formula, sRGB-encoded, behind a log2 shaper that puts
               extra grid planes at its two kinks (min = 2 F90 and max - f = Ks): an approximation, its
               agreement measured in docs/color.md.
"""
import os
import sys

import numpy as np

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "share", "ocio")
LUTS = os.path.join(OUT, "luts")

# ---- colour science -----------------------------------------------------------------------------------------
def rgb_to_xyz(primaries, white):
    """RGB -> XYZ of primaries and white given as xy (SMPTE RP 177-1993)."""
    P = np.array([[x / y, 1.0, (1.0 - x - y) / y] for x, y in primaries]).T
    W = np.array([white[0] / white[1], 1.0, (1.0 - white[0] - white[1]) / white[1]])
    return P * np.linalg.solve(P, W)


D65 = (0.3127, 0.3290)
D60_ACES = (0.32168, 0.33767)  # SMPTE ST 2065-1 white
REC709 = rgb_to_xyz([(0.64, 0.33), (0.30, 0.60), (0.15, 0.06)], D65)          # ITU-R BT.709-6
REC2020 = rgb_to_xyz([(0.708, 0.292), (0.170, 0.797), (0.131, 0.046)], D65)   # ITU-R BT.2020-2
AP1 = rgb_to_xyz([(0.713, 0.293), (0.165, 0.830), (0.128, 0.044)], D60_ACES)  # ACEScg, S-2014-004
REC709_TO_REC2020 = np.linalg.solve(REC2020, REC709)
REC2020_TO_REC709 = np.linalg.inv(REC709_TO_REC2020)
# The Bradford cone response (Lam 1985), for the von Kries adaptation of the ACES white to D65 (as ACES's own
# ACEScg <-> Rec.709 transforms do).
BRADFORD = np.array([[0.8951, 0.2664, -0.1614], [-0.7502, 1.7135, 0.0367], [0.0389, -0.0685, 1.0296]])


def white_xyz(w):
    return np.array([w[0] / w[1], 1.0, (1.0 - w[0] - w[1]) / w[1]])


def bradford(src, dst):
    s, d = BRADFORD @ white_xyz(src), BRADFORD @ white_xyz(dst)
    return np.linalg.inv(BRADFORD) @ np.diag(d / s) @ BRADFORD


ACESCG_TO_REC709 = np.linalg.solve(REC709, bradford(D60_ACES, D65) @ AP1)


def srgb_encode(l):
    """IEC 61966-2-1:1999 section 4.7, on [0, 1]."""
    l = np.clip(l, 0.0, 1.0)
    return np.where(l <= 0.0031308, 12.92 * l, 1.055 * np.power(l, 1.0 / 2.4) - 0.055)


def narkowicz(x):
    """Narkowicz 2015, 'ACES Filmic Tone Mapping Curve'."""
    x = np.maximum(x, 0.0)
    return np.clip(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0)


# Hill's fit (BakingLab ACES.hlsl): the matrices as published (rows) and the rational fit.
ACES_IN = np.array([[0.59719, 0.35458, 0.04823], [0.07600, 0.90834, 0.01566], [0.02840, 0.13383, 0.83777]])
ACES_OUT = np.array([[1.60475, -0.53108, -0.07367], [-0.10208, 1.10813, -0.00605], [-0.00327, -0.07276, 1.07602]])


def hill_fit(v):
    return (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081)


# AgX: Filament's AgxInsetMatrix and the inverse of its AgxOutsetMatrixInv (rows), log2 range, Wrensch's polynomial.
AGX_INSET = np.array([[0.856627153315983, 0.0951212405381588, 0.0482516061458583],
                      [0.137318972929847, 0.761241990602591, 0.101439036467562],
                      [0.11189821299995, 0.0767994186031903, 0.811302368396859]])
AGX_OUTSET = np.array([[1.1271005818144368, -0.11060664309660323, -0.016493938717834573],
                       [-0.1413297634984383, 1.157823702216272, -0.016493938717834257],
                       [-0.14132976349843826, -0.11060664309660294, 1.2519364065950405]])
AGX_MIN_EV, AGX_MAX_EV = -12.47393, 4.026069


def agx_sigmoid(t):
    return np.polyval([15.5, -40.14, 31.96, -6.868, 0.4298, 0.1191, -0.00232], t)


def pbr_neutral(c):
    """Khronos PBR Neutral, its specification (KhronosGroup/ToneMapping, PBR_Neutral/README.md)."""
    F90, Ks, Kd = 0.04, 0.8 - 0.04, 0.15
    c = np.maximum(c, 0.0)
    x = c.min(axis=-1, keepdims=True)
    f = np.where(x <= 2 * F90, x - x * x / (4 * F90), F90)
    c = c - f
    p = c.max(axis=-1, keepdims=True)
    pn = 1 - (1 - Ks) ** 2 / (p + 1 - 2 * Ks)
    g = 1 / (Kd * (p - pn) + 1)
    safe_p = np.where(p > Ks, p, 1.0)
    return np.where(p <= Ks, c, c * pn / safe_p * g + pn * (1 - g))


# ---- shapers and LUT files ----------------------------------------------------------------------------------
# The log2 shaper of the per-channel LUTs: u = (log2(x + 2^LO) - LO) / (HI - LO), x in [0, 2^HI - 2^LO].
LOG_LO, LOG_HI = -14.0, 12.0
N1D = 4096


def log_shaper_inverse(u, lo, hi):
    return np.exp2(lo + u * (hi - lo)) - np.exp2(lo)


def log_affine(lo, hi, offset):
    """OCIO LogAffineTransform for y = (log2(x + offset) - lo) / (hi - lo)."""
    s = 1.0 / (hi - lo)
    return (f"!<LogAffineTransform> {{base: 2, lin_side_offset: {fmt(offset)}, log_side_slope: {fmt(s)}, "
            f"log_side_offset: {fmt(-lo * s)}}}")


def fmt(v):
    return repr(float(v))


def write_spi1d(name, values, lo=0.0, hi=1.0):
    lines = ["Version 1", f"From {fmt(lo)} {fmt(hi)}", f"Length {len(values)}", "Components 1", "{"]
    lines += [f"  {v:.9g}" for v in values]
    lines.append("}")
    with open(os.path.join(LUTS, name), "w") as f:
        f.write("\n".join(lines) + "\n")


def matrix(m):
    m44 = np.eye(4)
    m44[:3, :3] = m
    return "!<MatrixTransform> {matrix: [" + ", ".join(fmt(v) for v in m44.ravel()) + "]}"


def file_transform(name, interp="linear"):
    return f"!<FileTransform> {{src: {name}, interpolation: {interp}}}"


CLAMP_BELOW = "!<RangeTransform> {min_in_value: 0, min_out_value: 0}"
CLAMP_01 = "!<RangeTransform> {min_in_value: 0, max_in_value: 1, min_out_value: 0, max_out_value: 1}"
SRGB_ENCODE = "!<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055, direction: inverse}"

# PBR Neutral's 3D LUT: grid planes placed by a density over the log2 shaper's u, with bumps at the kinks.
PBR_N = 33
PBR_LO, PBR_HI = -9.0, 12.0


def pbr_grid():
    uu = np.linspace(0.0, 1.0, 65536)
    kinks = [(np.log2(k + 2 ** PBR_LO) - PBR_LO) / (PBR_HI - PBR_LO) for k in (0.08, 0.78)]
    dens = 1.0 + sum(10.0 * np.exp(-(((uu - k) / 0.03) ** 2)) for k in kinks)
    F = np.concatenate([[0.0], np.cumsum((dens[1:] + dens[:-1]) / 2)])
    return uu, F / F[-1]


def main():
    os.makedirs(LUTS, exist_ok=True)
    u = np.linspace(0.0, 1.0, N1D)
    x = log_shaper_inverse(u, LOG_LO, LOG_HI)
    write_spi1d("filmic_srgb.spi1d", srgb_encode(narkowicz(x)))
    write_spi1d("aces_fit.spi1d", hill_fit(x))
    write_spi1d("agx_sigmoid.spi1d", agx_sigmoid(u))
    # PBR Neutral: shaper u -> t (1D), then the 3D LUT over t (.cube, red fastest).
    uu, F = pbr_grid()
    write_spi1d("pbr_neutral_shaper.spi1d", np.interp(u, uu, F))
    t = np.linspace(0.0, 1.0, PBR_N)
    gx = log_shaper_inverse(np.interp(t, F, uu), PBR_LO, PBR_HI)
    b, g, r = np.meshgrid(gx, gx, gx, indexing="ij")  # b slowest, r fastest
    rgb = np.stack([r, g, b], axis=-1).reshape(-1, 3)
    out = srgb_encode(pbr_neutral(rgb))
    with open(os.path.join(LUTS, "pbr_neutral_srgb.cube"), "w") as f:
        f.write("# Khronos PBR Neutral, sRGB-encoded, over scripts/make_ocio_config.py's shaped grid\n")
        f.write(f"LUT_3D_SIZE {PBR_N}\n")
        f.write("\n".join(f"{v[0]:.7f} {v[1]:.7f} {v[2]:.7f}" for v in out) + "\n")

    log_shaper = log_affine(LOG_LO, LOG_HI, 2 ** LOG_LO)
    views = {
        "Standard": [CLAMP_01, SRGB_ENCODE],
        "Filmic": [CLAMP_BELOW, log_shaper, file_transform("filmic_srgb.spi1d")],
        "PBR Neutral": [CLAMP_BELOW, log_affine(PBR_LO, PBR_HI, 2 ** PBR_LO), CLAMP_01,
                        file_transform("pbr_neutral_shaper.spi1d"), file_transform("pbr_neutral_srgb.cube", "tetrahedral")],
        "AgX": [CLAMP_BELOW, matrix(AGX_INSET @ REC709_TO_REC2020), log_affine(AGX_MIN_EV, AGX_MAX_EV, 1e-10), CLAMP_01,
                file_transform("agx_sigmoid.spi1d"), matrix(AGX_OUTSET),
                "!<ExponentTransform> {value: [2.2, 2.2, 2.2, 1], style: clamp}", matrix(REC2020_TO_REC709), CLAMP_01,
                SRGB_ENCODE],
        "ACES": [CLAMP_BELOW, matrix(ACES_IN), log_shaper, file_transform("aces_fit.spi1d"), matrix(ACES_OUT), CLAMP_01,
                 SRGB_ENCODE],
    }
    y = ["ocio_profile_version: 2.1", "",
         "# Written by scripts/make_ocio_config.py (do not edit): shadelab's views as OCIO transforms (docs/color.md).",
         "name: shadelab", "description: shadelab's view transforms (kernels/display.sl) and working spaces",
         "search_path: luts", "strictparsing: true", "",
         "roles:", "  default: Linear Rec.709", "  scene_linear: Linear Rec.709", "  reference: Linear Rec.709",
         "  data: Raw", "", "file_rules:", "  - !<Rule> {name: Default, colorspace: default}", "",
         "displays:", "  sRGB:"]
    for name in views:
        y.append(f"    - !<View> {{name: {name}, colorspace: sRGB - {name}}}")
    y += ["", "active_displays: [sRGB]", "active_views: [" + ", ".join(views) + "]", "", "colorspaces:",
          "  - !<ColorSpace>", "    name: Linear Rec.709", "    family: scene-linear", "    bitdepth: 32f",
          "    description: scene-linear, ITU-R BT.709 primaries, D65 (shadelab's working space)", "    isdata: false",
          "", "  - !<ColorSpace>", "    name: ACEScg", "    family: scene-linear", "    bitdepth: 32f",
          "    description: ACES AP1 primaries, ACES white (S-2014-004); to Rec.709 by Bradford adaptation to D65",
          "    isdata: false", "    to_reference: " + matrix(ACESCG_TO_REC709), "",
          "  - !<ColorSpace>", "    name: Raw", "    family: data", "    isdata: true", ""]
    for name, steps in views.items():
        y += ["  - !<ColorSpace>", f"    name: sRGB - {name}", "    family: display", "    bitdepth: 32f",
              f"    description: shadelab's '{name}' view, sRGB display code values", "    isdata: false",
              "    from_reference: !<GroupTransform>", "      children:"]
        y += [f"        - {s}" for s in steps]
        y.append("")
    with open(os.path.join(OUT, "shadelab.ocio"), "w") as f:
        f.write("\n".join(y))


if __name__ == "__main__":
    main()
