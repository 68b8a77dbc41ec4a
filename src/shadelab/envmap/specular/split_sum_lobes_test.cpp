// Tests of the split sum's lobe-matched lookup (split_sum_lobes.h): the moments of the A and B lobes against
// an independent integral over the light direction l (D, Smith's Lambda and Schlick's Fc written here from
// their papers, the library's generic sphere quadrature, not the half-vector variables of dfg.cpp), the
// chain lobe's spread against an integral in t = R.l and its closed form at alpha = 1, its inverse, and the
// table against its texels.
#include "shadelab/envmap/specular/split_sum_lobes.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/envmap/specular/ggx_test_formulas.h"
#include "shadelab/numeric/quadrature.h"

namespace shadelab {
namespace {


using test_formulas::ggx_d;
using test_formulas::ggx_lambda;

struct Moments {
  double weight[2];
  Vec3 mean[2];
  double spread[2];
};

// The A and B lobes' integrals, mean directions and spreads over the whole sphere of l (zero below n).
Moments independent_moments(double mu, double alpha) {
  const Vec3 v{std::sqrt(1.0 - mu * mu), 0.0, mu};
  const Vec3 r{-v.x, 0.0, v.z};
  const auto lobes = [&](const Vec3& l, double w[2]) {
    w[0] = w[1] = 0.0;
    if (l.z <= 0.0) return;
    const Vec3 h = normalize(v + l);
    const double g2 = 1.0 / (1.0 + ggx_lambda(mu, alpha) + ggx_lambda(l.z, alpha));  // Heitz 2014 eq. 99
    const double spec = ggx_d(h.z, alpha) * g2 / (4.0 * mu);
    const double fc = std::pow(1.0 - dot(v, h), 5.0);  // Schlick 1994
    w[0] = (1.0 - fc) * spec;
    w[1] = fc * spec;
  };
  QuadratureOptions o;
  o.rel_tol = 1e-8;
  o.abs_tol = 1e-12;
  o.max_subdivisions = 40000;
  const auto first = integrate_sphere(
      [&](const Vec3& l, std::span<double> out) {
        double w[2];
        lobes(l, w);
        for (int k = 0; k < 2; ++k) {
          out[static_cast<std::size_t>(4 * k)] = w[k];
          out[static_cast<std::size_t>(4 * k + 1)] = w[k] * l.x;
          out[static_cast<std::size_t>(4 * k + 2)] = w[k] * l.y;
          out[static_cast<std::size_t>(4 * k + 3)] = w[k] * l.z;
        }
      },
      8, r, r, o);
  Moments m{};
  for (int k = 0; k < 2; ++k) {
    const auto at = [&](int i) { return first.value[static_cast<std::size_t>(4 * k + i)]; };
    m.weight[k] = at(0);
    m.mean[k] = Vec3{at(1), at(2), at(3)} * (1.0 / at(0));
  }
  const auto second = integrate_sphere(
      [&](const Vec3& l, std::span<double> out) {
        double w[2];
        lobes(l, w);
        for (int k = 0; k < 2; ++k) out[static_cast<std::size_t>(k)] = w[k] * (1.0 - dot(l, normalize(m.mean[k])));
      },
      2, r, r, o);
  for (int k = 0; k < 2; ++k) m.spread[k] = second.value[static_cast<std::size_t>(k)] / m.weight[k];
  return m;
}

TEST(SplitSumLobes, MomentsEqualAnIndependentIntegralOverTheLightDirection) {
  const struct {
    double mu, alpha;
  } cases[] = {{0.15, 0.3}, {0.2, 0.6}, {0.5, 0.5}, {0.1, 0.9}, {0.8, 0.2}, {0.35, 1.0}};
  for (const auto& c : cases) {
    SCOPED_TRACE(testing::Message() << "mu " << c.mu << " alpha " << c.alpha);
    const DfgLobeMoments got = dfg_lobe_moments(c.mu, c.alpha);
    const Moments want = independent_moments(c.mu, c.alpha);
    const DfgValue ab = dfg_quadrature(c.mu, c.alpha, 1e-8);
    const double theta_r = std::acos(c.mu);
    for (int k = 0; k < 2; ++k) {
      SCOPED_TRACE(k == 0 ? "A" : "B");
      EXPECT_NEAR(got.weight[k], want.weight[k], 1e-6 * want.weight[k] + 1e-9);
      EXPECT_NEAR(got.weight[k], k == 0 ? ab.a : ab.b, 1e-6 * got.weight[k] + 1e-8);
      EXPECT_NEAR(want.mean[k].y, 0.0, 1e-7);  // the lobes are symmetric about the plane of n and v
      const double angle = std::atan2(-want.mean[k].x, want.mean[k].z);
      EXPECT_NEAR(got.angle[k], angle, 1e-5);
      EXPECT_NEAR(got.spread[k], want.spread[k], 1e-5 * want.spread[k]);
      EXPECT_NEAR(got.spread[k], 1.0 - length(want.mean[k]), 1e-5 * want.spread[k]);
    }
    // At oblique view the A lobe leans from R toward n: its angle lies between n (0) and R (at alpha = 1 it
    // is nearly n: -0.017 rad, just past it, at mu 0.35).
    EXPECT_GT(got.angle[0], c.alpha < 1.0 ? 0.0 : -0.05);
    EXPECT_LT(got.angle[0], theta_r);
  }
}

// The chain lobe's spread in t = R.l directly: K(t) = D(h) t with cos^2(theta_h) = (1 + t) / 2, dl = 2 pi dt.
double independent_chain_spread(double alpha) {
  QuadratureOptions o;
  o.rel_tol = 1e-11;
  o.max_subdivisions = 40000;
  o.initial_intervals = 64;
  const auto k = [&](double t) { return ggx_d(std::sqrt(0.5 * (1.0 + t)), alpha) * t; };
  const double z0 = integrate(k, 0.0, 1.0, o).value;
  const double z1 = integrate([&](double t) { return k(t) * (1.0 - t); }, 0.0, 1.0, o).value;
  return z1 / z0;
}

TEST(SplitSumLobes, ChainSpreadEqualsAnIntegralInTheCosineAndOneThirdAtAlphaOne) {
  // alpha = 1: D = 1/pi everywhere, the lobe is t: mean t = (1/3) / (1/2) = 2/3.
  EXPECT_NEAR(ggx_chain_spread(1.0), 1.0 / 3.0, 1e-12);
  for (const double alpha : {0.03, 0.1, 0.25, 0.5, 0.8}) {
    SCOPED_TRACE(alpha);
    const double want = independent_chain_spread(alpha);
    EXPECT_NEAR(ggx_chain_spread(alpha), want, 1e-7 * want);
  }
}

TEST(SplitSumLobes, TheSpreadIsInvertedWithinAThousandth) {
  for (double alpha = 2e-4; alpha <= 1.0; alpha *= 1.37) {
    SCOPED_TRACE(alpha);
    EXPECT_NEAR(ggx_chain_alpha_for_spread(ggx_chain_spread(alpha)), alpha, 1e-3 * alpha);
  }
  EXPECT_EQ(ggx_chain_alpha_for_spread(0.4), 1.0);  // wider than the cosine lobe: the widest the chain has
  EXPECT_NEAR(ggx_chain_alpha_for_spread(1.0 / 3.0), 1.0, 1e-12);
}

TEST(SplitSumLobes, TheTableHoldsItsTexelsAndReadsThemBilinearly) {
  const SplitSumLobeTable& t = split_sum_lobe_table();
  ASSERT_EQ(t.size(), split_sum_lobe_size);
  const int n = t.size();
  for (const auto& [i, j] : {std::pair{0, 0}, std::pair{5, 20}, std::pair{31, 7}, std::pair{17, 31}}) {
    SCOPED_TRACE(testing::Message() << i << ", " << j);
    const double mu = (i + 0.5) / n, r = (j + 0.5) / n;
    const SplitSumLobes want = split_sum_lobes_at(mu, r);
    const SplitSumLobes got = split_sum_lobes(t, mu, r);
    EXPECT_DOUBLE_EQ(got.a.angle, want.a.angle);
    EXPECT_DOUBLE_EQ(got.a.roughness, want.a.roughness);
    EXPECT_DOUBLE_EQ(got.b.angle, want.b.angle);
    EXPECT_DOUBLE_EQ(got.b.roughness, want.b.roughness);
  }
  // A mirror (r = 0) reads the delta at R; halfway to the first row's centre, halfway to it.
  for (const double mu : {0.1, 0.5, 0.9}) {
    const SplitSumLobes m = split_sum_lobes(t, mu, 0.0), row0 = split_sum_lobes(t, mu, 0.5 / n);
    const SplitSumLobes half = split_sum_lobes(t, mu, 0.25 / n);
    EXPECT_NEAR(m.a.angle, std::acos(mu), 1e-12);
    EXPECT_NEAR(m.b.angle, std::acos(mu), 1e-12);
    EXPECT_EQ(m.a.roughness, 0.0);
    EXPECT_EQ(m.b.roughness, 0.0);
    EXPECT_NEAR(half.a.roughness, 0.5 * row0.a.roughness, 1e-12);
    EXPECT_NEAR(half.b.angle, 0.5 * (std::acos(mu) + row0.b.angle), 1e-12);
  }
  // Halfway between two texel centres in N.V: the mean of the two.
  const SplitSumLobes lo = split_sum_lobes(t, 3.5 / n, 9.5 / n), hi = split_sum_lobes(t, 4.5 / n, 9.5 / n);
  const SplitSumLobes mid = split_sum_lobes(t, 4.0 / n, 9.5 / n);
  EXPECT_NEAR(mid.a.angle, 0.5 * (lo.a.angle + hi.a.angle), 1e-12);
  EXPECT_NEAR(mid.b.roughness, 0.5 * (lo.b.roughness + hi.b.roughness), 1e-12);
}

TEST(SplitSumLobes, BetweenTexelCentresTheTableIsCloseToTheMoments) {
  // The bilinear read's own error, at the middle of the cells (both coordinates half a texel off the
  // centres) over the table but its last cells in N.V (measured 0.021 rad and 0.013 at worst). In those
  // (N.V ~ 0.97) B's mean direction swings from past R to n (at normal view its ring of grazing half vectors is
  // centred on n): the read there is off by up to 0.19 rad and 0.08 in roughness, in a part whose weight B
  // is below 2% of A + B.
  const SplitSumLobeTable& t = split_sum_lobe_table();
  t.all();  // every row at once, in parallel (the reads below would compute them one by one)
  const int n = t.size();
  double worst_angle = 0.0, worst_rough = 0.0;
  for (int j = 0; j + 1 < n; j += 3) {
    for (int i = 0; i + 2 < n; i += 3) {
      const double mu = (i + 1.0) / n, r = (j + 1.0) / n;
      const SplitSumLobes got = split_sum_lobes(t, mu, r), want = split_sum_lobes_at(mu, r);
      worst_angle = std::max({worst_angle, std::abs(got.a.angle - want.a.angle), std::abs(got.b.angle - want.b.angle)});
      worst_rough = std::max({worst_rough, std::abs(got.a.roughness - want.a.roughness),
                              std::abs(got.b.roughness - want.b.roughness)});
    }
  }
  std::printf("bilinear read at cell middles: worst angle %.3g rad, worst roughness %.3g\n", worst_angle, worst_rough);
  EXPECT_LT(worst_angle, 0.03);
  EXPECT_LT(worst_rough, 0.02);
  // The last column's B weight against A + B, at its worst row.
  double worst_share = 0.0;
  for (int j = 0; j < n; ++j) {
    const DfgValue v = dfg_quadrature((n - 0.5) / n, std::pow((j + 0.5) / n, 2.0), 1e-7);
    worst_share = std::max(worst_share, v.b / (v.a + v.b));
  }
  EXPECT_LT(worst_share, 0.02);
}

// The table's moments by the fixed rule (dfg_lobe_moments_gauss with split_sum_lobe_rule) against the adaptive
// ones at relative tolerance 1e-9 (no absolute floor), as table texels: every 3rd texel of the 32 x 32 table
// and its first row and last column (grazing to normal view on the smoothest surfaces). Measured over the whole
// table: angle_a 1.1e-7 rad, roughness_a 3.3e-7, angle_b 1.2e-4 rad (at N.V 0.98, r 0.11, where B is a ring of
// grazing half vectors and below 1e-4 of A + B), roughness_b 1.6e-6.
TEST(SplitSumLobes, TheFixedRuleTexelsEqualTheAdaptiveMoments) {
  const int n = split_sum_lobe_size;
  std::vector<std::pair<int, int>> texels;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if ((i % 3 == 0 && j % 3 == 0) || j == 0 || i == n - 1) texels.emplace_back(i, j);
    }
  }
  std::vector<std::array<double, 4>> diff(texels.size());
  tbb::parallel_for(std::size_t{0}, texels.size(), [&](std::size_t q) {
    const double mu = (texels[q].first + 0.5) / n, r = (texels[q].second + 0.5) / n;
    const SplitSumLobes got = split_sum_lobes_at(mu, r);
    const DfgLobeMoments m = dfg_lobe_moments(mu, std::max(r * r, 1e-4), 1e-9, 0.0);
    // As split_sum_lobes_at makes texels of moments: the matched chain roughness, B no rougher than r.
    const double ra = std::sqrt(ggx_chain_alpha_for_spread(m.spread[0]));
    const double rb = std::min(std::sqrt(ggx_chain_alpha_for_spread(m.spread[1])), r);
    diff[q] = {std::abs(got.a.angle - m.angle[0]), std::abs(got.a.roughness - ra), std::abs(got.b.angle - m.angle[1]),
               std::abs(got.b.roughness - rb)};
  });
  std::array<double, 4> worst{};
  for (std::size_t q = 0; q < texels.size(); ++q) {
    for (int c = 0; c < 4; ++c) worst[static_cast<std::size_t>(c)] = std::max(worst[static_cast<std::size_t>(c)], diff[q][static_cast<std::size_t>(c)]);
  }
  std::printf("lobe texels, fixed rule against adaptive moments: angle_a %.2g, roughness_a %.2g, angle_b %.2g, roughness_b %.2g\n",
              worst[0], worst[1], worst[2], worst[3]);
  EXPECT_LT(worst[0], 1e-6);
  EXPECT_LT(worst[1], 1e-5);
  EXPECT_LT(worst[2], 3e-4);  // the adaptive moments at 1e-5, the table's former method: 2.1e-4
  EXPECT_LT(worst[3], 1e-5);
}

TEST(SplitSumLobes, RowsComputedAtFirstReadAreTheSameFromManyThreads) {
  // A small table of its own, read from every thread at once through the bilinear lookup (each read may be
  // the first of its rows): every texel as split_sum_lobes_at computes it, whichever thread filled its row.
  const SplitSumLobeTable t(6);
  tbb::parallel_for(0, 600, [&](int k) {
    const double mu = (k % 25 + 0.5) / 25.0, r = (k / 25 % 24 + 0.5) / 24.0;
    const SplitSumLobes l = split_sum_lobes(t, mu, r);
    EXPECT_TRUE(std::isfinite(l.a.angle) && std::isfinite(l.b.roughness));
  });
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 6; ++i) {
      const SplitSumLobes want = split_sum_lobes_at((i + 0.5) / 6.0, (j + 0.5) / 6.0);
      EXPECT_EQ(t.at(i, j).a.angle, want.a.angle);
      EXPECT_EQ(t.at(i, j).b.roughness, want.b.roughness);
    }
  }
  EXPECT_EQ(t.all().size(), 36u);
}

TEST(SplitSumLobes, EachLobeIsReadWhereAndAsWideAsItsMoments) {
  // The lookup reproduces each lobe's mean vector: the chain lobe about d at the matched roughness has mean
  // (1 - spread) d, and a linear environment's average over a lobe is its value at that mean.
  for (const auto& [mu, r] : {std::pair{0.2, 0.5}, std::pair{0.4, 0.75}, std::pair{0.15, 0.35}}) {
    SCOPED_TRACE(testing::Message() << mu << ", " << r);
    const SplitSumLobes s = split_sum_lobes_at(mu, r);
    const Moments m = independent_moments(mu, r * r);
    const SplitSumLobe* parts[2] = {&s.a, &s.b};
    for (int k = 0; k < 2; ++k) {
      const double len = 1.0 - ggx_chain_spread(parts[k]->roughness * parts[k]->roughness);
      const Vec3 d{-std::sin(parts[k]->angle), 0.0, std::cos(parts[k]->angle)};  // n = +Z, R toward -X
      EXPECT_NEAR(len * d.x, m.mean[k].x, 2e-3);
      EXPECT_NEAR(len * d.z, m.mean[k].z, 2e-3);
    }
    // At grazing view B (the Fresnel part) is narrower than A, and both lie on R's side of n.
    EXPECT_LT(s.b.roughness, s.a.roughness);
    EXPECT_GT(s.b.angle, s.a.angle);
  }
}

}  // namespace
}  // namespace shadelab
