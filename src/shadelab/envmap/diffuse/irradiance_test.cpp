#include "shadelab/envmap/diffuse/irradiance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/base/downsample.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/light/hemisphere_light.h"
#include "shadelab/envmap/base/cube_test_util.h"

namespace shadelab {
namespace {

using test_cubes::make_cube;

// Largest |texel - value| over every channel of every texel.
double max_deviation(const Image& img, double value) {
  double m = 0.0;
  for (float v : img.data) m = std::max(m, std::abs(static_cast<double>(v) - value));
  return m;
}
double max_deviation(const CubeMap& cube, double value) {
  double m = 0.0;
  for (const Image& face : cube.faces) m = std::max(m, max_deviation(face, value));
  return m;
}

TEST(Irradiance, ConstantHalfBakesToHalfInGameUnits) {
  // The seed's oracle (AMD CubeMapGen / HDRShop): a constant 0.5 environment bakes to 0.5 in game units and
  // to 0.5 pi radiometric. E(n) is normalised by the discrete cosine weight W(n) = sum max(0, n.w) dOmega
  // of the same texels (irradiance.h), so a constant L gives L W(n) / W(n): 0.5 exactly, in the stored
  // floats (radiometric: pi x 0.5 in double, within the float storage's rounding, 3e-8 relative). The
  // plain discrete sum was off by up to 1.2e-4 relative (128 x 64 lat-long to 6 x 16^2). Lat-long inputs
  // with even sizes (paired rings) and an odd height, cube inputs of even and odd face size, an input
  // halved first (max_input_size), cube and lat-long outputs at even and odd sizes.
  const auto latlong = [](int w, int h) {
    Image img(w, h);
    for (float& v : img.data) v = 0.5f;
    return img;
  };
  const auto cube = [](int n) { return make_cube(n, [](const Vec3&) { return Rgb::gray(0.5); }); };
  const double radiometric_tol = 0.5 * pi * 3e-8;
  ConvolveOptions halve;
  halve.max_input_size = 16;  // 128 x 64 -> 64 x 32, 6 x 32^2 -> 6 x 16^2
  for (const int size : {16, 32, 7, 15}) {
    for (const auto& [name, in] : {std::pair<const char*, Image>{"128x64", latlong(128, 64)}, {"126x63", latlong(126, 63)}}) {
      EXPECT_EQ(max_deviation(irradiance_cube(in, size, RadianceUnits::game), 0.5), 0.0) << name << " -> cube " << size;
      EXPECT_EQ(max_deviation(irradiance_latlong(in, 2 * size + 1, RadianceUnits::game), 0.5), 0.0) << name << " -> lat-long " << 2 * size + 1;
      EXPECT_LE(max_deviation(irradiance_cube(in, size, RadianceUnits::radiometric), 0.5 * pi), radiometric_tol) << name << " " << size;
    }
    EXPECT_EQ(max_deviation(irradiance_cube(latlong(128, 64), size, RadianceUnits::game, halve), 0.5), 0.0) << "halved, " << size;
    for (const int n : {32, 15}) {
      EXPECT_EQ(max_deviation(irradiance_cube(cube(n), size, RadianceUnits::game), 0.5), 0.0) << "cube " << n << " -> " << size;
      EXPECT_EQ(max_deviation(irradiance_latlong(cube(n), 2 * size, RadianceUnits::game), 0.5), 0.0) << "cube " << n << " -> lat-long";
      EXPECT_LE(max_deviation(irradiance_cube(cube(n), size, RadianceUnits::radiometric), 0.5 * pi), radiometric_tol) << "cube " << n;
    }
    EXPECT_EQ(max_deviation(irradiance_cube(cube(32), size, RadianceUnits::game, halve), 0.5), 0.0) << "halved cube, " << size;
  }
}

TEST(Irradiance, ColouredConstantBakesToItselfWithinFloatRounding) {
  // A constant that is not a power of two: the prefix tables are rounded to float after scaling, so L W(n)
  // and W(n) are summed from differently rounded entries, and a run's sum is a difference of two prefix
  // entries; the quotient is L within that float rounding (1.4e-6 measured, cube 24 -> 9; the plain
  // discrete sum was off by 1.2e-4 and 5.7e-4 here).
  const Rgb c{0.3, 1.7, 12.5};
  Image ll(128, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 128; ++x) ll.set(x, y, c);
  const CubeMap cube = make_cube(24, [&](const Vec3&) { return c; });
  for (const CubeMap& e : {irradiance_cube(ll, 16, RadianceUnits::game), irradiance_cube(cube, 9, RadianceUnits::game)}) {
    double max_rel = 0.0;
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < e.size; ++y)
        for (int x = 0; x < e.size; ++x)
          for (int ch = 0; ch < 3; ++ch) max_rel = std::max(max_rel, std::abs(e.texel(f, x, y)[ch] - c[ch]) / c[ch]);
    EXPECT_LE(max_rel, 5e-6) << "output size " << e.size;
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
  // E(n) = pi flux max(0, n.d) / W(n), W(n) = sum over the 6 x 16^2 texels of max(0, n.w) dOmega (written
  // again here): the bake normalises by the discrete cosine weights, which differ from pi by up to 1e-3
  // at 16^2 (irradiance.h).
  CubeMap env(16);
  env.set(4, 7, 8, Rgb::gray(50.0));
  const Vec3 d = texel_direction(4, 7, 8, 16);
  const double flux = 50.0 * cube_texel_solid_angle(7, 8, 16);
  const CubeMap e = irradiance_cube(env, 4, RadianceUnits::radiometric);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const Vec3 n = texel_direction(f, x, y, 4);
        double weight = 0.0;
        for (int g = 0; g < 6; ++g)
          for (int j = 0; j < 16; ++j)
            for (int i = 0; i < 16; ++i) weight += std::max(0.0, dot(n, texel_direction(g, i, j, 16))) * cube_texel_solid_angle(i, j, 16);
        const double expected = pi * flux * std::max(0.0, dot(n, d)) / weight;
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
