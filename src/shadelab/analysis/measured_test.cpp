// The measured model's sampler (brdf/measured.h) on tables the virtual gonioreflectometer wrote (brdf/merl.h):
// chi-square over 24 (table, theta) configurations with a Sidak correction, the pdf's integral, the sampled pdf and
// weight against pdf() and eval(), and the mean weight against the albedo by quadrature (independent of sample()).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadelab/analysis/chi_square.h"
#include "shadelab/analysis/test_brdfs.h"
#include "shadelab/brdf/measured.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

using testing::view;

struct Table {
  std::string name;
  std::shared_ptr<const MeasuredBrdf> brdf;
};

// Twelve tables: diffuse, glossy and sharp, coloured, anisotropy averaged out by the binning (ward measured at
// phi_h = 0), a retro-reflective Lafortune lobe.
const std::vector<Table>& tables() {
  static const std::vector<Table> t = [] {
    const std::vector<std::pair<std::string, ParamAssignments>> models = {
        {"lambert", {{"kd", "0.8"}}},
        {"ggx", {{"roughness", "0.1"}, {"kd", "0"}, {"f0", "0.9"}}},
        {"ggx", {{"roughness", "0.3"}, {"kd", "0.2,0.4,0.6"}, {"f0", "0.04"}}},
        {"ggx", {{"roughness", "0.8"}, {"kd", "0.1"}, {"f0", "0.5"}}},
        {"cook-torrance", {{"kd", "0.1"}, {"ks", "0.6"}, {"m", "0.2"}}},
        {"phong-modified", {{"kd", "0.3"}, {"ks", "0.5"}, {"n", "40"}}},
        {"blinn-phong-modified", {{"kd", "0.05"}, {"ks", "0.9"}, {"n", "300"}}},
        {"ward", {{"kd", "0.2"}, {"ks", "0.3"}, {"alpha", "0.15"}}},
        {"burley", {{"kd", "0.7,0.5,0.3"}, {"roughness", "0.9"}}},
        {"filament", {{"base_color", "0.9,0.7,0.4"}, {"metallic", "1"}, {"perceptual_roughness", "0.45"}}},
        {"gltf", {{"metallic", "0"}, {"roughness", "0.5"}, {"sheen_color", "0.5"}, {"sheen_roughness", "0.4"}}},
        {"wrapped-diffuse", {{"kd", "0.6"}, {"w", "0.3"}}},
    };
    std::vector<Table> out;
    for (const auto& [name, p] : models) {
      auto f = make_brdf(name, p);
      if (!f) throw std::runtime_error(f.error().message);
      out.push_back({name, std::make_shared<const MeasuredBrdf>(std::make_shared<const MerlTable>(measure_merl(**f)))});
    }
    return out;
  }();
  return t;
}

constexpr double thetas[] = {0.0, 35.0, 65.0, 85.0};

// Six of the twelve tables (every one goes through the same piecewise-constant sampler; these span the diffuse,
// the sharpest, the coloured, the anisotropic and the sheen tables): 24 configurations in about 14 s, where all 48
// took 30 s of the suite's budget.
constexpr std::size_t chi_square_tables[] = {0, 1, 2, 6, 7, 10};

TEST(MeasuredSamplers, ChiSquareOverTwentyFourConfigurations) {
  const int tests = static_cast<int>(std::size(chi_square_tables) * std::size(thetas));
  ASSERT_GE(tests, 24);
  const double level = sidak_significance(0.01, tests);
  // Bins on the sampler's own cell boundaries (8 x 32 over the upper hemisphere: 8 x 4 of its 64 x 128 cells each;
  // the view's azimuth is 0). The per-cell quadrature to 3e-3 (about 1 of ~400 expected counts, against a noise of
  // 20): the density jumps inside each bin, and adaptive quadrature to the default 1e-5 took minutes.
  ChiSquareOptions o;
  o.samples = 100'000;
  o.cos_theta_bins = 16;
  o.phi_bins = 32;
  o.cell_rel_tol = 3e-3;
  double lowest = 1.0;
  for (std::size_t index : chi_square_tables) {
    const Table& t = tables().at(index);
    for (double th : thetas) {
      const ChiSquareResult r = chi_square_test(*t.brdf, view(th), o);
      lowest = std::min(lowest, r.p_value);
      EXPECT_GE(r.p_value, level) << "measured " << t.name << " theta " << th << ": statistic " << r.statistic;
    }
  }
  std::printf("[ measured ] chi-square: %d configurations, lowest p %.3g (Sidak level %.3g)\n", tests, lowest, level);
}

// The midpoint rule in (cos theta_i, phi_i) over the upper hemisphere (dw = dz dphi) on nz x nphi points: on a
// grid finer than and aligned with the sampler's 64 x 128 cells (the view at azimuth 0), each point lies inside
// one cell, so the piecewise-constant part is summed exactly and the rest (cosine, the table's smooth f) to the
// rule's accuracy. Adaptive quadrature chases the table's kinks and jumps for minutes instead.
template <typename F>
double hemisphere_sum(F&& fn, int nz, int nphi) {
  double sum = 0.0;
  for (int j = 0; j < nz; ++j) {
    const double z = (j + 0.5) / nz, s = std::sqrt(1.0 - z * z);
    for (int i = 0; i < nphi; ++i) {
      const double phi = (i + 0.5) / nphi * 2.0 * pi;
      sum += fn(Vec3{s * std::cos(phi), s * std::sin(phi), z});
    }
  }
  return sum * (2.0 * pi) / (static_cast<double>(nz) * nphi);
}

TEST(MeasuredSamplers, PdfIntegratesToOneAndWeightsAreFCosOverPdf) {
  for (const auto& t : tables()) {
    for (double th : {0.0, 70.0}) {
      const Vec3 wo = view(th);
      const double integral = hemisphere_sum([&](const Vec3& wi) { return t.brdf->pdf(wi, wo); }, 512, 1024);
      EXPECT_NEAR(integral, 1.0, 1e-5) << t.name << " theta " << th;
      const SampleConsistency c = sample_consistency(*t.brdf, wo, 20'000);
      EXPECT_LE(c.max_pdf_error, 1e-6) << t.name;
      EXPECT_LE(c.max_weight_error, 1e-6) << t.name;
      EXPECT_EQ(c.non_finite, 0u) << t.name;
      EXPECT_EQ(c.below_horizon, 0u) << t.name;
    }
  }
}

// Independent of sample(): the mean weight (green) equals the albedo by the midpoint sum within 5 standard errors
// (plus the sum's own error, 1e-4).
TEST(MeasuredSamplers, MeanWeightIsTheAlbedo) {
  for (std::size_t k : {0u, 2u, 3u, 9u}) {
    for (double th : {20.0, 75.0}) {
      const Vec3 wo = view(th);
      const MeasuredBrdf& f = *tables()[k].brdf;
      const double albedo = hemisphere_sum([&](const Vec3& wi) { return f.eval(wi, wo).g * wi.z; }, 512, 1024);
      Pcg32 rng(99);
      double sum = 0.0, sum2 = 0.0;
      const int n = 100'000;
      for (int i = 0; i < n; ++i) {
        const BrdfSample s = f.sample(wo, {rng.next_double(), rng.next_double()}, rng.next_double());
        sum += s.weight.g;
        sum2 += s.weight.g * s.weight.g;
      }
      const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
      EXPECT_NEAR(mean, albedo, 5.0 * se + 1e-4) << tables()[k].name << " theta " << th;
    }
  }
}

}  // namespace
}  // namespace shadelab
