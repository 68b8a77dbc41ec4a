#include "shadelab/numeric/quadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "shadelab/core/constants.h"

namespace shadelab {
namespace {

// One interval (no subdivision): the 15-point Kronrod rule integrates polynomials up to degree 22 exactly,
// and its embedded 7-point Gauss rule up to degree 13, so the error estimate is at the roundoff floor for
// x^13 and clearly above it for x^14. This pins every node and both weight sets.
TEST(Quadrature, KronrodAndGaussDegreesOfExactness) {
  QuadratureOptions one;
  one.max_subdivisions = 0;
  for (int k = 0; k <= 22; ++k) {
    const auto r = integrate([k](double x) { return std::pow(x, k); }, 0.0, 1.0, one);
    EXPECT_NEAR(r.value, 1.0 / (k + 1), 4e-16) << "x^" << k;
    EXPECT_EQ(r.evaluations, 15);
    if (k <= 13) {
      EXPECT_LT(r.error, 1e-13) << "x^" << k << ": the Gauss rule should be exact";
    } else {
      EXPECT_GT(r.error, 1e-13) << "x^" << k << ": the Gauss rule cannot be exact";
    }
  }
  const auto beyond = integrate([](double x) { return std::pow(x, 30); }, 0.0, 1.0, one);
  EXPECT_GT(std::abs(beyond.value - 1.0 / 31.0), 1e-14);  // degree 30 is past the Kronrod rule's reach
}

// The n-point Gauss-Legendre rule integrates x^k exactly for k <= 2n - 1 and not x^2n; n = 7 is QUADPACK's
// embedded 7-point Gauss rule (its tabulated nodes and weights, written here).
TEST(Quadrature, GaussLegendreRulesAreExactToDegreeTwoNMinusOne) {
  for (const int n : {1, 2, 3, 7, 16, 24, 64}) {
    const GaussLegendreRule& r = gauss_legendre_rule(n);
    ASSERT_EQ(r.nodes.size(), static_cast<std::size_t>(n));
    for (int k = 0; k <= 2 * n; ++k) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += r.weights[static_cast<std::size_t>(i)] * std::pow(r.nodes[static_cast<std::size_t>(i)], k);
      const double exact = k % 2 == 1 ? 0.0 : 2.0 / (k + 1);  // integral of x^k over [-1, 1]
      if (k < 2 * n) {
        EXPECT_NEAR(sum, exact, 1e-14) << "n " << n << ", x^" << k;
      } else {
        // x^2n is beyond the rule by exactly 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2) (Abramowitz & Stegun 25.4.29's
        // remainder with f^(2n) = (2n)!), where that is above rounding.
        const double remainder = std::exp((2 * n + 1) * std::log(2.0) + 4.0 * std::lgamma(n + 1.0) -
                                          std::log(2.0 * n + 1.0) - 2.0 * std::lgamma(2.0 * n + 1.0));
        if (remainder > 1e-12) {
          EXPECT_NEAR(exact - sum, remainder, 1e-6 * remainder + 1e-15) << "n " << n << ": x^" << k;
        }
      }
    }
    for (int i = 0; i + 1 < n; ++i) EXPECT_LT(r.nodes[static_cast<std::size_t>(i)], r.nodes[static_cast<std::size_t>(i + 1)]);
  }
  const GaussLegendreRule& g7 = gauss_legendre_rule(7);
  const double nodes[4] = {0.949107912342758524526189684047851, 0.741531185599394439863864773280788,
                           0.405845151377397166906606412076961, 0.0};
  const double weights[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                             0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(g7.nodes[static_cast<std::size_t>(6 - i)], nodes[i], 1e-15);
    EXPECT_NEAR(g7.nodes[static_cast<std::size_t>(i)], -nodes[i], 1e-15);
    EXPECT_NEAR(g7.weights[static_cast<std::size_t>(i)], weights[i], 1e-15);
  }
  EXPECT_THROW(gauss_legendre_rule(0), std::invalid_argument);
  EXPECT_THROW(gauss_legendre_rule(129), std::invalid_argument);
  EXPECT_EQ(&gauss_legendre_rule(16), &gauss_legendre_rule(16));  // built once
}

TEST(Quadrature, SmoothKnownIntegrals) {
  QuadratureOptions o;
  o.rel_tol = 1e-13;
  const auto e = integrate([](double x) { return std::exp(x); }, 0.0, 1.0, o);
  EXPECT_TRUE(e.converged);
  EXPECT_NEAR(e.value, std::exp(1.0) - 1.0, 1e-13);
  // Cancellation: the roundoff floor 50 eps int |sin| ~ 7e-13 is above 1e-13 of the value 0.14, so this one
  // asks for 1e-10.
  QuadratureOptions loose;
  loose.rel_tol = 1e-10;
  const auto osc = integrate([](double x) { return std::sin(x); }, 0.0, 100.0, loose);
  EXPECT_TRUE(osc.converged);
  EXPECT_NEAR(osc.value, 1.0 - std::cos(100.0), 1e-12);
  const auto lorentz = integrate([](double x) { return 1.0 / (1.0 + 1e6 * x * x); }, -1.0, 1.0, o);
  EXPECT_NEAR(lorentz.value, 2.0 * std::atan(1e3) / 1e3, 1e-13 * lorentz.value);
}

// The zoo's integrands with the sharpest peak (n = 10000 at t = 0) and a derivative singularity at pi/2
// (n = 0.5), to 1e-12 relative, with an error estimate that covers the true error.
TEST(Quadrature, PeakyCosinePowers) {
  QuadratureOptions o;
  o.rel_tol = 1e-12;
  for (double n : {0.0, 0.5, 1.0, 2.0, 5.0, 10.0, 100.0, 1000.0, 10000.0}) {
    const auto r = integrate([n](double t) { return std::pow(std::cos(t), n) * std::sin(t); }, 0.0, pi / 2, o);
    const double exact = 1.0 / (n + 1.0);
    EXPECT_TRUE(r.converged) << "n = " << n;
    EXPECT_LE(std::abs(r.value - exact), 1e-12 * exact) << "n = " << n;
    EXPECT_LE(r.error, 1e-12 * exact) << "n = " << n;
    EXPECT_GE(r.error, 0.5 * std::abs(r.value - exact)) << "n = " << n << ": the estimate must cover the error";
  }
}

TEST(Quadrature, EndpointSingularities) {
  QuadratureOptions o;
  o.rel_tol = 1e-12;
  const auto root = integrate([](double x) { return std::sqrt(x); }, 0.0, 1.0, o);
  EXPECT_TRUE(root.converged);
  EXPECT_NEAR(root.value, 2.0 / 3.0, 1e-12);
  // f is never evaluated at the endpoints, so integrable infinities there are fine.
  const auto inv_root = integrate([](double x) { return 1.0 / std::sqrt(x); }, 0.0, 1.0, o);
  EXPECT_TRUE(inv_root.converged);
  EXPECT_NEAR(inv_root.value, 2.0, 2e-11);
  const auto log = integrate([](double x) { return std::log(x); }, 0.0, 1.0, o);
  EXPECT_NEAR(log.value, -1.0, 1e-12);
}

TEST(Quadrature, EmptyReversedAndNonConverged) {
  const auto empty = integrate([](double) { return 1.0; }, 2.0, 2.0);
  EXPECT_EQ(empty.value, 0.0);
  EXPECT_TRUE(empty.converged);
  const auto reversed = integrate([](double x) { return x; }, 1.0, 0.0);
  EXPECT_NEAR(reversed.value, -0.5, 1e-15);
  QuadratureOptions tight;
  tight.rel_tol = 1e-14;
  tight.max_subdivisions = 3;
  const auto capped = integrate([](double x) { return std::pow(std::cos(x), 1e4); }, 0.0, 1.5, tight);
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.subdivisions, 3);
  const auto nan = integrate([](double x) { return x > 0.5 ? std::nan("") : 1.0; }, 0.0, 1.0);
  EXPECT_FALSE(nan.converged);
}

TEST(Quadrature, InitialIntervalsFindANarrowPeakAwayFromTheNodes) {
  // A spike of width 1e-3 at 0.3 is invisible to one 15-point rule on [0, 1]; 64 initial pieces see it.
  const auto spike = [](double x) { return std::exp(-0.5 * std::pow((x - 0.3) / 1e-3, 2.0)); };
  const double exact = 1e-3 * std::sqrt(two_pi);
  QuadratureOptions o;
  o.initial_intervals = 64;
  const auto r = integrate(spike, 0.0, 1.0, o);
  EXPECT_NEAR(r.value, exact, 1e-10 * exact);
}

TEST(Quadrature, VectorComponentsEachMeetTheirTolerance) {
  QuadratureOptions o;
  o.rel_tol = 1e-12;
  const auto r = integrate_vector(
      [](double t, std::span<double> out) {
        out[0] = std::pow(std::cos(t), 1000.0) * std::sin(t);
        out[1] = 1e-6 * std::sin(t);
        out[2] = 0.0;
      },
      3, 0.0, pi / 2, o);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.value[0], 1.0 / 1001.0, 1e-12 / 1001.0);
  EXPECT_NEAR(r.value[1], 1e-6, 1e-18);
  EXPECT_EQ(r.value[2], 0.0);
}

TEST(Quadrature, TwoDimensional) {
  QuadratureOptions o;
  o.rel_tol = 1e-11;
  const auto tri = integrate_2d([](double x, double y) { return x * y; }, 0.0, 1.0, [](double) { return 0.0; },
                                [](double x) { return x; }, o);
  EXPECT_TRUE(tri.converged);
  EXPECT_NEAR(tri.value, 0.125, 1e-14);
  // The unit disk, whose outer integrand has square-root endpoint singularities.
  const auto disk = integrate_2d([](double, double) { return 1.0; }, -1.0, 1.0,
                                 [](double x) { return -std::sqrt(1.0 - x * x); },
                                 [](double x) { return std::sqrt(1.0 - x * x); }, o);
  EXPECT_NEAR(disk.value, pi, 1e-10);
  EXPECT_LE(std::abs(disk.value - pi), std::max(disk.error, 1e-14));
  // A sharp 2D Gaussian in a corner: pi / (4 k), erf(100)^2 == 1 in double precision.
  const double k = 1e4;
  const auto gauss = integrate_2d([k](double x, double y) { return std::exp(-k * (x * x + y * y)); }, 0.0, 1.0,
                                  [](double) { return 0.0; }, [](double) { return 1.0; }, o);
  EXPECT_NEAR(gauss.value, pi / (4.0 * k), 1e-10 * pi / (4.0 * k));
}

double sphere_integral(const std::function<double(const Vec3&)>& g, const Vec3& axis, SphereRegion region,
                       double rel_tol = 1e-11) {
  QuadratureOptions o;
  o.rel_tol = rel_tol;
  return integrate_directions([&g](const Vec3& w, std::span<double> out) { out[0] = g(w); }, 1, axis, region, o)
      .value[0];
}

TEST(Quadrature, DirectionsSolidAnglesAndCosines) {
  const auto one = [](const Vec3&) { return 1.0; };
  const auto cos_up = [](const Vec3& w) { return w.z > 0.0 ? w.z : 0.0; };
  for (double tilt_deg : {0.0, 30.0, 80.0, 89.99, 120.0}) {
    const double t = deg_to_rad(tilt_deg);
    const Vec3 axis{std::sin(t) * std::cos(0.3), std::sin(t) * std::sin(0.3), std::cos(t)};
    EXPECT_NEAR(sphere_integral(one, axis, SphereRegion::upper), two_pi, 1e-10) << tilt_deg;
    EXPECT_NEAR(sphere_integral(one, axis, SphereRegion::lower), two_pi, 1e-10) << tilt_deg;
    EXPECT_NEAR(sphere_integral(one, axis, SphereRegion::sphere), four_pi, 2e-10) << tilt_deg;
    EXPECT_NEAR(sphere_integral(cos_up, axis, SphereRegion::upper), pi, 1e-10) << tilt_deg;
    EXPECT_NEAR(sphere_integral(cos_up, axis, SphereRegion::lower), 0.0, 1e-12) << tilt_deg;
  }
}

TEST(Quadrature, DirectionsSharpLobeAcrossTheHorizon) {
  // The normalized power-cosine lobe (n + 1)/(2 pi) max(0, c.w)^n integrates to 1 over the sphere, also when
  // its axis is 0.01 degrees above the horizon so that the lobe straddles it.
  const double n = 1e4;
  for (double tilt_deg : {0.0, 45.0, 89.99}) {
    const double t = deg_to_rad(tilt_deg);
    const Vec3 c{std::sin(t), 0.0, std::cos(t)};
    const auto lobe = [&](const Vec3& w) {
      const double d = dot(c, w);
      return d > 0.0 ? (n + 1.0) * inv_two_pi * std::pow(d, n) : 0.0;
    };
    const double up = sphere_integral(lobe, c, SphereRegion::upper, 1e-11);
    const double down = sphere_integral(lobe, c, SphereRegion::lower, 1e-11);
    EXPECT_NEAR(up + down, 1.0, 1e-9) << tilt_deg;
    if (tilt_deg == 0.0) {
      EXPECT_NEAR(up, 1.0, 1e-11);
    }
    if (tilt_deg > 89.0) {
      EXPECT_GT(down, 0.3);  // a good part of the lobe lies below the horizon
    }
  }
}

}  // namespace
}  // namespace shadelab
