#include "shadelab/light/punctual.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadelab {
namespace {

TEST(Punctual, PointLightInverseSquare) {
  const PointLight l{{0.0, 4.0, 0.0}, Rgb::gray(8.0)};
  const auto in = incident(l, {0.0, 2.0, 0.0});
  EXPECT_DOUBLE_EQ(in.distance, 2.0);
  EXPECT_DOUBLE_EQ(in.irradiance_perp.r, 2.0);  // 8 / 2^2
  EXPECT_DOUBLE_EQ(in.wi.y, 1.0);
  EXPECT_TRUE(incident(l, l.position).irradiance_perp.is_black());
}

TEST(Punctual, SpotFalloffFollowsKhrLightsPunctual) {
  EXPECT_DOUBLE_EQ(spot_falloff(0.95, 0.9, 0.8), 1.0);
  EXPECT_DOUBLE_EQ(spot_falloff(0.7, 0.9, 0.8), 0.0);
  EXPECT_NEAR(spot_falloff(0.85, 0.9, 0.8), 0.25, 1e-12);  // half-way: (0.5)^2
}

TEST(Punctual, SpotAttenuatesOffAxis) {
  const SpotLight s{{0.0, 0.0, 1.0}, {0.0, 0.0, -1.0}, Rgb::gray(1.0), std::cos(0.2), std::cos(0.4)};
  EXPECT_NEAR(incident(s, {0.0, 0.0, 0.0}).irradiance_perp.r, 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(incident(s, {1.0, 0.0, 0.0}).irradiance_perp.r, 0.0);  // 45 degrees: outside
}

}  // namespace
}  // namespace shadelab
