// shadelab LDR-FLIP: the perceptual difference of two display images, per pixel in [0, 1] and its mean.
//
// Sources (formulas and published constants; no code is taken from anywhere):
//   P. Andersson, J. Nilsson, T. Akenine-Moller, M. Oskarsson, K. Astrom, M. D. Fairchild 2020, "FLIP: A
//   Difference Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2) (HPG 2020):
//   section 4 (colour pipeline), section 5 (feature pipeline), section 6 (final error); and the authors'
//   note separatedConvolutions.pdf (github.com/NVlabs/flip, misc/) for the normalisation of the filters that
//   the published values were computed with. docs/images.md states the tests and the published value
//   (0.159691 on the repository's reference.png / test.png at 67 pixels per degree) this implementation meets.
//
// Contract:
// - Inputs are linear display RGB (the sRGB-decoded values of what a screen shows; image.h's linear Rec.709),
//   test and reference of the same size; values are clamped to [0, 1] first (LDR-FLIP). Non-finite values,
//   empty images and different sizes are Errors naming the image (CompareOptions names, as metrics.h).
// - Colour pipeline, per pixel: linear RGB -> XYZ (D65) -> YCxCz (the linearised L*a*b* of Zhang & Wandell
//   1997: Y = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn)); each channel convolved with
//   its contrast sensitivity filter, the spatial form of a sum of Gaussians,
//     S(x) = sum_i a_i sqrt(pi / b_i) exp(-pi^2 |x|^2 / b_i),  |x| in degrees = pixels / ppd,
//   (Y: a = 1, b = 0.0047; Cx: a = 1, b = 0.0053; Cz: a = 34.1, b = 0.04 plus a = 13.5, b = 0.025), over a
//   (2r+1)^2 square, r = ceil(3 sqrt(b_max / (2 pi^2)) ppd), normalised to sum 1, edges clamped; back to
//   linear RGB, clamped to [0, 1], to CIE L*a*b*, Hunt-adjusted (a, b) *= 0.01 L; then HyAB
//   dE = |L1 - L2| + sqrt((a1 - a2)^2 + (b1 - b2)^2), raised to q_c = 0.7, and mapped to [0, 1] by
//   e_c = dE p_t / (p_c c_max) below p_c c_max, else p_t + (dE - p_c c_max) / (c_max - p_c c_max) (1 - p_t),
//   p_c = 0.4, p_t = 0.95, c_max = HyAB(Hunt(green), Hunt(blue))^q_c (the sRGB primaries, the largest
//   difference).
// - Feature pipeline, on the achromatic y = (Y + 16) / 116 of the unfiltered YCxCz: the first and second
//   derivatives of a Gaussian of sigma = 0.5 w ppd pixels (w = 0.082 degrees), r = ceil(3 sigma), the
//   Gaussian normalised to sum 1 and each derivative's positive and negative weights to +1 and -1, in x and
//   y; edge = |(d/dx, d/dy)|, point = |(d2/dx2, d2/dy2)|; e_f = (max(|edge_t - edge_r|, |point_t - point_r|)
//   / sqrt(2))^q_f, q_f = 0.5.
// - FLIP = e_c^(1 - e_f). Symmetric in its two images; 0 for identical images; in [0, 1].
// - Same inputs, same output on every run (double arithmetic in a fixed order; no threads).
#pragma once

#include <string>

#include "shadelab/core/error.h"
#include "shadelab/image/image.h"
#include "shadelab/image/metrics.h"

namespace shadelab {

// The paper's default viewing condition: a 0.7 m wide 3840-pixel monitor seen from 0.7 m, about 67 pixels
// per degree (Andersson et al. 2020, section 7).
inline constexpr double flip_default_ppd = 67.0;

struct FlipOptions {
  double pixels_per_degree = flip_default_ppd;
  std::string name_test = "test";
  std::string name_reference = "reference";
};

struct FlipResult {
  Plane map;          // per-pixel FLIP, the images' size
  double mean = 0.0;  // its mean (FLIP's pooled figure in the paper and the reference tool)
};

// FLIP of test against reference (both linear display RGB, clamped to [0, 1]).
Result<FlipResult> flip(const Image& test, const Image& reference, const FlipOptions& options = {});

// The colour error e_c of two flat colours (no spatial variation: the filters keep them as they are and the
// feature error is 0), linear display RGB clamped to [0, 1]; what flip() gives for two flat images.
double flip_flat_color_error(const Rgb& test, const Rgb& reference);

// c_max^(1/q_c): the HyAB distance of the Hunt-adjusted sRGB green and blue primaries in L*a*b*.
double flip_max_hyab();

}  // namespace shadelab
