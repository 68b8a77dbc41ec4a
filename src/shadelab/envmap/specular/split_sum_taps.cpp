// shadelab split-sum taps (split_sum_taps.h).
#include "shadelab/envmap/specular/split_sum_taps.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shadelab/brdf/microfacet.h"
#include "shadelab/core/constants.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/sampling/sobol.h"

namespace shadelab {

namespace {

// Tap i of n for wo at GGX alpha (split_sum_taps.h).
SplitSumTap make_tap(const Vec3& wo, double alpha, int i, int n) {
  SplitSumTap t;
  if (!(wo.z > 0.0)) return t;  // a view below the (shading) horizon: no tap weighs anything
  // Hammersley point i of n: ((i + 1/2)/n, radical inverse of i), the latter Sobol's dimension 0.
  const Vec2 u{(i + 0.5) / n, radical_inverse(static_cast<std::uint32_t>(i))};
  const Vec3 h = sample_ggx_vndf_bounded(wo, u, alpha, alpha);
  const double vh = dot(wo, h);
  t.l = h * (2.0 * vh) - wo;  // reflect(wo, h)
  if (!(t.l.z > 0.0) || !(vh > 0.0)) return t;
  const double p = ggx_vndf_bounded_pdf(t.l, wo, alpha, alpha);
  if (!(p > 0.0)) return t;
  // f cos / p with f cos = D G2 / (4 N.V) per unit F, split by Schlick's Fc = (1 - v.h)^5 (dfg.h), the
  // kernels' F_schlick at f0 = 0.
  const double w = D_ggx(h.z, alpha) * G2_ggx_correlated(t.l, wo, alpha, alpha) / (4.0 * wo.z * p);
  const double fc = kernel::F_schlick(vh, 0.0);
  t.weight_a = w * (1.0 - fc);
  t.weight_b = w * fc;
  // The tap's share of solid angle 1 / (n p), covered by a chain lobe of solid angle 4 pi alpha_i^2.
  const double alpha_i = std::sqrt(1.0 / (n * p * 4.0 * pi));
  t.roughness = std::min(std::sqrt(alpha_i), 1.0);
  return t;
}

void check_count(int n) {
  if (n < 1 || n > split_sum_taps_max) throw std::invalid_argument("split-sum taps: the tap count must be in [1, 1024]");
}

}  // namespace

void split_sum_taps(const Vec3& wo, double roughness, std::span<SplitSumTap> out) {
  const auto n = static_cast<int>(out.size());
  check_count(n);
  const double alpha = std::max(kernel::alpha_from_roughness(roughness), 1e-4);
  for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = make_tap(wo, alpha, i, n);
}

SplitSumReads split_sum_filtered_reads(const GgxPrefilteredCube& chain, const Frame& frame, const Vec3& wo,
                                       double roughness, int taps) {
  check_count(taps);
  const double alpha = std::max(kernel::alpha_from_roughness(roughness), 1e-4);
  if (chain.levels.empty()) return {};
  // The chain bound once for all the taps; each tap is the kernel's chain read (kernels/game_ibl.sl).
  const GgxChainTexels c_texels(chain);
  const kernel::IblTexels texels = c_texels.texels();
  const kernel::IblBinding bind(texels);
  const auto read = [&](const Vec3& dir, double r) -> Rgb {
    return kernel::ggx_chain_read(dir, ggx_chain_roughness(r), texels.cube_count, c_texels.mapping);
  };
  Rgb sum_a, sum_b;
  double wa = 0.0, wb = 0.0;
  for (int i = 0; i < taps; ++i) {
    const SplitSumTap tap = make_tap(wo, alpha, i, taps);
    if (tap.weight_a <= 0.0 && tap.weight_b <= 0.0) continue;
    const Rgb c = read(frame.to_world(tap.l), tap.roughness);
    sum_a += c * tap.weight_a;
    sum_b += c * tap.weight_b;
    wa += tap.weight_a;
    wb += tap.weight_b;
  }
  Rgb along_r;  // a part with no weight reads the chain along R (the mirror direction, local (-x, -y, z))
  if (!(wa > 0.0) || !(wb > 0.0)) along_r = read(frame.to_world(Vec3{-wo.x, -wo.y, wo.z}), roughness);
  return {wa > 0.0 ? sum_a * (1.0 / wa) : along_r, wb > 0.0 ? sum_b * (1.0 / wb) : along_r};
}

}  // namespace shadelab
