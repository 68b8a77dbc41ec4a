#include "shadelab/envmap/diffuse/sh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/envmap/base/latlong.h"

namespace shadelab {
namespace {

CubeMap constant_cube(int n, Rgb c) {
  CubeMap cube(n);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) cube.set(f, x, y, c);
  return cube;
}

TEST(Sh9, BasisConstantsAreTheClosedForms) {
  EXPECT_NEAR(sh_c0, 1.0 / (2.0 * std::sqrt(pi)), 1e-16);
  EXPECT_NEAR(sh_c1, std::sqrt(3.0 / (4.0 * pi)), 1e-16);
  EXPECT_NEAR(sh_c2, std::sqrt(15.0 / (4.0 * pi)), 1e-15);
  EXPECT_NEAR(sh_c3, std::sqrt(5.0 / (16.0 * pi)), 1e-16);
  EXPECT_NEAR(sh_c4, std::sqrt(15.0 / (16.0 * pi)), 2e-16);
  // The PI-or-not article's rounded constants.
  EXPECT_NEAR(sh_c0, 0.282095, 1e-6);
  EXPECT_NEAR(sh_c1, 0.488603, 1e-6);
  EXPECT_NEAR(sh_c2, 1.092548, 1e-6);
  EXPECT_NEAR(sh_c3, 0.315392, 1e-6);
  EXPECT_NEAR(sh_c4, 0.546274, 1e-6);
}

TEST(Sh9, BasisIsOrthonormal) {
  for (std::size_t i = 0; i < 9; ++i) {
    const Sh9 p = project_sh9([i](const Vec3& d) { return Rgb::gray(sh9_basis(d)[i]); }, 64);
    for (std::size_t j = 0; j < 9; ++j) EXPECT_NEAR(p.c[j].r, i == j ? 1.0 : 0.0, 2e-4) << i << " " << j;
  }
}

TEST(Sh9, ConstantEnvironmentGivesTheConstantBack) {
  // CubeMapGen's check: a constant 0.5 environment bakes to 0.5 in game units, pi x 0.5 radiometric.
  const Sh9 sh = project_sh9(constant_cube(32, Rgb::gray(0.5)));
  EXPECT_NEAR(sh.c[0].r, 0.5 * std::sqrt(4.0 * pi), 1e-5);
  for (const Vec3 n : {Vec3{0, 1, 0}, normalize(Vec3{1, -2, 0.5})}) {
    EXPECT_NEAR(sh9_irradiance_game(sh, n).g, 0.5, 1e-6);
    EXPECT_NEAR(sh9_irradiance(sh, n).g, 0.5 * pi, 1e-5);
  }
  // The same from a lat-long map.
  Image ll(128, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 128; ++x) ll.set(x, y, Rgb::gray(0.5));
  // The lat-long midpoint rule integrates the band-2 basis only to O(h^2): 3e-5 at 128 x 64.
  EXPECT_NEAR(sh9_irradiance_game(project_sh9(ll), {0, 0, 1}).r, 0.5, 1e-4);
}

TEST(Sh9, ClampedCosineHasKnownCoefficients) {
  // f = max(0, z): c0 = sqrt(pi)/2, c(1,0) = sqrt(pi/3), c(2,0) = sqrt(5 pi)/8 (Ramamoorthi & Hanrahan 2001).
  const Sh9 sh = project_sh9([](const Vec3& d) { return Rgb::gray(std::max(0.0, d.z)); }, 128);
  EXPECT_NEAR(sh.c[0].r, std::sqrt(pi) / 2.0, 1e-4);
  EXPECT_NEAR(sh.c[2].r, std::sqrt(pi / 3.0), 1e-4);
  EXPECT_NEAR(sh.c[6].r, std::sqrt(5.0 * pi) / 8.0, 1e-4);
  for (std::size_t i : {1u, 3u, 4u, 5u, 7u, 8u}) EXPECT_NEAR(sh.c[i].r, 0.0, 1e-6) << i;
}

TEST(Sh9, BandFactorsAreTheCosineLobeProjection) {
  // Funk-Hecke: the factor of band l of a zonal kernel k is 2 pi integral_{-1}^{1} k(t) P_l(t) dt.
  auto factor = [](int l, double w) {
    const int cells = 200000;
    double sum = 0.0;
    for (int i = 0; i < cells; ++i) {
      const double t = -1.0 + 2.0 * (i + 0.5) / cells;
      const double k = std::max(0.0, t + w) / (pi * (1 + w) * (1 + w));  // wrapped cosine / pi
      const double p = l == 0 ? 1.0 : (l == 1 ? t : 0.5 * (3 * t * t - 1));
      sum += k * p;
    }
    return two_pi * sum * 2.0 / cells;
  };
  for (int l = 0; l < 3; ++l) {
    EXPECT_NEAR(factor(l, 0.0), cosine_band_factors_over_pi[static_cast<std::size_t>(l)], 1e-8) << l;
    EXPECT_NEAR(factor(l, 0.0) * pi, cosine_band_factors[static_cast<std::size_t>(l)], 1e-8) << l;
    for (double w : {0.25, 0.5, 1.0}) {
      EXPECT_NEAR(factor(l, w), wrapped_band_factors_over_pi(w)[static_cast<std::size_t>(l)], 1e-8) << l << " " << w;
    }
  }
}

TEST(Sh9, WrapZeroIsPlainSh) {
  const Sh9 sh = project_sh9([](const Vec3& d) { return Rgb{std::exp(d.x), 1 + d.y * d.y, std::max(0.0, d.z)}; }, 32);
  const Vec3 n = normalize(Vec3{0.2, 0.9, -0.4});
  const Rgb a = sh9_evaluate(sh, n, wrapped_band_factors_over_pi(0.0));
  const Rgb b = sh9_irradiance_game(sh, n);
  EXPECT_DOUBLE_EQ(a.r, b.r);
  EXPECT_DOUBLE_EQ(a.b, b.b);
}

TEST(Sh9, DirectionalLightHasD3DXSemantics) {
  // A white directional light of game colour 1 gives exit radiance 1 on a white Lambert surface facing it.
  const Vec3 d = normalize(Vec3{0.3, 0.8, -0.5});
  const Sh9 sh = sh9_directional_light(d, Rgb::gray(1.0));
  EXPECT_NEAR(sh9_irradiance_game(sh, d).r, 1.0, 1e-14);
  // Without the normalization the order-3 truncation overshoots by 17/16.
  const Sh9 raw = sh9_directional_light(d, Rgb::gray(1.0), false);
  EXPECT_NEAR(sh9_irradiance_game(raw, d).r, 17.0 / 16.0, 1e-14);
  // Without the pi of the game unit it would be 17/(16 pi): the test fails if a pi goes missing.
  EXPECT_GT(sh9_irradiance_game(raw, d).r, 1.0);
}

TEST(Sh9, SingleHotTexelMatchesTheAdditionTheorem) {
  // One texel of radiance L: its projection is L dOmega Y_i(d), and the irradiance is
  // L dOmega sum_l A_l (2l + 1)/(4 pi) P_l(n.d) (the addition theorem), computed here independently.
  const int n = 16;
  CubeMap cube(n);
  const int face = 2, x = 5, y = 9;
  cube.set(face, x, y, Rgb::gray(100.0));
  const Sh9 sh = project_sh9(cube);
  const Vec3 d = texel_direction(face, x, y, n);
  const double d_omega = cube_texel_solid_angle(x, y, n);
  for (const Vec3 nrm : {d, Vec3{0, 1, 0}, normalize(Vec3{1, 0, 1}), Vec3{0, -1, 0}}) {
    const double t = dot(nrm, d);
    const double p[3] = {1.0, t, 0.5 * (3 * t * t - 1)};
    double e = 0.0;
    for (int l = 0; l < 3; ++l) e += cosine_band_factors[static_cast<std::size_t>(l)] * (2 * l + 1) / (4 * pi) * p[l];
    e *= 100.0 * d_omega;
    EXPECT_NEAR(sh9_irradiance(sh, nrm).r, e, 1e-5 * 100.0 * d_omega);
  }
}

TEST(Sh9, EveryTexelProjectsToItsBasisValues) {
  // The cube projection sums a face with its opposite face and a row with its mirror row at once (sh.cpp):
  // one hot texel anywhere must still project to L dOmega Y_i(d), with Y_i and dOmega computed here from
  // the basis and the texel's own solid angle. Sizes: 11 (a middle row paired with zeros and texels past
  // the last whole step of 8 or 16 lanes), 16 (whole steps only) and 21 (both), on every kernel wrapper
  // the CPU has (baseline, AVX2, AVX-512).
  for (const int widest : {0, 1, 2})
  for (const int n : {11, 16, 21}) {
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          if (n == 21 && (x + 2 * y + f) % 3 != 0) continue;  // a third of the largest size is enough
          CubeMap cube(n);
          cube.set(f, x, y, Rgb{100.0, 50.0, 25.0});
          const Sh9 sh = detail::project_sh9_simd(cube, widest);
          const ShBasis b = sh9_basis(texel_direction(f, x, y, n));
          const double d_omega = cube_texel_solid_angle(x, y, n);
          for (std::size_t i = 0; i < 9; ++i) {
            const double want = 100.0 * d_omega * b[i];
            ASSERT_NEAR(sh.c[i].r, want, 1e-5 * 100.0 * d_omega) << "wrapper " << widest << " n " << n << " face " << f << " x " << x << " y " << y << " i " << i;
            ASSERT_NEAR(sh.c[i].b, 0.25 * want, 1e-5 * 25.0 * d_omega) << "n " << n << " face " << f << " x " << x << " y " << y;
          }
        }
  }
}

TEST(Sh9, EveryKernelWrapperGivesTheSameProjection) {
  // The wrappers sum in different lane orders (and the baseline without FMA), so they may differ in the
  // last bits only: on a rough map at the benchmark's size, within 2e-6 of the largest coefficient. The
  // reference is a float64 sum over the texels, computed here from the basis and the solid angles.
  const int n = 512;
  CubeMap cube(n);
  std::uint32_t state = 12345u;
  auto next = [&] { state = state * 1664525u + 1013904223u; return (state >> 8) * (1.0 / 16777216.0); };
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) cube.set(f, x, y, Rgb{next() * 4.0, next(), 10.0 * next() * next()});
  Sh9 exact;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const ShBasis b = sh9_basis(texel_direction(f, x, y, n));
        const Rgb l = cube.texel(f, x, y) * cube_texel_solid_angle(x, y, n);
        for (std::size_t i = 0; i < 9; ++i) exact.c[i] += l * b[i];
      }
  for (const int widest : {0, 1, 2}) {
    const Sh9 got = detail::project_sh9_simd(cube, widest);
    for (std::size_t i = 0; i < 9; ++i) {
      EXPECT_NEAR(got.c[i].r, exact.c[i].r, 2e-6 * exact.c[0].r) << "wrapper " << widest << " i " << i;
      EXPECT_NEAR(got.c[i].g, exact.c[i].g, 2e-6 * exact.c[0].g) << "wrapper " << widest << " i " << i;
      EXPECT_NEAR(got.c[i].b, exact.c[i].b, 2e-6 * exact.c[0].b) << "wrapper " << widest << " i " << i;
    }
  }
}

TEST(Sh9, RotationIsExactAndIrradianceFollows) {
  // A band-limited function (degree <= 2), so the re-projection differs only by the quadrature error.
  const auto f = [](const Vec3& d) { return Rgb{1 + d.x + 2 * d.y * d.z, 0.5 + d.x * d.x - d.z, d.y}; };
  const Sh9 sh = project_sh9(f, 64);
  const Mat3 r = Mat3::rotation(normalize(Vec3{1, 2, 3}), 0.7);
  const Sh9 rotated = sh9_rotate(sh, r);
  const Sh9 reprojected = project_sh9([&](const Vec3& d) { return f(r.transposed().apply(d)); }, 64);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(rotated.c[i].r, reprojected.c[i].r, 2e-4) << i;
  // Irradiance is rotation-invariant: E_rotated(R n) = E(n), to rounding.
  for (const Vec3 n : {Vec3{0, 0, 1}, normalize(Vec3{-1, 0.3, 0.2})}) {
    EXPECT_NEAR(sh9_irradiance(rotated, r.apply(n)).g, sh9_irradiance(sh, n).g, 1e-12);
  }
  // Rotating by R then R^T is the identity.
  const Sh9 back = sh9_rotate(rotated, r.transposed());
  for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(back.c[i].b, sh.c[i].b, 1e-12) << i;
}

TEST(Sh9, WindowingReducesRinging) {
  // One directional light: the order-3 game irradiance is 1/4 + t/2 + 5/16 P_2(t) at t = n.d (unnormalized
  // projection), which dips below zero; a window halves the dip (figures in docs/envmap.md).
  const Vec3 d{0, 1, 0};
  const Sh9 sh = sh9_directional_light(d, Rgb::gray(1.0), false);
  auto minimum = [&](const BandFactors& window) {
    BandFactors f{};
    for (std::size_t l = 0; l < 3; ++l) f[l] = window[l] * cosine_band_factors_over_pi[l];
    double m = 1e9;
    for (int i = 0; i <= 2000; ++i) {
      const double t = -1.0 + i / 1000.0;
      m = std::min(m, sh9_evaluate(sh, {std::sqrt(1 - t * t), t, 0.0}, f).r);
    }
    return m;
  };
  const double plain = minimum(sh_window_factors(ShWindow::none));
  EXPECT_NEAR(plain, 0.09375 - 0.25 * 0.25 / 0.46875, 1e-6);  // the parabola's minimum, -0.0396
  EXPECT_NEAR(minimum(sh_window_factors(ShWindow::hanning)), -0.01893, 1e-4);
  EXPECT_NEAR(minimum(sh_window_factors(ShWindow::lanczos)), -0.01924, 1e-4);
}

TEST(Sh9, ProjectionIsDeterministic) {
  CubeMap cube(64);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) cube.set(f, x, y, Rgb{std::sin(x * 0.3 + f), std::cos(y * 0.2), 0.1 * x});
  const Sh9 a = project_sh9(cube);
  const Sh9 b = project_sh9(cube);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_EQ(a.c[i].r, b.c[i].r);
}

}  // namespace
}  // namespace shadelab
