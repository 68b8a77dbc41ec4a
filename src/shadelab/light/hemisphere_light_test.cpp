#include "shadelab/light/hemisphere_light.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadelab {
namespace {

TEST(HemisphereLight, MatchesNumericIntegration) {
  // E = integral over the normal's hemisphere of L(w) cos: sky where w.up > 0, ground below.
  const Rgb sky{1.0, 2.0, 3.0};
  const Rgb ground{0.5, 0.25, 0.0};
  for (double t : {0.0, 30.0, 90.0, 135.0, 180.0}) {
    const double th = t * pi / 180.0;
    const Vec3 n{std::sin(th), std::cos(th), 0.0};  // angle t from up (+Y)
    const int cells = 1000;
    double sum_sky = 0.0;
    double sum_ground = 0.0;
    // Midpoint rule over the normal's hemisphere in (cos, phi) about n.
    const Vec3 a = normalize(cross(n, std::abs(n.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0}));
    const Vec3 b = cross(n, a);
    for (int i = 0; i < cells; ++i) {
      const double c = (i + 0.5) / cells;
      const double s = std::sqrt(1 - c * c);
      for (int j = 0; j < cells; ++j) {
        const double phi = two_pi * (j + 0.5) / cells;
        const Vec3 w = n * c + a * (s * std::cos(phi)) + b * (s * std::sin(phi));
        (w.y > 0 ? sum_sky : sum_ground) += c;
      }
    }
    const double dw = two_pi / (cells * double(cells));
    const Rgb expected = sky * (sum_sky * dw) + ground * (sum_ground * dw);
    const Rgb e = hemisphere_irradiance(HemisphereLight{{0, 1, 0}, sky, ground}, n);
    EXPECT_NEAR(e.g, expected.g, 1e-4) << t;
    EXPECT_NEAR(e.r, expected.r, 1e-4) << t;
  }
  // A uniform environment of radiance L gives pi L whatever the orientation.
  EXPECT_NEAR(hemisphere_irradiance(Rgb::gray(0.5), Rgb::gray(0.5), 0.3).r, 0.5 * pi, 1e-15);
}

}  // namespace
}  // namespace shadelab
