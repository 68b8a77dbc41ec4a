// Tests of the DFG table (dfg.h) against an independent integral: the same A and B integrated over the
// light direction l (not the half vector) with the library's generic hemisphere quadrature about the mirror
// direction, and with D, Smith's Lambda and Schlick's Fc written here from their papers, not taken from the
// kernels.
#include "shadelab/envmap/specular/dfg.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "shadelab/envmap/specular/ggx_test_formulas.h"
#include "shadelab/numeric/quadrature.h"

namespace shadelab {
namespace {


using test_formulas::ggx_d;
using test_formulas::ggx_lambda;

struct AB {
  double a;
  double b;
};

// A and B by integrating D G2 / (4 N.V) (1 - Fc, Fc) over the light direction l.
AB independent_dfg(double mu, double alpha) {
  const Vec3 v{std::sqrt(1.0 - mu * mu), 0.0, mu};
  QuadratureOptions options;
  options.rel_tol = 0.0;
  options.abs_tol = 2e-7;
  options.max_subdivisions = 20000;
  const auto r = integrate_directions(
      [&](const Vec3& l, std::span<double> out) {
        out[0] = out[1] = 0.0;
        if (l.z <= 0.0) return;
        Vec3 h{v.x + l.x, v.y + l.y, v.z + l.z};
        const double len = std::sqrt(dot(h, h));
        h = {h.x / len, h.y / len, h.z / len};
        const double vh = dot(v, h);
        const double g2 = 1.0 / (1.0 + ggx_lambda(mu, alpha) + ggx_lambda(l.z, alpha));  // Heitz 2014 eq. 99
        const double spec = ggx_d(h.z, alpha) * g2 / (4.0 * mu);
        const double fc = std::pow(1.0 - vh, 5.0);
        out[0] = (1.0 - fc) * spec;
        out[1] = fc * spec;
      },
      2, Vec3{-v.x, 0.0, v.z}, SphereRegion::upper, options);
  return {r.value[0], r.value[1]};
}

TEST(Dfg, EveryTexelOfASmallTableEqualsAnIndependentIntegral) {
  DfgOptions options;
  options.size = 8;
  options.multiscatter = true;
  const DfgTable t = bake_dfg(options);
  ASSERT_EQ(t.size, 8);
  EXPECT_LT(t.max_error_estimate, 2e-6);
  double worst = 0.0;
  for (int j = 0; j < t.size; ++j) {
    for (int i = 0; i < t.size; ++i) {
      const double mu = (i + 0.5) / t.size;
      const double r = (j + 0.5) / t.size;
      const AB ref = independent_dfg(mu, r * r);
      worst = std::max({worst, std::abs(t.at(i, j, 0) - ref.a), std::abs(t.at(i, j, 1) - ref.b)});
      EXPECT_NEAR(t.at(i, j, 0), ref.a, 2e-4) << "A at N.V " << mu << ", roughness " << r;
      EXPECT_NEAR(t.at(i, j, 1), ref.b, 2e-4) << "B at N.V " << mu << ", roughness " << r;
      EXPECT_EQ(t.at(i, j, 2), t.at(i, j, 0) + t.at(i, j, 1));
    }
  }
  RecordProperty("max_abs_difference", std::to_string(worst));
  std::printf("DFG 8x8 against the l-space integral: max |difference| %.3g\n", worst);
  EXPECT_LT(worst, 2e-5);  // the issue asks 2e-4; both integrals are far better
}

// The fixed rule (dfg_gauss, the table's default) against the adaptive quadrature to 1e-10: every texel of a
// 16 x 16 table, and the grazing columns and the edge rows of 128 and 4096 tables, where its error is largest.
// Measured on the whole 64 x 64 and 128 x 128 tables (docs/envmap.md): at most 2.0e-7 and 3.6e-7.
TEST(Dfg, TheFixedRuleIsWithinAMillionthOfTheAdaptiveQuadrature) {
  std::vector<std::pair<double, double>> texels;  // (N.V, roughness)
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) texels.emplace_back((i + 0.5) / 16, (j + 0.5) / 16);
  for (const int n : {128, 4096}) {
    for (const int k : {0, 1, 2, 5, n / 8, n / 2, n - 1}) {
      for (const int edge : {0, 1, n - 1}) {
        texels.emplace_back((edge + 0.5) / n, (k + 0.5) / n);  // a grazing (or normal-view) column
        texels.emplace_back((k + 0.5) / n, (edge + 0.5) / n);  // the smoothest (or roughest) row
      }
    }
  }
  std::vector<double> diff(texels.size());
  tbb::parallel_for(std::size_t{0}, texels.size(), [&](std::size_t q) {
    const auto [mu, r] = texels[q];
    const DfgValue fixed = dfg_gauss(mu, r * r), exact = dfg_quadrature(mu, r * r, 1e-10);
    diff[q] = std::max(std::abs(fixed.a - exact.a), std::abs(fixed.b - exact.b));
  });
  double worst = 0.0;
  for (std::size_t q = 0; q < texels.size(); ++q) {
    EXPECT_LT(diff[q], 1e-6) << "N.V " << texels[q].first << ", roughness " << texels[q].second;
    worst = std::max(worst, diff[q]);
  }
  RecordProperty("max_abs_difference", std::to_string(worst));
  std::printf("fixed rule against the adaptive quadrature at %zu texels: max |difference| %.3g\n", texels.size(), worst);
  // The table's error estimate (the difference to the 1.5x finer rule on a subset) is of the same size.
  DfgOptions options;
  options.size = 16;
  const DfgTable t = bake_dfg(options);
  EXPECT_GT(t.max_error_estimate, 0.0);
  EXPECT_LT(t.max_error_estimate, 1e-6);
}

TEST(Dfg, TheAdaptiveOptionIsTheFormerQuadrature) {
  DfgOptions options;
  options.size = 3;
  options.adaptive = true;
  options.tolerance = 1e-5;
  const DfgTable t = bake_dfg(options);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      const double r = (j + 0.5) / 3;
      const DfgValue v = dfg_quadrature((i + 0.5) / 3, r * r, 1e-5);
      EXPECT_EQ(t.at(i, j, 0), v.a);
      EXPECT_EQ(t.at(i, j, 1), v.b);
    }
  }
}

TEST(Dfg, AMirrorSurfaceGivesSchlicksFresnelAtTheViewAngle) {
  // alpha -> 0: D G2 / (4 N.V) is a delta at the mirror direction with G2 -> 1 and h = n, so
  // A = 1 - (1 - mu)^5 and B = (1 - mu)^5 (Schlick's Fresnel at N.V).
  for (double mu : {0.3, 0.6, 0.95}) {
    const DfgValue v = dfg_quadrature(mu, 1e-4);
    const double fc = std::pow(1.0 - mu, 5.0);
    EXPECT_NEAR(v.a, 1.0 - fc, 1e-5) << mu;
    EXPECT_NEAR(v.b, fc, 1e-5) << mu;
    const DfgValue g = dfg_gauss(mu, 1e-4);
    EXPECT_NEAR(g.a, 1.0 - fc, 1e-5) << mu;
    EXPECT_NEAR(g.b, fc, 1e-5) << mu;
  }
}

TEST(Dfg, ScaleAndBiasArePositiveAndTheAlbedoIsAtMostOne) {
  DfgOptions options;
  options.size = 16;
  options.multiscatter = true;
  const DfgTable t = bake_dfg(options);
  // (E_ss is not monotonic in roughness at grazing N.V, so only the bound is a law here.)
  for (int i = 0; i < t.size; ++i) {
    for (int j = 0; j < t.size; ++j) {
      EXPECT_GT(t.at(i, j, 0), 0.0);
      EXPECT_GT(t.at(i, j, 1), 0.0);
      EXPECT_LE(t.at(i, j, 2), 1.0 + 1e-9);
    }
  }
}

TEST(Dfg, HammersleySamplingConvergesToTheQuadrature) {
  // Karis 2013's sampled estimate: its error falls as the sample count grows (deterministic points).
  for (double r : {0.3, 0.7}) {
    const double mu = 0.5;
    const DfgValue q = dfg_quadrature(mu, r * r);
    const DfgValue s1 = dfg_sampled(mu, r * r, 256);
    const DfgValue s2 = dfg_sampled(mu, r * r, 65536);
    const double e1 = std::abs(s1.a - q.a) + std::abs(s1.b - q.b);
    const double e2 = std::abs(s2.a - q.a) + std::abs(s2.b - q.b);
    EXPECT_LT(e2, 1e-3) << r;
    EXPECT_LT(e2, e1) << r;
  }
}

TEST(Dfg, TheTableIsTheSameForAnyThreadCount) {
  DfgOptions options;
  options.size = 8;
  DfgTable one;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = bake_dfg(options);
  }
  const DfgTable two = bake_dfg(options);
  EXPECT_EQ(one.texels, two.texels);
  for (int k = 0; k < 8 * 8; ++k) EXPECT_EQ(one.texels[static_cast<std::size_t>(k) * 3 + 2], 0.0);
}

TEST(Dfg, OptionsOutOfRangeAreErrors) {
  DfgOptions o;
  o.size = 0;
  EXPECT_THROW(bake_dfg(o), std::invalid_argument);
  o.size = 5000;
  EXPECT_THROW(bake_dfg(o), std::invalid_argument);
  o.size = 8;
  o.samples = -1;
  EXPECT_THROW(bake_dfg(o), std::invalid_argument);
}

}  // namespace
}  // namespace shadelab
