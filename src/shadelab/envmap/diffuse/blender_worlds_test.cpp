// SH9 irradiance against brute-force irradiance on every real HDR environment of Debian's blender-data
// (CC0), within the rigorous order-2 truncation bound, with the measured error recorded.
//
// The bound: E - E_SH9 = sum_{l >= 3} A_l sum_m L_lm Y_lm(n), and A_l = 0 for odd l >= 3, so by Cauchy-Schwarz
// (over m with the addition theorem, then over l) |E(n) - E_SH9(n)| <= K sqrt(R), where
// K = sqrt(sum_{l even >= 4} A_l^2 (2l + 1)/(4 pi)) = 0.1279158 (A_l of Ramamoorthi & Hanrahan 2001, eq. 8)
// and R = integral of L^2 - sum of the nine squared coefficients is the energy SH9 leaves out (Parseval).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "shadelab/envmap/base/latlong.h"
#include "shadelab/envmap/diffuse/irradiance.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/image/image_io.h"

namespace shadelab {
namespace {

double truncation_constant() {
  double s = 0.0;
  for (int l = 4; l <= 200000; l += 2) {
    // A_l = 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * l! / (2^l ((l/2)!)^2)
    const double log_ratio = std::lgamma(l + 1.0) - l * std::log(2.0) - 2.0 * std::lgamma(l / 2.0 + 1.0);
    const double a = two_pi / ((l + 2.0) * (l - 1.0)) * std::exp(log_ratio);
    s += a * a * (2.0 * l + 1.0) / (4.0 * pi);
  }
  return std::sqrt(s);
}

TEST(BlenderWorlds, TruncationConstant) {
  EXPECT_NEAR(truncation_constant(), 0.1279158, 1e-6);
  EXPECT_NEAR(truncation_constant(), sh9_truncation_constant, 1e-7);  // the library's constant
  // A_2 from the same formula is pi/4, A_4 = -pi/24 in magnitude.
}

TEST(BlenderWorlds, ShIrradianceWithinTheTruncationBound) {
  const std::filesystem::path dir = SHADELAB_BLENDER_WORLDS;
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir << " is missing: scripts/setup.sh installs blender-data";
  int count = 0;
  for (const char* name : {"city", "courtyard", "forest", "interior", "night", "studio", "sunrise", "sunset"}) {
    const auto img = read_image(dir / (std::string(name) + ".exr"));
    ASSERT_TRUE(img.has_value()) << img.error().message;
    const CubeMap env = latlong_to_cube(*img, 64, 2);
    const Sh9 sh = project_sh9(env);
    const double bound = sh9_irradiance_error_bound(env, sh).g;
    const CubeMap brute = irradiance_cube(env, 8, RadianceUnits::radiometric);
    double max_err = 0.0;
    double max_rel = 0.0;
    double mean_e = 0.0;
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
          const Vec3 n = texel_direction(f, x, y, 8);
          const double e = brute.texel(f, x, y).g;
          const double err = std::abs(sh9_irradiance(sh, n).g - e);
          max_err = std::max(max_err, err);
          max_rel = std::max(max_rel, err / e);
          mean_e += e / (6 * 64);
        }
    // The brute force's own discretization (O(h^2), 1e-4 relative at 64 x 64) is allowed on top.
    EXPECT_LE(max_err, bound + 1e-3 * mean_e) << name;
    std::printf("%-10s max |E_sh - E| = %.4g = %.1f%% of the mean E %.4g (%.0f%% of the local E at worst); bound %.4g\n",
                name, max_err, 100.0 * max_err / mean_e, mean_e, 100.0 * max_rel, bound);
    RecordProperty(std::string(name) + "_max_relative_error", std::to_string(max_rel));
    ++count;
  }
  EXPECT_EQ(count, 8);
}

}  // namespace
}  // namespace shadelab
