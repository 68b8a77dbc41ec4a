// shadelab prefiltered specular cube maps: the radiance convolved with a normalized lobe about the
// reflection direction, one lobe width per mip level, as engines sample them by gloss (split-sum style
// image-based lighting).
//
//   out_i(R) = sum_w L(w) K_i(R.w) dOmega / sum_w K_i(R.w) dOmega
//
// Phong lobe (the only one today): K_n(t) = (n + 1)/(2 pi) max(0, t)^n, the normalized Phong lobe of the
// zoo (integral over the sphere = 1). Dividing by the discrete weight sum instead of by 1 makes a constant
// environment come back exactly at every level. Its SH band factors (Funk-Hecke) are 1, (n+1)/(n+2),
// n/(n+3), which the tests use as an independent reference.
//
// Gloss-to-mip mapping (as cmft's glossScale / glossBias): level i of M has the Phong exponent
//   n_i = 2^(scale (1 - i/(M - 1)) + bias), default scale 10, bias 1: 2048 at level 0 down to 2 at the last.
// A shader with gloss g in [0, 1] reads level (1 - g)(M - 1), i.e. the exponent 2^(scale g + bias).
// Blinn-Phong exponents convert by n_phong = n_blinn / 4 (the lobe (N.H)^n about the mirror direction has
// the angular width of (R.L)^(n/4) near its peak, since the half vector turns half as fast as L).
//
// Each level sums the input texels inside the cap where the lobe is at least 1e-9 of its peak (a result
// changes by at most 1e-9 x the input's dynamic range). The cap is bounded per face by the rows and
// columns whose great circles pass within the cap's angle of R, and the weights are evaluated 8 at a time
// (AVX2 where the CPU has it) in float: t^n = exp(n ln(1 - d)) with d = |R - w|^2 / 2 = 1 - t, so narrow
// lobes keep their precision near t = 1. Each level reads the finest input level (the full input, the
// brute-force sum) unless that level would cost more than 2e9 weight evaluations; then it reads the finest
// pyramid level (solid-angle-weighted halving) within that budget, and never one whose texels are wider than
// half the lobe (1/sqrt(n) radians). A lobe narrower than the input's texels that catches no texel centre
// returns the bilinear sample at R.
//
// Adding a lobe (e.g. GGX for split-sum IBL): a value of PrefilterLobe, and in prefilter.cpp a struct with
// the weight as a function of d = 1 - R.w (8 lanes) and the cosine where it falls below 1e-9 of its peak;
// the cap search, the pyramid choice and the normalization are shared.
#pragma once

#include <vector>

#include "shadelab/brdf/gloss.h"
#include "shadelab/core/error.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/base/progress.h"

namespace shadelab {

enum class PrefilterLobe { phong };

struct PrefilterOptions {
  int size = 128;          // face size of level 0
  int mip_count = 0;       // 0: down to 1 x 1 (log2(size) + 1 levels)
  double gloss_scale = 10.0;
  double gloss_bias = 1.0;
  PrefilterLobe lobe = PrefilterLobe::phong;
  ProgressFn progress;
};

double prefilter_exponent(int level, int mip_count, double gloss_scale, double gloss_bias);
// phong_exponent_from_blinn_phong (n / 4) is in brdf/gloss.h.

struct PrefilteredCube {
  std::vector<CubeMap> levels;
  std::vector<double> exponents;  // Phong exponent of each level
};

// Validates the options (size a power of two >= 1, mip_count within range, finite scale and bias).
Result<PrefilteredCube> prefilter_specular(const CubeMap& radiance, const PrefilterOptions& options);

// One output direction at one exponent over every input texel, no culling, in double (for tests).
Rgb prefilter_brute_force(const CubeMap& radiance, const Vec3& r, double exponent);

}  // namespace shadelab
