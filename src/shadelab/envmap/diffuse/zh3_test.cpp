#include "shadelab/envmap/diffuse/zh3.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadelab {
namespace {

double y20(double t) { return std::sqrt(5.0 / (16.0 * pi)) * (3.0 * t * t - 1.0); }

TEST(Zh3, AxisIsTheLuminanceWeightedL1Direction) {
  // Red light from +x, green from +y: the luminance weights (0.2126, 0.7152) tilt the axis toward +y by
  // atan(0.7152 / 0.2126) for lobes of the same shape.
  const auto f = [](const Vec3& d) {
    return Rgb{std::pow(std::max(0.0, d.x), 4.0), std::pow(std::max(0.0, d.y), 4.0), 0.0};
  };
  const Zh3 z = zh3_from_sh(project_sh_bands(f, 48, 3), Zh3Mode::stored);
  EXPECT_NEAR(std::atan2(z.axis.y, z.axis.x), std::atan2(0.7152, 0.2126), 1e-6);
  EXPECT_NEAR(z.axis.z, 0.0, 1e-9);
  // A directional light's axis is its direction.
  const Vec3 d = normalize(Vec3{-0.2, 0.5, 0.7});
  const Zh3 l = zh3_from_sh(sh_bands_directional_light(d, Rgb{1, 0.5, 0.2}, 3), Zh3Mode::hallucinated);
  EXPECT_NEAR(dot(l.axis, d), 1.0, 1e-14);
}

TEST(Zh3, StoredCoefficientIsTheZonalProjection) {
  // z = integral L Y_20(a . w) dw, by direct quadrature over a cube (independent of the addition theorem).
  const auto f = [](const Vec3& d) {
    return Rgb{1.0 + std::exp(3.0 * d.y) + d.x * d.z, 0.3 + std::max(0.0, d.x), 2.0 * d.y * d.y + d.z};
  };
  const Zh3 z = zh3_from_sh(project_sh_bands(f, 64, 3), Zh3Mode::stored);
  const CubeTexelTable& t = CubeTexelTable::get(64);
  Rgb direct;
  for (std::size_t k = 0; k < t.direction.size(); ++k) direct += f(t.direction[k]) * (t.solid_angle[k] * y20(dot(z.axis, t.direction[k])));
  EXPECT_NEAR(z.zonal.r, direct.r, 1e-3 * std::abs(direct.r));
  EXPECT_NEAR(z.zonal.g, direct.g, 1e-3 * std::abs(direct.g));
  EXPECT_NEAR(z.zonal.b, direct.b, 1e-3 * std::abs(direct.b) + 1e-4);
  EXPECT_GT(std::abs(direct.r), 0.1);
}

TEST(Zh3, StoredIsExactL2ForAFunctionSymmetricAboutItsAxis) {
  // Band 2 of a function symmetric about a is c Y_20(a . w) alone, so ZH3 stored irradiance = SH9 irradiance.
  const Vec3 a = normalize(Vec3{0.3, 0.4, -0.6});
  const auto f = [&](const Vec3& d) {
    const double t = dot(a, d);
    return Rgb{std::exp(2.0 * t), 1.0 + t * t, 0.5 + std::max(0.0, t)};
  };
  const ShBands sh = project_sh_bands(f, 64, 3);
  const Zh3 z = zh3_from_sh(sh, Zh3Mode::stored);
  EXPECT_NEAR(dot(z.axis, a), 1.0, 1e-6);
  const auto e = sh_irradiance_factors(3, false);
  for (const Vec3 n : {a, -1.0 * a, Vec3{1, 0, 0}, normalize(Vec3{-1, 2, 0.5})}) {
    const Rgb want = sh_bands_evaluate(sh, n, e), got = zh3_irradiance(z, n);
    EXPECT_NEAR(got.r, want.r, 1e-4 * want.r);
    EXPECT_NEAR(got.g, want.g, 1e-4 * want.g);
    EXPECT_NEAR(got.b, want.b, 1e-4 * want.b);
  }
}

TEST(Zh3, HallucinatedFollowsThePapersFit) {
  // c_00 = 2, v = (0.4, 0, 0) along x  ->  r = 0.2, z = 2 (0.08 * 0.2 + 0.6 * 0.04) = 0.08.
  std::array<Rgb, 4> lin{Rgb::gray(2.0), Rgb::gray(0.0), Rgb::gray(0.0), Rgb::gray(-0.4)};
  EXPECT_NEAR(zh3_axis(lin).x, 1.0, 1e-15);
  EXPECT_NEAR(zh3_hallucinated_zonal(lin, {1, 0, 0}).g, 0.08, 1e-15);
  // No directionality: no zonal term; a dark channel stays dark.
  lin = {Rgb{1.0, 1.0, 0.0}, Rgb{}, Rgb{}, Rgb{}};
  EXPECT_EQ(zh3_hallucinated_zonal(lin, zh3_axis(lin)).r, 0.0);
  EXPECT_EQ(zh3_hallucinated_zonal(lin, zh3_axis(lin)).b, 0.0);
}

TEST(Zh3, DirectionalLightRatioAndZonalValueRederived) {
  // A delta light: c_l0 along its axis = Y_l0(1), so r = sqrt(3/(4 pi)) / (1/(2 sqrt(pi))) = sqrt(3) and the
  // exact (stored) z/c_00 = Y_20(1)/Y_00 = sqrt(5); the fit gives 0.08 sqrt(3) + 1.8 = 1.9386 (13% low).
  const Vec3 d = normalize(Vec3{0.5, 0.5, -0.2});
  const ShBands sh = sh_bands_directional_light(d, Rgb::gray(1.0), 3, false);
  const Zh3 stored = zh3_from_sh(sh, Zh3Mode::stored), hall = zh3_from_sh(sh, Zh3Mode::hallucinated);
  EXPECT_NEAR(stored.zonal.r / sh.c[0].r, std::sqrt(5.0), 1e-12);
  EXPECT_NEAR(hall.zonal.r / sh.c[0].r, 0.08 * std::sqrt(3.0) + 0.6 * 3.0, 1e-12);
  // Stored ZH3 of a delta is its L2 SH exactly (the delta is symmetric about its axis).
  for (const Vec3 n : {d, Vec3{0, 0, 1}, normalize(Vec3{1, -1, 0})})
    EXPECT_NEAR(zh3_irradiance(stored, n).r, sh_bands_evaluate(sh, n, sh_irradiance_factors(3, false)).r, 1e-12);
}

TEST(Zh3, HallucinationIsTheLowOrderLimitOfASmoothLobe) {
  // For L = exp(k a . w), c_l0 = 4 pi i_l(k) Y_l0(1) (i_l the modified spherical Bessel functions), so
  // r = sqrt(3) i_1/i_0 and z/c_00 = sqrt(5) i_2/i_0 -> r^2/sqrt(5) as k -> 0: the stored value grows as r^2
  // like the fit's 0.6 r^2 term, and both vanish with r. Checked on projected data against the closed form.
  for (double k : {0.25, 0.5, 1.0}) {
    const Vec3 a{0, 1, 0};
    const ShBands sh = project_sh_bands([&](const Vec3& w) { return Rgb::gray(std::exp(k * dot(a, w))); }, 64, 3);
    const Zh3 z = zh3_from_sh(sh, Zh3Mode::stored);
    const double i0 = std::sinh(k) / k, i1 = (k * std::cosh(k) - std::sinh(k)) / (k * k),
                 i2 = ((k * k + 3.0) * std::sinh(k) - 3.0 * k * std::cosh(k)) / (k * k * k);
    const double r = std::abs(dot(Vec3{-sh.c[3].r, -sh.c[1].r, sh.c[2].r}, z.axis)) / sh.c[0].r;
    EXPECT_NEAR(r, std::sqrt(3.0) * i1 / i0, 1e-4) << k;
    EXPECT_NEAR(z.zonal.r / sh.c[0].r, std::sqrt(5.0) * i2 / i0, 1e-4) << k;
  }
}

}  // namespace
}  // namespace shadelab
