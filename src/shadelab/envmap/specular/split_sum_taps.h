// shadelab split-sum taps: each part of the split sum (f0 A, f90 B) averaged over its own true lobe by
// filtered importance sampling of the same GGX chain (Krivanek & Colbert 2008, "Real-time Shading with
// Filtered Importance Sampling": a sample reads the prefiltered map with a footprint equal to its share of
// solid angle), the samples drawn from the visible normals (bounded VNDF, Eto & Tokuyoshi 2023,
// brdf/microfacet.h).
//
// The split sum (Karis 2013) shades f0 A + f90 B times one read of the chain along R. Its error is the shape
// of that read's lobe (n = v = R, radially symmetric) against the true lobes of A and B,
//   w_A(l) = (1 - Fc) D G2 / (4 N.V),   w_B(l) = Fc D G2 / (4 N.V),   Fc = (1 - v.h)^5   (dfg.h),
// cut by the horizon and stretched at oblique view. Here part k's radiance is the lobe-weighted mean
//   read_k = sum_i w_k(l_i)/p(l_i) chain(l_i, r_i) / sum_i w_k(l_i)/p(l_i)
// over N fixed taps l_i = reflect(wo, h_i), h_i the bounded-VNDF half vector of the i-th point of the
// Hammersley set u_i = ((i + 1/2)/N, radical inverse of i) (the first Sobol dimension, sampling/sobol.h), p
// the density of l_i (ggx_vndf_bounded_pdf); the tap weight w(l)/p(l) = (1 - Fc or Fc) D G2 / (4 N.V p).
// Each tap reads the chain at the roughness whose lobe covers the tap's share of solid angle,
//   Omega_i = 1 / (N p(l_i)),  the chain lobe's solid angle 4 pi alpha^2 (the lobe D(h) (R.l) over its
//   integral, about 4 for small alpha, peaks at D(1) / 4 = 1 / (4 pi alpha^2)),  so  alpha_i = sqrt(Omega_i / (4 pi)),
// perceptual roughness r_i = sqrt(alpha_i), at most 1. The shading stays f0 A read_A + f90 B read_B with A and
// B from the DFG table: a constant environment comes back exactly (each read is a weighted mean), the same
// chain and the same table (the same storage), N reads instead of one. Taps below the horizon weigh 0.
// Measured against the path tracer by `shadelab ibl-error --correction filtered` (docs/envmap.md).
#pragma once

#include <span>

#include "shadelab/color/rgb.h"
#include "shadelab/core/frame.h"
#include "shadelab/core/vec.h"
#include "shadelab/envmap/specular/prefilter_ggx.h"

namespace shadelab {

struct SplitSumTap {
  Vec3 l;                  // the tap direction, in wo's frame (n = +Z)
  double roughness = 0.0;  // the chain's perceptual roughness read there
  double weight_a = 0.0;   // w_A(l) / p(l)
  double weight_b = 0.0;   // w_B(l) / p(l)
};

constexpr int split_sum_taps_max = 1024;

// The taps for wo (local) at perceptual roughness r in [0, 1], into out (out.size() taps, in
// [1, split_sum_taps_max], else std::invalid_argument); alpha = r^2 floored at 1e-4. The same wo, r and count
// give the same taps; with wo.z <= 0 every tap weighs 0.
void split_sum_taps(const Vec3& wo, double roughness, std::span<SplitSumTap> out);

struct SplitSumReads {
  Rgb a;  // the f0 A part's lobe-weighted radiance
  Rgb b;  // the f90 B part's
};

// read_A and read_B of the chain for wo (in frame's local coordinates) at perceptual roughness r with `taps`
// taps (in [1, split_sum_taps_max], else std::invalid_argument): each tap computed as split_sum_taps computes
// it and read by sample_ggx_chain at frame.to_world(l_i) and r_i. A part whose taps all weigh 0 (wo.z <= 0:
// none do) reads the chain along R at r.
SplitSumReads split_sum_filtered_reads(const GgxPrefilteredCube& chain, const Frame& frame, const Vec3& wo,
                                       double roughness, int taps);

}  // namespace shadelab
