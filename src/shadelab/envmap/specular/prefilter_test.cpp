#include "shadelab/envmap/specular/prefilter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/envmap/base/cube_test_util.h"

namespace shadelab {
namespace {

using test_cubes::make_cube;

TEST(Prefilter, GlossMapping) {
  EXPECT_DOUBLE_EQ(prefilter_exponent(0, 8, 10, 1), 2048.0);
  EXPECT_DOUBLE_EQ(prefilter_exponent(7, 8, 10, 1), 2.0);
  EXPECT_NEAR(prefilter_exponent(1, 3, 10, 1), std::exp2(6.0), 1e-12);
  EXPECT_DOUBLE_EQ(phong_exponent_from_blinn_phong(400.0), 100.0);
}

TEST(Prefilter, ConstantComesBackAtEveryLevel) {
  const CubeMap env = make_cube(32, [](const Vec3&) { return Rgb{0.5, 1.0, 2.0}; });
  PrefilterOptions o;
  o.size = 16;
  const auto p = prefilter_specular(env, o);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->levels.size(), 5u);
  for (const auto& level : p->levels)
    for (int f = 0; f < 6; ++f) EXPECT_NEAR(level.texel(f, 0, level.size - 1).g, 1.0, 1e-6);
}

TEST(Prefilter, MatchesTheFunkHeckeBandFactors) {
  // For an environment of degree <= 2, the normalized Phong convolution is sum_l L_l c_lm Y_lm(R) with
  // L = (1, (n+1)/(n+2), n/(n+3)) (independent closed form).
  const auto f = [](const Vec3& d) { return Rgb::gray(1.0 + 0.6 * d.x + 0.8 * d.y * d.z - 0.3 * d.z * d.z); };
  const CubeMap env = make_cube(64, f);
  const Sh9 sh = project_sh9(env);
  PrefilterOptions o;
  o.size = 8;
  o.mip_count = 4;
  const auto p = prefilter_specular(env, o);
  ASSERT_TRUE(p.has_value());
  for (std::size_t i = 0; i < p->levels.size(); ++i) {
    const double n = p->exponents[i];
    const BandFactors factors = {1.0, (n + 1) / (n + 2), n / (n + 3)};
    const CubeMap& level = p->levels[i];
    for (int face : {0, 3, 4}) {
      const int c = level.size / 2;
      const Vec3 r = texel_direction(face, c, c, level.size);
      const double expected = sh9_evaluate(sh, r, factors).r;
      // Within 0.3%: texels of half the lobe width discretize the lobe.
      EXPECT_NEAR(level.texel(face, c, c).r, expected, 3e-3 * expected) << "level " << i << " n " << n;
    }
  }
}

TEST(Prefilter, CullingChangesNothingMeasurable) {
  // A sharp feature: one texel 10^4 times brighter than the rest. Culling drops weights below 1e-9 of the
  // lobe's peak, so the culled convolution is within 1e-9 x 10^4 of the brute-force one.
  CubeMap env(32);
  env.set(0, 10, 12, Rgb::gray(1000.0));
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        if (!(f == 0 && x == 10 && y == 12)) env.set(f, x, y, Rgb::gray(0.1));
  PrefilterOptions o;
  o.size = 8;
  o.mip_count = 3;
  const auto p = prefilter_specular(env, o);
  ASSERT_TRUE(p.has_value());
  for (std::size_t i = 0; i < 3; ++i) {
    const CubeMap& level = p->levels[i];
    for (int y = 0; y < level.size; ++y) {
      const Vec3 r = texel_direction(0, 2, y, level.size);
      // Level 0 (n = 2048) reads the full-resolution input; compare against the brute force on it.
      if (i == 0) {
        const Rgb ref = prefilter_brute_force(env, r, p->exponents[i]);
        EXPECT_NEAR(level.texel(0, 2, y).r, ref.r, 2e-5 * ref.r) << y;
      }
    }
  }
}

TEST(Prefilter, EveryTexelOfEveryFaceMatchesTheBruteForce) {
  // Output texels are computed in groups of four mirror images ((x, y), (N - 1 - x, y), (x, N - 1 - y) and
  // (N - 1 - x, N - 1 - y) share their weights, the images reading the mirror images of the first one's
  // texels; the 1 x 1 level's single texel alone): an environment with no symmetry and a bright texel on each
  // face at a different place, and every texel of every level (8, 4, 2, 1; n = 2048 .. 2, all read from the
  // 32^2 input), all four quadrants of every face, against the brute force. A mirror image taken along the
  // wrong local axis fails it (and BakeAccuracy.SpecularChainWithinItsStatedErrorOfTheBruteForce).
  CubeMap env(32);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        const double v = 0.05 + 0.9 * std::fmod(0.6180339887 * (1 + f + 7 * x + 131 * y + x * y), 1.0);
        env.set(f, x, y, Rgb{v, 1.0 - v, 0.5 * v * v});
      }
  for (int f = 0; f < 6; ++f) env.set(f, 3 + 5 * f, 29 - 4 * f, Rgb{300.0, 20.0, 1.0});
  PrefilterOptions o;
  o.size = 8;
  o.mip_count = 4;
  const auto p = prefilter_specular(env, o);
  ASSERT_TRUE(p.has_value());
  ASSERT_EQ(p->levels.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const CubeMap& level = p->levels[i];
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < level.size; ++y)
        for (int x = 0; x < level.size; ++x) {
          const Rgb ref = prefilter_brute_force(env, texel_direction(f, x, y, level.size), p->exponents[i]);
          const Rgb got = level.texel(f, x, y);
          for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], ref[c], 2e-5 * ref[c]) << "level " << i << " face " << f << " (" << x << ", " << y << ") channel " << c;
        }
  }
}

TEST(Prefilter, BadOptionsAreErrors) {
  const CubeMap env(4);
  PrefilterOptions o;
  o.size = 12;
  EXPECT_FALSE(prefilter_specular(env, o).has_value());
  o.size = 16;
  o.mip_count = 9;
  EXPECT_FALSE(prefilter_specular(env, o).has_value());
  o.mip_count = 2;
  o.gloss_scale = std::nan("");
  EXPECT_FALSE(prefilter_specular(env, o).has_value());
}

}  // namespace
}  // namespace shadelab
