#include "shadelab/envmap/diffuse/sh_bands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "shadelab/envmap/base/latlong.h"

namespace shadelab {
namespace {

// Legendre P_l(t) by Bonnet's recurrence (l + 1) P_l+1 = (2l + 1) t P_l - l P_l-1: independent of the library.
double legendre(int l, double t) {
  double p0 = 1.0, p1 = t;
  if (l == 0) return p0;
  for (int k = 1; k < l; ++k) {
    const double p2 = ((2.0 * k + 1.0) * t * p1 - k * p0) / (k + 1.0);
    p0 = p1;
    p1 = p2;
  }
  return p1;
}

const Vec3 test_dirs[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0.6, -0.8, 0}, {0.2, 0.3, 0.9327379053088815},
                          {-0.48, 0.6, -0.64}, {0.1, -0.9, 0.4242640687119285}};

TEST(ShBands, FirstNineAreTheSh9Basis) {
  for (const Vec3& d : test_dirs) {
    const Vec3 n = normalize(d);
    const std::vector<double> b = sh_basis(n, 5);
    const ShBasis s = sh9_basis(n);
    for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(b[i], s[i], 1e-15) << i;
  }
}

TEST(ShBands, BasisIsStdSphLegendreWithTheRealForm) {
  // std::sph_legendre(l, m, theta) = (-1)^m K_lm P_l^m(cos theta) (C++17 special functions, with the
  // Condon-Shortley phase): the real basis is sqrt(2) of it times cos(m phi) / sin(|m| phi).
  for (const Vec3& d : test_dirs) {
    const Vec3 n = normalize(d);
    const double theta = std::acos(std::clamp(n.z, -1.0, 1.0)), phi = std::atan2(n.y, n.x);
    const std::vector<double> b = sh_basis(n, 5);
    for (int l = 0; l < 5; ++l)
      for (int m = -l; m <= l; ++m) {
        const int am = std::abs(m);
        const double s = std::sph_legendre(static_cast<unsigned>(l), static_cast<unsigned>(am), theta);
        const double want = m == 0 ? s : std::sqrt(2.0) * s * (m > 0 ? std::cos(am * phi) : std::sin(am * phi));
        EXPECT_NEAR(b[static_cast<std::size_t>(sh_index(l, m))], want, 1e-14) << l << " " << m;
      }
  }
}

TEST(ShBands, BasisMatchesSloansClosedForms) {
  // Sloan 2008, appendix A2 (polynomials in x, y, z), a few of bands 3 and 4.
  for (const Vec3& d : test_dirs) {
    const Vec3 n = normalize(d);
    const double x = n.x, y = n.y, z = n.z;
    const std::vector<double> b = sh_basis(n, 5);
    EXPECT_NEAR(b[sh_index(3, 0)], std::sqrt(7.0 / (16.0 * pi)) * (5 * z * z * z - 3 * z), 1e-14);
    EXPECT_NEAR(b[sh_index(3, 3)], -std::sqrt(35.0 / (32.0 * pi)) * (x * x * x - 3 * x * y * y), 1e-14);
    EXPECT_NEAR(b[sh_index(3, -3)], -std::sqrt(35.0 / (32.0 * pi)) * (3 * x * x * y - y * y * y), 1e-14);
    EXPECT_NEAR(b[sh_index(3, -2)], std::sqrt(105.0 / (4.0 * pi)) * x * y * z, 1e-14);
    EXPECT_NEAR(b[sh_index(4, 0)], 3.0 / (16.0 * std::sqrt(pi)) * (35 * z * z * z * z - 30 * z * z + 3), 1e-14);
    EXPECT_NEAR(b[sh_index(4, 4)], 3.0 / 16.0 * std::sqrt(35.0 / pi) * (x * x * x * x - 6 * x * x * y * y + y * y * y * y), 1e-14);
    EXPECT_NEAR(b[sh_index(4, -4)], 3.0 / 4.0 * std::sqrt(35.0 / pi) * x * y * (x * x - y * y), 1e-14);
  }
}

TEST(ShBands, BasisIsOrthonormalByExactQuadrature) {
  // Gauss-Legendre in z (16 nodes, exact to degree 31) times 24 equally spaced phi (exact for trigonometric
  // degree < 24): exact for every product of two basis functions of degree <= 4.
  const int nz = 16, nphi = 24;
  std::vector<double> node(nz), weight(nz);
  for (int i = 0; i < nz; ++i) {
    double t = std::cos(pi * (i + 0.75) / (nz + 0.5));
    for (int it = 0; it < 100; ++it) {
      const double p = legendre(nz, t), q = legendre(nz - 1, t);
      const double dp = nz * (t * p - q) / (t * t - 1.0);
      const double step = p / dp;
      t -= step;
      if (std::abs(step) < 1e-16) break;
    }
    const double p = legendre(nz, t), q = legendre(nz - 1, t);
    const double dp = nz * (t * p - q) / (t * t - 1.0);
    node[static_cast<std::size_t>(i)] = t;
    weight[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - t * t) * dp * dp);
  }
  std::vector<double> gram(625, 0.0);
  for (int i = 0; i < nz; ++i)
    for (int j = 0; j < nphi; ++j) {
      const double z = node[static_cast<std::size_t>(i)], s = std::sqrt(1.0 - z * z), phi = two_pi * j / nphi;
      const std::vector<double> b = sh_basis({s * std::cos(phi), s * std::sin(phi), z}, 5);
      const double w = weight[static_cast<std::size_t>(i)] * two_pi / nphi;
      for (std::size_t a = 0; a < 25; ++a)
        for (std::size_t c = 0; c < 25; ++c) gram[a * 25 + c] += w * b[a] * b[c];
    }
  for (std::size_t a = 0; a < 25; ++a)
    for (std::size_t c = 0; c < 25; ++c) EXPECT_NEAR(gram[a * 25 + c], a == c ? 1.0 : 0.0, 1e-13) << a << " " << c;
}

TEST(ShBands, CosineBandFactorsAreTheClampedCosinesLegendreCoefficients) {
  // Funk-Hecke: A_l = 2 pi integral_0^1 t P_l(t) dt, by the midpoint rule (error ~1e-11).
  const int cells = 200000;
  for (int l = 0; l <= 6; ++l) {
    double s = 0.0;
    for (int i = 0; i < cells; ++i) {
      const double t = (i + 0.5) / cells;
      s += t * legendre(l, t);
    }
    EXPECT_NEAR(sh_cosine_band_factor(l), two_pi * s / cells, 1e-9) << l;
  }
  EXPECT_NEAR(sh_cosine_band_factor(0), pi, 1e-15);
  EXPECT_NEAR(sh_cosine_band_factor(1), 2 * pi / 3, 1e-15);
  EXPECT_NEAR(sh_cosine_band_factor(2), pi / 4, 1e-15);
  EXPECT_EQ(sh_cosine_band_factor(3), 0.0);
  EXPECT_NEAR(sh_cosine_band_factor(4), -pi / 24, 1e-15);
  // The order-3 factors of sh.h.
  for (std::size_t l = 0; l < 3; ++l) EXPECT_NEAR(sh_irradiance_factors(3, true)[l], cosine_band_factors_over_pi[l], 1e-15);
}

TEST(ShBands, WindowsGeneraliseTheOrderThreeOnes) {
  for (ShWindow w : {ShWindow::none, ShWindow::hanning, ShWindow::lanczos}) {
    const std::vector<double> f = sh_window_factors(w, 3);
    const BandFactors g = sh_window_factors(w);
    for (std::size_t l = 0; l < 3; ++l) EXPECT_NEAR(f[l], g[l], 1e-15);
  }
  // L4: hanning (1 + cos(pi l / 9))/2, lanczos sinc(pi l / 8); the top band of lanczos is always 2/pi.
  const std::vector<double> h = sh_window_factors(ShWindow::hanning, 5), z = sh_window_factors(ShWindow::lanczos, 5);
  EXPECT_NEAR(h[4], 0.5 * (1.0 + std::cos(4.0 * pi / 9.0)), 1e-15);
  EXPECT_NEAR(h[4], 0.586824, 1e-6);
  EXPECT_NEAR(z[2], std::sqrt(8.0) / pi, 1e-15);  // sin(pi/4)/(pi/4)
  for (int b = 2; b <= 5; ++b) EXPECT_NEAR(sh_window_factors(ShWindow::lanczos, b).back(), 2.0 / pi, 1e-15) << b;
  EXPECT_NEAR(sh_window_factors(ShWindow::hanning, 2)[1], 0.75, 1e-15);  // (1 + cos(pi/3))/2
}

TEST(ShBands, ADegreeFourPolynomialIsReproduced) {
  // Band-limited to l <= 4, so five bands give it back up to the cube rule's O(h^2) error (3e-4 at 96^2);
  // four do not.
  const auto f = [](const Vec3& d) {
    return Rgb{1.0 + d.x + 2.0 * d.y * d.z * d.z, 0.5 + d.x * d.x * d.x * d.x - d.z * d.y, 2.0 + d.x * d.y * d.z};
  };
  const ShBands sh5 = project_sh_bands(f, 96, 5);
  const ShBands sh4 = project_sh_bands(f, 96, 4);
  double worst5 = 0.0, worst4 = 0.0;
  for (const Vec3& d : test_dirs) {
    const Vec3 n = normalize(d);
    worst5 = std::max(worst5, std::abs(sh_bands_evaluate(sh5, n).g - f(n).g));
    worst4 = std::max(worst4, std::abs(sh_bands_evaluate(sh4, n).g - f(n).g));
    EXPECT_NEAR(sh_bands_evaluate(sh5, n).r, f(n).r, 1e-3);
    EXPECT_NEAR(sh_bands_evaluate(sh5, n).b, f(n).b, 1e-3);
  }
  EXPECT_LT(worst5, 1e-3);
  EXPECT_GT(worst4, 0.05);  // x^4 has an l = 4 part
}

TEST(ShBands, CubeAndLatlongProjectionsAgree) {
  const auto f = [](const Vec3& d) { return Rgb{std::exp(2.0 * d.x), 1.0 + d.y * d.y * d.y, std::max(0.0, d.z + 0.3 * d.x)}; };
  CubeMap cube(48);
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x) cube.set(face, x, y, f(texel_direction(face, x, y, 48)));
  Image ll(384, 192);
  for (int y = 0; y < 192; ++y)
    for (int x = 0; x < 384; ++x) ll.set(x, y, f(latlong_direction((x + 0.5) / 384, (y + 0.5) / 192)));
  const ShBands a = project_sh_bands(cube, 5), b = project_sh_bands(ll, 5);
  const Sh9 s = project_sh9(cube);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_EQ(a.c[i].r, s.c[i].r) << i;  // bands 0..2 are project_sh9's
  for (std::size_t i = 0; i < 25; ++i) {
    EXPECT_NEAR(a.c[i].r, b.c[i].r, 2e-3) << i;
    EXPECT_NEAR(a.c[i].b, b.c[i].b, 2e-3) << i;
  }
  // The high bands are not zero here (the test would pass trivially on zeros).
  EXPECT_GT(std::abs(a.c[static_cast<std::size_t>(sh_index(3, 3))].r), 0.05);
  EXPECT_GT(std::abs(a.c[static_cast<std::size_t>(sh_index(3, -3))].g), 0.05);
}

TEST(ShBands, SingleHotTexelMatchesTheAdditionTheorem) {
  const int n = 16;
  CubeMap cube(n);
  const int face = 4, x = 3, y = 11;
  cube.set(face, x, y, Rgb::gray(50.0));
  const ShBands sh = project_sh_bands(cube, 5);
  const Vec3 d = texel_direction(face, x, y, n);
  const double flux = 50.0 * cube_texel_solid_angle(x, y, n);
  const double a_l[5] = {pi, 2 * pi / 3, pi / 4, 0.0, -pi / 24};
  for (const Vec3 nrm : {d, Vec3{0, 1, 0}, normalize(Vec3{1, 0, 1}), Vec3{0, 0, -1}}) {
    const double t = dot(nrm, d);
    double e = 0.0;
    for (int l = 0; l < 5; ++l) e += a_l[l] * (2 * l + 1) / (4 * pi) * legendre(l, t);
    // float accumulation of bands 0..2 (sh.cpp): 1e-5 relative
    EXPECT_NEAR(sh_bands_evaluate(sh, nrm, sh_irradiance_factors(5, false)).r, e * flux, 1e-5 * flux);
  }
}

TEST(ShBands, DirectionalLightIsExactFacingIt) {
  const Vec3 d = normalize(Vec3{0.3, -0.8, 0.5});
  // Unnormalized peaks: sum_l A_l (2l + 1)/(4 pi) = 3/4, 17/16, 17/16, 31/32.
  const double peaks[] = {0.75, 17.0 / 16.0, 17.0 / 16.0, 31.0 / 32.0};
  for (int b = 2; b <= 5; ++b) {
    const auto f = sh_irradiance_factors(b, true);
    EXPECT_NEAR(sh_bands_evaluate(sh_bands_directional_light(d, Rgb::gray(2.0), b), d, f).g, 2.0, 1e-13) << b;
    EXPECT_NEAR(sh_bands_evaluate(sh_bands_directional_light(d, Rgb::gray(1.0), b, false), d, f).g, peaks[b - 2], 1e-13) << b;
  }
  // Order 3 is sh9_directional_light.
  const ShBands a = sh_bands_directional_light(d, Rgb::gray(1.0), 3);
  const Sh9 s = sh9_directional_light(d, Rgb::gray(1.0));
  for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(a.c[i].r, s.c[i].r, 1e-15);
}

TEST(ShBands, RefusesBadBandCounts) {
  EXPECT_THROW(sh_basis({0, 0, 1}, 6), std::invalid_argument);
  EXPECT_THROW(sh_basis({0, 0, 1}, 0), std::invalid_argument);
  EXPECT_THROW(sh_window_factors(ShWindow::hanning, 7), std::invalid_argument);
}

}  // namespace
}  // namespace shadelab
