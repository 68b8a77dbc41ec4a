#include "shadelab/brdf/cook_torrance.h"

#include "shadelab/brdf/fresnel.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {
using testing::dir;
using testing::make;

TEST(CookTorrance, Form1981IsFourTimesMicrofacet) {
  for (const char* g : {"cook-torrance", "kelemen", "smith"}) {
    const auto a = make("cook-torrance", {{"kd", "0"}, {"g", g}, {"form", "1981"}});
    const auto b = make("cook-torrance", {{"kd", "0"}, {"g", g}, {"form", "microfacet"}});
    const Rgb fa = a->eval(dir(30, 0), dir(50, 170));
    const Rgb fb = b->eval(dir(30, 0), dir(50, 170));
    EXPECT_NEAR(fa.r, 4.0 * fb.r, 1e-14 * fa.r) << g;
  }
}

TEST(CookTorrance, LectureFormulaWithBeckmannAndMinG) {
  // Lecture 5: R_s = F D G / (pi (N.L)(N.V)), D = exp(-(tan a / m)^2) / (m^2 cos^4 a), G = min(1, ...).
  const double m = 0.35;
  const auto f = make("cook-torrance", {{"kd", "0"}, {"ks", "1"}, {"m", "0.35"}, {"g", "cook-torrance"},
                                        {"f", "dielectric"}, {"ior", "1.6"}, {"form", "1981"}});
  const Vec3 l = dir(20, 30);
  const Vec3 v = dir(65, 200);
  const Vec3 h = normalize(l + v);
  const double a = std::acos(h.z);
  const double d = std::exp(-std::pow(std::tan(a) / m, 2)) / (m * m * std::pow(std::cos(a), 4));
  const double vh = dot(v, h);
  const double g = std::min({1.0, 2 * h.z * v.z / vh, 2 * h.z * l.z / vh});
  const double fr = F_dielectric(vh, 1.6);
  const double expected = fr * d * g / (pi * l.z * v.z);
  EXPECT_NEAR(f->eval(l, v).r, expected, 1e-12 * expected);
}

TEST(CookTorrance, KelemenVisibility) {
  const auto f = make("cook-torrance", {{"kd", "0"}, {"ks", "1"}, {"g", "kelemen"}, {"f", "none"}, {"m", "0.4"}});
  const Vec3 l = dir(60, 0);
  const Vec3 v = dir(10, 90);
  const Vec3 h = normalize(l + v);
  const double expected = D_beckmann(h.z, 0.4) / (4.0 * dot(l, h) * dot(l, h));
  EXPECT_NEAR(f->eval(l, v).g, expected, 1e-13 * expected);
}

TEST(CookTorrance, ExponentAndRoughnessAreInterchangeable) {
  // n = 2/m^2 - 2: giving n = 48 is the same as m = 0.2.
  const auto a = make("cook-torrance", {{"n", "48"}});
  const auto b = make("cook-torrance", {{"m", "0.2"}});
  EXPECT_NEAR(a->eval(dir(30, 0), dir(40, 180)).r, b->eval(dir(30, 0), dir(40, 180)).r, 1e-12);
  EXPECT_FALSE(make_brdf("cook-torrance", {{"n", "48"}, {"m", "0.2"}}).has_value());
}

TEST(CookTorrance, BlinnPhongDistributionIsHeightfieldNormalized) {
  const auto f = make("cook-torrance", {{"kd", "0"}, {"d", "blinn-phong"}, {"n", "40"}, {"g", "kelemen"}, {"f", "none"}});
  const Vec3 l = dir(30, 0);
  const Vec3 v = dir(30, 180);  // mirror pair: H = N, L.H = cos 30
  const double expected = (40.0 + 2.0) / (2 * pi) / (4.0 * std::pow(std::cos(deg_to_rad(30)), 2));
  EXPECT_NEAR(f->eval(l, v).b, expected, 1e-12 * expected);
}

TEST(CookTorrance, ConductorFresnelUsesComplexIor) {
  const auto f = make("cook-torrance", {{"kd", "0"}, {"f", "conductor"}, {"ior", "0.2,0.4,1.4"}, {"k", "3.6,2.6,1.9"}});
  const auto* ct = dynamic_cast<const CookTorrance*>(f.get());
  ASSERT_NE(ct, nullptr);
  EXPECT_NEAR(ct->fresnel(1.0).r, f0_from_ior(0.2, 3.6), 1e-12);
  EXPECT_NEAR(ct->fresnel(1.0).b, f0_from_ior(1.4, 1.9), 1e-12);
}

}  // namespace
}  // namespace shadelab
