#include "shadelab/envmap/irradiance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/sh.h"
#include "shadelab/light/hemisphere_light.h"
#include "shadelab/envmap/cube_test_util.h"

namespace shadelab {
namespace {

using test_cubes::make_cube;

TEST(Irradiance, ConstantHalfBakesToHalfInGameUnits) {
  const CubeMap env = make_cube(32, [](const Vec3&) { return Rgb::gray(0.5); });
  const CubeMap game = irradiance_cube(env, 8, RadianceUnits::game);
  const CubeMap radiometric = irradiance_cube(env, 8, RadianceUnits::radiometric);
  // Texels cut by the horizon of n make the discrete sum differ from pi L by O(h^2): 3e-5 at 32 x 32.
  for (int f = 0; f < 6; ++f) {
    EXPECT_NEAR(game.texel(f, 3, 5).r, 0.5, 5e-5) << f;
    EXPECT_NEAR(radiometric.texel(f, 0, 7).g, 0.5 * pi, 5e-5 * pi) << f;
  }
}

TEST(Irradiance, SkyAndGroundMatchTheHemisphereFormula) {
  // Sky above the horizon, ground below: E = pi (sky (1 + cos)/2 + ground (1 - cos)/2), exactly.
  const CubeMap env = make_cube(64, [](const Vec3& d) { return d.y > 0 ? Rgb::gray(1.0) : Rgb::gray(0.2); });
  for (const Vec3 n : {Vec3{0, 1, 0}, normalize(Vec3{1, 1, 0}), Vec3{1, 0, 0}, normalize(Vec3{0, -1, 3})}) {
    const double expected = hemisphere_irradiance(Rgb::gray(1.0), Rgb::gray(0.2), n.y).r;
    EXPECT_NEAR(irradiance_brute_force(env, n).r, expected, 2e-3) << n.x << " " << n.y << " " << n.z;
  }
}

TEST(Irradiance, SingleHotTexelIsItsCosineLaw) {
  CubeMap env(16);
  env.set(4, 7, 8, Rgb::gray(50.0));
  const Vec3 d = texel_direction(4, 7, 8, 16);
  const double flux = 50.0 * cube_texel_solid_angle(7, 8, 16);
  const CubeMap e = irradiance_cube(env, 4, RadianceUnits::radiometric);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const double expected = flux * std::max(0.0, dot(texel_direction(f, x, y, 4), d));
        EXPECT_NEAR(e.texel(f, x, y).r, expected, 1e-6 * flux);
      }
}

TEST(Irradiance, DownsamplingKeepsTheIntegral) {
  const CubeMap env = make_cube(64, [](const Vec3& d) { return Rgb{std::exp(3 * d.x), 1 + d.y, d.z * d.z}; });
  const CubeMap half = downsample_cube(env);
  ASSERT_EQ(half.size, 32);
  auto integral = [](const CubeMap& c) {
    double s = 0;
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < c.size; ++y)
        for (int x = 0; x < c.size; ++x) s += c.texel(f, x, y).r * cube_texel_solid_angle(x, y, c.size);
    return s;
  };
  EXPECT_NEAR(integral(half), integral(env), 1e-7 * integral(env));  // float texels
  // The irradiance of the downsampled input is within 1e-3 of the full one.
  const Vec3 n = normalize(Vec3{0.3, 0.5, -0.8});
  EXPECT_NEAR(irradiance_brute_force(half, n).r, irradiance_brute_force(env, n).r, 1e-3 * irradiance_brute_force(env, n).r);
}

TEST(Irradiance, ShAgreesWithBruteForceOnASmoothEnvironment) {
  // An environment of degree <= 2 is represented exactly by SH9, so SH irradiance equals brute force up to
  // the brute force's own discretization of the horizon (O(h^2), 8e-5 at 64 x 64).
  const CubeMap env = make_cube(64, [](const Vec3& d) { return Rgb::gray(1.0 + 0.5 * d.x + 0.3 * d.y * d.z); });
  const Sh9 sh = project_sh9(env);
  for (const Vec3 n : {Vec3{0, 0, 1}, normalize(Vec3{1, -1, 0.5})}) {
    EXPECT_NEAR(sh9_irradiance(sh, n).r, irradiance_brute_force(env, n).r, 1.5e-4 * sh9_irradiance(sh, n).r);
  }
}

TEST(Irradiance, SameResultWhateverTheSplit) {
  const CubeMap env = make_cube(32, [](const Vec3& d) { return Rgb{std::exp(3 * d.x), 1 + d.y, d.z * d.z}; });
  const CubeMap a = irradiance_cube(env, 8, RadianceUnits::game);
  ConvolveOptions o;
  int calls = 0;
  o.progress = [&](double) { ++calls; };
  const CubeMap b = irradiance_cube(env, 8, RadianceUnits::game, o);
  EXPECT_GT(calls, 0);
  for (int f = 0; f < 6; ++f) EXPECT_EQ(a.faces[static_cast<std::size_t>(f)].data, b.faces[static_cast<std::size_t>(f)].data);
  const Image ll = irradiance_latlong(env, 16, RadianceUnits::game);
  EXPECT_EQ(ll.height, 8);
}

TEST(Irradiance, LatLongDownsamplingIsTheSolidAngleWeightedMeanOfEachTexelsFourChildren) {
  // Row y of a W x H lat-long map subtends (2 pi / W)(cos(pi y / H) - cos(pi (y + 1) / H)) per texel (written
  // again here); an output texel is the flux of its 2 x 2 children over its own solid angle. Every texel
  // differs, so reading a wrong child shows.
  const int w = 16, h = 8;
  Image ll(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      ll.set(x, y, Rgb{1.0 + x + 17.0 * y, 1.0 + (x * 7 + y * 3) % 11, 0.5 + 0.25 * ((x + y) % 2)});
  const Image half = downsample_latlong(ll);
  ASSERT_EQ(half.width, w / 2);
  ASSERT_EQ(half.height, h / 2);
  auto omega = [](int y, int width, int height) {
    return 2.0 * pi / width * (std::cos(pi * y / height) - std::cos(pi * (y + 1) / height));
  };
  for (int y = 0; y < h / 2; ++y)
    for (int x = 0; x < w / 2; ++x) {
      Rgb flux;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) flux = flux + ll.at(2 * x + dx, 2 * y + dy) * omega(2 * y + dy, w, h);
      const Rgb expected = flux / omega(y, w / 2, h / 2);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(half.at(x, y)[c], expected[c], 1e-6 * expected[c]) << x << " " << y;
    }
}

}  // namespace
}  // namespace shadelab
