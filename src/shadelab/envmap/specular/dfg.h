// shadelab DFG table: the split-sum environment BRDF of the height-correlated Smith GGX model, as engines
// load it next to a prefiltered specular cube (Karis 2013, "Real Shading in Unreal Engine 4", eqs. 4-8;
// Filament's documentation, "Pre-integrated DFG"; multiple-scattering use: Turquin 2019, "Practical
// multiple scattering compensation for microfacet models"; Filament, "Energy compensation").
//
// For a view direction v at N.V = mu and GGX roughness alpha = r^2 (r the perceptual roughness), with
// Schlick's F = F0 + (1 - F0) Fc, Fc = (1 - V.H)^5:
//   integral f_spec(v, l) N.L dl = F0 A + B,
//   A = integral (1 - Fc) D G2 / (4 N.V) dl,   B = integral Fc D G2 / (4 N.V) dl,
// and A + B = E_ss(mu, alpha), the single-scattering albedo with F = 1 (what Filament/Turquin compensation
// divides by). D is GGX (microfacet.sl D_ggx), G2 the height-correlated Smith term (microfacet.sl).
//
// Contract:
// - Texel (i, j) of a size x size table holds x = N.V = (i + 0.5) / size (column i, left to right) and
//   y = r = (j + 0.5) / size (row j; row 0, the first row in memory, is the smallest roughness: uploaded
//   row by row as a GL/Vulkan texture, texture coordinates (N.V, r) address it directly; in an image viewer
//   that row is at the top).
// - Channels: 0 = A (scale of F0), 1 = B (bias), 2 = A + B (the albedo E_ss) when multiscatter, else 0.
// - Method quadrature (default): per texel, an adaptive Gauss-Kronrod double integral (numeric/quadrature.h)
//   over the half vector, in Walter et al. 2007's GGX sampling variable xi (D cos(theta_h) d(omega_h) =
//   d(xi) d(phi) / (2 pi)) and azimuth phi, with the horizon N.L = 0 an exact integration bound; every
//   texel's estimated absolute error is reported and below `tolerance`. Method sampling (samples > 0): the
//   engines' way, `samples` Hammersley points per texel importance-sampled from D (Karis 2013's
//   IntegrateBRDF), deterministic; its error is what it is (the CLI reports it against the quadrature).
// - Same options, same bits, any thread count. size in [1, 4096], samples in [0, 2^24].
#pragma once

#include <cstdint>
#include <vector>

namespace shadelab {

struct DfgOptions {
  int size = 128;
  bool multiscatter = false;
  int samples = 0;             // 0: quadrature (dfg_gauss, or dfg_quadrature when adaptive); > 0: Hammersley sampling
  bool adaptive = false;       // the adaptive quadrature to `tolerance` instead of the fixed rule (the reference)
  double tolerance = 1e-6;     // absolute error per texel and channel (adaptive quadrature)
};

struct DfgTable {
  int size = 0;
  bool multiscatter = false;
  std::vector<double> texels;       // size * size * 3, row-major (row = roughness), channels A, B, A + B | 0
  double max_error_estimate = 0.0;  // quadrature: the largest per-texel error estimate; sampling: 0 (unknown)
  std::int64_t evaluations = 0;     // integrand evaluations (quadrature) or samples (sampling), in total

  double at(int i, int j, int c) const {
    return texels[(static_cast<std::size_t>(j) * static_cast<std::size_t>(size) + static_cast<std::size_t>(i)) * 3 +
                  static_cast<std::size_t>(c)];
  }
};

// A and B at one (mu, alpha) by the quadrature described above; error_out receives the larger of the two
// error estimates, evaluations_out the integrand calls. mu in (0, 1], alpha > 0.
struct DfgValue {
  double a = 0.0;
  double b = 0.0;
  double error = 0.0;
  std::int64_t evaluations = 0;
};
DfgValue dfg_quadrature(double mu, double alpha, double tolerance = 1e-6);

// The same A and B by a fixed product Gauss-Legendre rule in the same measure (dfg.cpp says which variables
// and panels): no error control of its own, its error measured against dfg_quadrature instead (dfg_test.cpp,
// docs/envmap.md). The node counts are per texel; `evaluations` counts the nodes.
struct DfgGaussRule {
  int phi_outer = 6;           // nodes on each of phi in [0, pi/3] and [2 pi/3, pi]
  int phi_middle = 12;         // nodes over cos(phi) in [-1/2, 1/2], in tau (cos(phi) = eps sinh(tau)), at least
  double phi_middle_per_tau = 3.3;  // and this many per unit of tau's range (it grows as ln(sin(theta_v) / N.V))
  int w_core = 16;             // nodes on w in [0, min(w_h, core_end)]
  int w_tail = 8;              // nodes on [core_end, w_h] where the lobe's core ends before the horizon layer
  int w_horizon = 8;           // nodes on [w_h, w_max], the horizon layer l.z < horizon_layer alpha
  double core_end = 3.0;       // w at the end of the core panel (xi = 1 - e^-9)
  double horizon_layer = 2.0;  // the horizon layer's depth in l.z, in units of alpha
};
DfgValue dfg_gauss(double mu, double alpha, const DfgGaussRule& rule = {});
// The default rule with 1.5 times its nodes in every direction: bake_dfg's error estimate is the difference to it.
DfgGaussRule dfg_gauss_check_rule();
// The same by `samples` Hammersley points importance-sampled from D cos(theta_h).
DfgValue dfg_sampled(double mu, double alpha, int samples);

// The first moments of the A and B lobes, the weights (1 - Fc) D G2 / (4 N.V) and Fc D G2 / (4 N.V) over l in
// the upper hemisphere (the integrands of A and B above), in the local frame n = +Z, v = (sin theta_v, 0, mu),
// R = (-sin theta_v, 0, mu): for part k (0 = A, 1 = B) its integral (= dfg_quadrature's a, b), its mean
// direction m_k = integral w_k l dl / integral w_k dl as the angle from n toward R (radians, in the plane of
// n and v; negative: past n, away from R), and its spread 1 - |m_k| = integral w_k (1 - l.m_k/|m_k|) dl /
// integral w_k dl (taken in a second pass, with 1 - l.d = |l - d|^2 / 2, so that it keeps its relative
// precision for the thinnest lobes). Used by the split sum's lobe-matched lookup (split_sum_lobes.h).
// rel_tol: relative tolerance of every integral, abs_tol its absolute floor (B at near-normal view on smooth
// surfaces is as small as 1e-9: a floor of 1e-10 leaves its moments loose there). mu in (0, 1], alpha > 0.
struct DfgLobeMoments {
  double weight[2] = {0.0, 0.0};
  double angle[2] = {0.0, 0.0};
  double spread[2] = {0.0, 0.0};
};
DfgLobeMoments dfg_lobe_moments(double mu, double alpha, double rel_tol = 1e-7, double abs_tol = 1e-10);
// The same moments by dfg_gauss's fixed rule (both passes over the same nodes): what the lobe table uses, its
// error against dfg_lobe_moments measured in split_sum_lobes_test.cpp.
DfgLobeMoments dfg_lobe_moments_gauss(double mu, double alpha, const DfgGaussRule& rule = {});

// Throws std::invalid_argument naming the option when size or samples is out of range or tolerance <= 0.
DfgTable bake_dfg(const DfgOptions& options);

// A coordinate x in [0, 1] of a table of n texel centres (i + 0.5) / n, as a GPU's bilinear sampler reads it
// (clamped to the edge texels; NaN reads texel 0): the two texels around it and the weight of the second.
struct TexelLerp {
  int i0 = 0;
  int i1 = 0;
  double t = 0.0;
};
TexelLerp texel_lerp(double x, int n);

// A and B at (N.V = mu, perceptual roughness r) read from the table as a GPU's bilinear sampler reads the
// texture at coordinates (mu, r): between the four nearest texel centres, clamped to the edge texels (so mu
// and r below half a texel read the first column / row). What the game renderer's split-sum uses: the kernel text kernels/game_ibl.sl dfg_read (mu or r not finite reads as 0).
struct DfgAb {
  double a = 0.0;
  double b = 0.0;
};
DfgAb dfg_lookup(const DfgTable& table, double mu, double roughness);

}  // namespace shadelab
