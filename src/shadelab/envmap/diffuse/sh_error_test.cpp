// The SH-family encodings of Blender's eight HDRIs (Debian's blender-data, CC0) against the exact irradiance:
// windowed L2 never goes negative, and the measured errors behave as the theory says.
#include "shadelab/envmap/diffuse/sh_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/envmap/diffuse/sh_bands.h"
#include "shadelab/envmap/diffuse/zh3.h"
#include "shadelab/image/image_io.h"

namespace shadelab {
namespace {

TEST(ShEncodingErrors, ConstantEnvironmentIsExactForEveryEncoding) {
  CubeMap env(16);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) env.set(f, x, y, Rgb::gray(0.7));
  // Up to the brute force's own discretization where the horizon cuts texels (2e-4 at 16^2).
  for (const ShEncodingError& e : sh_encoding_errors(env, 8)) {
    EXPECT_LT(e.max_relative, 5e-4) << e.encoding;
    EXPECT_EQ(e.negative_solid_angle, 0.0) << e.encoding;
  }
}

TEST(ShEncodingErrors, ANearDeltaRingsWhereTheTheorySays) {
  // A small bright cap about +y (half-angle 5.7 degrees, nearly a delta). The order-3 irradiance of a delta
  // is proportional to sum_l w_l A_l (2l + 1) P_l(t) (addition theorem), negative on an interval of
  // t = n.y: solid angle 2 pi (t2 - t1), 3.652 sr without a window (roots of 15 t^2 + 16 t + 3); windowing only
  // shrinks it (sh.h). Found here by a fine scan of t, independently of the library's evaluation.
  CubeMap env(32);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) env.set(f, x, y, Rgb::gray(texel_direction(f, x, y, 32).y > 0.995 ? 1000.0 : 0.0));
  std::map<std::string, ShEncodingError> by;
  for (const ShEncodingError& e : sh_encoding_errors(env, 32)) by[e.encoding] = e;
  auto negative_band = [](double w1, double w2) {
    int count = 0;
    const int steps = 200000;
    for (int i = 0; i < steps; ++i) {
      const double t = -1.0 + 2.0 * (i + 0.5) / steps;
      if (1.0 + w1 * 2.0 * t + w2 * 1.25 * 0.5 * (3 * t * t - 1) < 0.0) ++count;  // A_l (2l+1)/pi = 1, 2, 5/4
    }
    return 2.0 * pi * 2.0 * count / steps;
  };
  EXPECT_NEAR(negative_band(1.0, 1.0), 2.0 * pi * std::sqrt(76.0) / 15.0, 1e-3);  // t2 - t1 = sqrt(76)/15
  EXPECT_NEAR(by["L2"].negative_solid_angle, negative_band(1.0, 1.0), 0.15);
  const double h1 = 0.5 * (1 + std::cos(pi / 5)), h2 = 0.5 * (1 + std::cos(2 * pi / 5));
  EXPECT_NEAR(by["L2 hanning"].negative_solid_angle, negative_band(h1, h2), 0.15);
  EXPECT_LT(by["L2 hanning"].negative_solid_angle, by["L2"].negative_solid_angle - 0.3);
  EXPECT_EQ(by.size(), 14u);
  EXPECT_EQ(by["L4"].coefficients, 25);
  EXPECT_EQ(by["ZH3 stored"].coefficients, 5);
  // Band 3 adds nothing to irradiance (A_3 = 0): L3 and L2 agree without a window.
  EXPECT_NEAR(by["L3"].mean_relative, by["L2"].mean_relative, 1e-9);
}

TEST(ShEncodingErrors, BlenderWorldsWindowedL2HasNoNegativeTexel) {
  const std::filesystem::path dir = SHADELAB_BLENDER_WORLDS;
  if (!std::filesystem::is_directory(dir)) GTEST_FAIL() << dir << " is missing (scripts/setup.sh installs blender-data)";
  int count = 0;
  for (const char* name : {"city", "courtyard", "forest", "interior", "night", "studio", "sunrise", "sunset"}) {
    const auto img = read_image(dir / (std::string(name) + ".exr"));
    ASSERT_TRUE(img.has_value()) << img.error().message;
    const CubeMap env = latlong_to_cube(*img, 32, 2);
    std::map<std::string, ShEncodingError> by;
    for (const ShEncodingError& e : sh_encoding_errors(env, 16)) {
      by[e.encoding] = e;
      std::printf("%-10s %-18s mean %6.2f%%  max %7.2f%%  negative %.4f sr\n", name, e.encoding.c_str(),
                  100 * e.mean_relative, 100 * e.max_relative, e.negative_solid_angle);
    }
    EXPECT_EQ(by["L2 hanning"].negative_solid_angle, 0.0) << name;
    EXPECT_EQ(by["L2 lanczos"].negative_solid_angle, 0.0) << name;
    // More bands never hurt on average: L2 beats L1, and the truncation error of L2 is what A_4 leaves.
    EXPECT_LT(by["L2"].mean_relative, by["L1"].mean_relative) << name;
    EXPECT_LT(by["ZH3 stored"].mean_relative, by["L1"].mean_relative) << name;
    ++count;
  }
  EXPECT_EQ(count, 8);
}

}  // namespace
}  // namespace shadelab
