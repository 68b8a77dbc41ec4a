// The sheen lobe (kernels/sheen.sl) and its albedo table (kernels/tables.cpp): D_charlie's normalization, the
// fitted Lambda against Estevez & Kulla's published coefficients, closed-form albedos, and the table's
// interpolation error against a converged integral computed another way (adaptive in both angles, over the
// kernel's D V: not the table's quadrature).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "shadelab/kernels/kernels.h"
#include "shadelab/kernels/tables.h"
#include "shadelab/numeric/quadrature.h"

namespace shadelab::kernel {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Projected-area normalization: integral of D(h) cos(theta_h) d(omega_h) = 1 (the lobe's defining property).
TEST(Sheen, CharlieDistributionIsNormalized) {
  for (double r : {0.07, 0.1, 0.3, 0.6, 1.0}) {
    const double alpha = sheen_alpha(r);
    QuadratureOptions o;
    o.rel_tol = 1e-12;
    const QuadratureResult q = integrate(
        [&](double t) { return 2.0 * kPi * D_charlie(std::cos(t), alpha) * std::cos(t) * std::sin(t); }, 0.0, 0.5 * kPi, o);
    EXPECT_NEAR(q.value, 1.0, 1e-9) << "r " << r;
  }
}

// Estevez & Kulla 2017, table 1 and eq. 3, re-evaluated here from their published numbers: L(x) = a / (1 + b x^c)
// + d x + e with the r = 0 row (25.3245, 3.32435, 0.16801, -1.27393, -4.85967) and the r = 1 row (21.5473,
// 3.82987, 0.19823, -1.97760, -4.32054), interpolated with (1 - r)^2 (their r is the D's alpha).
TEST(Sheen, LambdaIsEstevezKullasFit) {
  const double p0[5] = {25.3245, 3.32435, 0.16801, -1.27393, -4.85967};
  const double p1[5] = {21.5473, 3.82987, 0.19823, -1.97760, -4.32054};
  for (double alpha : {0.0049, 0.09, 0.36, 1.0}) {
    const double t = (1.0 - alpha) * (1.0 - alpha);
    double c[5];
    for (int k = 0; k < 5; ++k) c[k] = t * p0[k] + (1.0 - t) * p1[k];
    const auto l = [&](double x) { return c[0] / (1.0 + c[1] * std::pow(x, c[2])) + c[3] * x + c[4]; };
    for (double mu : {0.01, 0.2, 0.49, 0.51, 0.8, 1.0}) {
      const double expected = mu < 0.5 ? std::exp(l(mu)) : std::exp(2.0 * l(0.5) - l(1.0 - mu));
      EXPECT_NEAR(sheen_lambda(mu, alpha), expected, 1e-12 * expected) << "alpha " << alpha << " mu " << mu;
    }
    // The two branches meet at mu = 0.5.
    EXPECT_NEAR(sheen_lambda(0.5 - 1e-12, alpha), sheen_lambda(0.5, alpha), 1e-9 * sheen_lambda(0.5, alpha));
  }
  // Charlie's visibility is the Smith form 1 / ((1 + Lambda(wo) + Lambda(wi)) 4 N.L N.V), symmetric.
  const double a = 0.2;
  EXPECT_DOUBLE_EQ(V_sheen_charlie(0.3, 0.7, a), V_sheen_charlie(0.7, 0.3, a));
  EXPECT_NEAR(V_sheen_charlie(0.3, 0.7, a), 1.0 / ((1.0 + sheen_lambda(0.3, a) + sheen_lambda(0.7, a)) * 4.0 * 0.21), 1e-15);
  EXPECT_DOUBLE_EQ(V_sheen_ashikhmin(0.3, 0.7), 1.0 / (4.0 * (0.3 + 0.7 - 0.21)));
}

// Closed forms at normal incidence with the ashikhmin visibility (V = 1/4 at N.V = 1), h = the bisector, theta_h =
// theta_i / 2: E = (2 + 1/a)/4 integral_0^{pi/2} sin t cos t sin(t/2)^(1/a) dt. For a = 1: 3/4 (2 sqrt 2 / 15) =
// sqrt(2) / 10; for a = 1/2 (sin^2(t/2) = (1 - cos t)/2): integral_0^1 c (1 - c) / 2 dc = 1/12.
TEST(Sheen, AlbedoMeetsClosedFormsAtNormalIncidence) {
  EXPECT_NEAR(sheen_directional_albedo(1.0, 1.0).e[SHEEN_VISIBILITY_ASHIKHMIN], std::sqrt(2.0) / 10.0, 1e-8);
  EXPECT_NEAR(sheen_directional_albedo(1.0, std::sqrt(0.5)).e[SHEEN_VISIBILITY_ASHIKHMIN], 1.0 / 12.0, 1e-8);
  // The table at its own nodes (mu = 1 is a column of every row, r = 1 the last row).
  EXPECT_NEAR(sheen_energy(SHEEN_VISIBILITY_ASHIKHMIN, 1.0, 1.0), std::sqrt(2.0) / 10.0, 1e-8);
}

// The converged directional albedo, computed independently of the table's quadrature: the kernel's D V cos over
// the hemisphere of wi by nested adaptive Gauss-Kronrod (integrate_directions, polar about +Z).
double converged_albedo(int visibility, double mu, double r) {
  const Vec3 wo{std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu};
  const double alpha = sheen_alpha(r);
  QuadratureOptions o;
  o.rel_tol = 1e-9;
  o.abs_tol = 1e-11;
  const VectorQuadratureResult q = integrate_directions(
      [&](const Vec3& wi, std::span<double> out) { out[0] = sheen_dv(visibility, wi, wo, alpha) * wi.z; }, 1,
      Vec3{0.0, 0.0, 1.0}, SphereRegion::upper, o);
  return q.value[0];
}

// The table's claim: |E_table - E| <= 1e-4 for r in [0.07, 1] and theta in [0, 85] degrees, and <= 3e-4 up to 89
// degrees, both visibilities, at the cell centres of every fourth row and eighth column (where interpolation is
// worst; 30 s of quadrature at every fourth column, CI's budget), on
// the grazing edges (85 and 89 degrees, and the first rows' centres) and at points of a 2D low-discrepancy sequence.
TEST(Sheen, TableInterpolationErrorBelow1e4) {
  const SheenEnergyTable& t = sheen_energy_table();
  for (double err : t.e_error) EXPECT_LE(err, 1e-7);
  double worst[2] = {0.0, 0.0};
  double worst_grazing = 0.0;
  const double mu_85 = std::cos(85.0 * kPi / 180.0);
  const auto check = [&](double mu, double r) {
    for (int v = 0; v < 2; ++v) {
      const double d = std::abs(sheen_energy(v, mu, r) - converged_albedo(v, mu, r));
      if (mu >= mu_85) {
        worst[v] = std::max(worst[v], d);
        EXPECT_LE(d, 1e-4) << "visibility " << v << " mu " << mu << " r " << r;
      } else {
        worst_grazing = std::max(worst_grazing, d);
        EXPECT_LE(d, 3e-4) << "visibility " << v << " mu " << mu << " r " << r;
      }
    }
  };
  for (int j = 0; j + 1 < t.rows; j += 4) {
    const double r = 0.5 * (t.roughness[static_cast<std::size_t>(j)] + t.roughness[static_cast<std::size_t>(j + 1)]);
    for (int i = 0; i + 1 < t.cols; i += 8) {
      const std::size_t c = static_cast<std::size_t>(j * t.cols + i);
      check(0.5 * (t.mu[c] + t.mu[c + 1]), r);
    }
    check(SHEEN_ENERGY_MU_MIN, r);
    check(mu_85, r);
  }
  for (int j = 0; j < 3; ++j) {  // the corner of lowest roughness, where E rises steepest at grazing
    const double r = 0.5 * (t.roughness[static_cast<std::size_t>(j)] + t.roughness[static_cast<std::size_t>(j + 1)]);
    for (double mu : {SHEEN_ENERGY_MU_MIN, 0.05, mu_85, 0.1}) check(mu, r);
  }
  for (int n = 0; n < 60; ++n) {  // a 2D Weyl sequence (R2, Roberts 2018): even, deterministic
    const double u = std::fmod(0.5 + n * 0.7548776662466927, 1.0);
    const double w = std::fmod(0.5 + n * 0.5698402909980532, 1.0);
    const double mu = SHEEN_ENERGY_MU_MIN + (1.0 - SHEEN_ENERGY_MU_MIN) * (n % 3 == 0 ? u * u * u : u);
    check(mu, SHEEN_ROUGHNESS_MIN + (1.0 - SHEEN_ROUGHNESS_MIN) * w);
  }
  std::printf("[ sheen    ] table interpolation error to 85 deg: charlie %.3g, ashikhmin %.3g; 85-89 deg: %.3g\n",
              worst[0], worst[1], worst_grazing);
  ::testing::Test::RecordProperty("max_error_charlie", std::to_string(worst[0]));
  ::testing::Test::RecordProperty("max_error_ashikhmin", std::to_string(worst[1]));
}

// Neither visibility is a Smith term of D_charlie: the lobe reflects more than it receives near grazing at low
// roughness (E > 1), and both tables say so; at normal incidence E is small.
TEST(Sheen, AlbedoExceedsOneNearGrazingAtLowRoughness) {
  const double mu = std::cos(89.0 * kPi / 180.0);
  EXPECT_GT(sheen_energy(SHEEN_VISIBILITY_CHARLIE, mu, 0.08), 1.0);
  EXPECT_GT(sheen_energy(SHEEN_VISIBILITY_ASHIKHMIN, mu, 0.08), 1.0);
  EXPECT_LT(sheen_energy(SHEEN_VISIBILITY_CHARLIE, 1.0, 0.5), 0.05);
}

}  // namespace
}  // namespace shadelab::kernel
