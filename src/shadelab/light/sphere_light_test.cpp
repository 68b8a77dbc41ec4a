#include "shadelab/light/sphere_light.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/core/frame.h"
#include "shadelab/light/hemisphere_light.h"

namespace shadelab {
namespace {

// Brute force: the midpoint rule over the cap in (cos, phi) about its centre, summing max(0, n.w) d(omega).
double numeric_factor(double theta, double beta, int n = 1500) {
  const Vec3 c{std::sin(theta), 0.0, std::cos(theta)};
  const Frame f = Frame::from_normal(c);
  const double cos_beta = std::cos(beta);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = cos_beta + (1.0 - cos_beta) * (i + 0.5) / n;
    const double s = std::sqrt(1.0 - u * u);
    for (int j = 0; j < n; ++j) {
      const double phi = two_pi * (j + 0.5) / n;
      const double z = f.to_world({s * std::cos(phi), s * std::sin(phi), u}).z;
      if (z > 0.0) sum += z;
    }
  }
  return sum * (1.0 - cos_beta) / n * two_pi / n;
}

TEST(SphereLight, FullyAboveHorizonIsPiLSin2Beta) {
  // The zoo article: E = pi L sin^2(beta) when the cap faces the surface.
  for (double beta_deg : {1.0, 10.0, 40.0}) {
    const double beta = deg_to_rad(beta_deg);
    EXPECT_NEAR(sphere_irradiance_factor(1.0, std::sin(beta)), pi * std::pow(std::sin(beta), 2), 1e-15);
    EXPECT_NEAR(sphere_irradiance_factor(1.0, std::sin(beta)), numeric_factor(0.0, beta), 1e-6 * pi);
  }
}

TEST(SphereLight, MatchesNumericIntegrationIncludingBelowHorizon) {
  struct Case { double theta, beta; };
  for (const Case c : {Case{30, 20}, Case{80, 20}, Case{95, 20}, Case{100, 30}, Case{60, 40}, Case{89, 5},
                       Case{120, 40}, Case{91, 60}}) {
    const double exact = sphere_irradiance_factor(std::cos(deg_to_rad(c.theta)), std::sin(deg_to_rad(c.beta)));
    const double numeric = numeric_factor(deg_to_rad(c.theta), deg_to_rad(c.beta));
    EXPECT_NEAR(exact, numeric, 2e-6 * std::max(numeric, 1e-3)) << c.theta << " " << c.beta;
  }
  EXPECT_EQ(sphere_irradiance_factor(std::cos(deg_to_rad(130)), std::sin(deg_to_rad(30))), 0.0);
}

TEST(SphereLight, ContinuousAcrossTheHorizonCases) {
  const double sb = std::sin(deg_to_rad(25));
  const double edge = std::cos(deg_to_rad(65));  // theta = 90 - beta
  EXPECT_NEAR(sphere_irradiance_factor(edge + 1e-9, sb), sphere_irradiance_factor(edge - 1e-9, sb), 1e-7);
  EXPECT_NEAR(sphere_irradiance_factor(-sb + 1e-12, sb), 0.0, 1e-6);
}

TEST(SphereLight, TouchingSphereIsAHemisphereOfRadiance) {
  // beta = 90 degrees: the cap is the hemisphere about the centre direction (the sky formula, sky = L).
  for (double t : {0.0, 40.0, 120.0}) {
    const double c = std::cos(deg_to_rad(t));
    EXPECT_NEAR(sphere_irradiance_factor(c, 1.0), hemisphere_irradiance(Rgb::gray(1), Rgb{}, c).r, 1e-12) << t;
  }
}

TEST(SphereLight, FarAwayItIsAPointLightOfIntensityPiLr0Squared) {
  // I = pi L r0^2 (zoo article): far away the irradiance is I cos / d^2.
  const SphereLight s{{0.0, 0.0, 1000.0}, 0.5, Rgb::gray(7.0)};
  const Vec3 n = normalize(Vec3{0.0, 0.6, 0.8});
  const Rgb e = sphere_light_irradiance(s, {}, n);
  const Rgb i = sphere_light_intensity(s.radiance, s.radius);
  EXPECT_NEAR(i.r, pi * 7.0 * 0.25, 1e-14);
  EXPECT_NEAR(e.r, i.r * 0.8 / (1000.0 * 1000.0), 1e-9 * e.r);  // exact: sin^2 beta = r0^2/d^2
  EXPECT_TRUE(sphere_light_irradiance(s, {0.0, 0.0, 1000.2}, n).is_black());  // inside
}

}  // namespace
}  // namespace shadelab
