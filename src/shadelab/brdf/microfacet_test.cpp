#include "shadelab/brdf/microfacet.h"

#include <gtest/gtest.h>

#include <functional>

namespace shadelab {
namespace {

// Midpoint rule in theta on [0, pi/2] with many cells: an independent check of a normalization.
double integrate_theta(const std::function<double(double)>& f, int cells = 200000) {
  const double h = 0.5 * pi / cells;
  double sum = 0.0;
  for (int i = 0; i < cells; ++i) sum += f((i + 0.5) * h);
  return sum * h;
}

TEST(Microfacet, BeckmannIsProjectedAreaNormalized) {
  for (double m : {0.05, 0.2, 0.5, 1.0}) {
    const double v = two_pi * integrate_theta([m](double t) { return D_beckmann(std::cos(t), m) * std::cos(t) * std::sin(t); });
    EXPECT_NEAR(v, 1.0, 1e-6) << m;
  }
}

TEST(Microfacet, BlinnPhongRowsAreNormalized) {
  for (double n : {0.0, 1.0, 20.0, 500.0}) {
    const double hf = two_pi * integrate_theta([n](double t) { return D_blinn_phong(std::cos(t), n) * std::cos(t) * std::sin(t); });
    const double ndf = two_pi * integrate_theta([n](double t) { return D_blinn_phong_ndf(std::cos(t), n) * std::sin(t); });
    EXPECT_NEAR(hf, 1.0, 1e-6) << n;
    EXPECT_NEAR(ndf, 1.0, 1e-6) << n;
  }
}

TEST(Microfacet, ExponentRoughnessRoundTrip) {
  for (double n : {0.0, 2.0, 48.0, 1000.0}) EXPECT_NEAR(exponent_from_beckmann_m(beckmann_m_from_exponent(n)), n, 1e-9 * (n + 1));
  EXPECT_NEAR(beckmann_m_from_exponent(48.0), 0.2, 1e-15);
}

TEST(Microfacet, SmithLambdaMatchesItsIntegralDefinition) {
  // Lambda(w) = (1/cos) integral over the microsurface of max(0, -w.h) D(h) ... ; here via the 1D slope form:
  // Lambda = integral_{a}^{inf} (q - a) P(q) dq / a with the Beckmann slope density, a = cot(theta)/m
  // (Smith 1967; Walter et al. 2007 eq. 27 integrates to the closed form).
  for (double m : {0.1, 0.4}) {
    for (double theta_deg : {30.0, 60.0, 85.0}) {
      const double c = std::cos(theta_deg * pi / 180.0);
      const double mu = c / std::sqrt(1 - c * c);  // cot(theta)
      // Slopes q of the 1D Beckmann marginal: p(q) = exp(-q^2/m^2)/(m sqrt(pi)).
      const int cells = 400000;
      const double qmax = 12 * m + mu;
      const double h = (qmax - mu) / cells;
      double sum = 0;
      for (int i = 0; i < cells; ++i) {
        const double q = mu + (i + 0.5) * h;
        sum += (q - mu) * std::exp(-q * q / (m * m)) / (m * std::sqrt(pi));
      }
      const double lambda = sum * h / mu;
      EXPECT_NEAR(lambda_beckmann(c, m), lambda, 1e-6 * std::max(1.0, lambda)) << m << " " << theta_deg;
    }
  }
}

TEST(Microfacet, SmithGIsBetweenZeroAndOne) {
  for (double c : {0.01, 0.3, 0.9, 1.0}) {
    const double g = G_smith_beckmann(c, 0.7, 0.3);
    EXPECT_GT(g, 0.0);
    EXPECT_LE(g, 1.0);
  }
  EXPECT_DOUBLE_EQ(G_smith_beckmann(1.0, 1.0, 0.3), 1.0);
}

TEST(Microfacet, BeckmannSamplingHasDensityDcos) {
  // The CDF of theta_h under D cos is 1 - exp(-tan^2/m^2): check the inverse at a few u.
  const double m = 0.3;
  for (double u : {0.1, 0.5, 0.9}) {
    const Vec3 h = sample_beckmann_h({u, 0.2}, m);
    const double tan2 = (1 - h.z * h.z) / (h.z * h.z);
    EXPECT_NEAR(1 - std::exp(-tan2 / (m * m)), u, 1e-12);
  }
}

}  // namespace
}  // namespace shadelab
