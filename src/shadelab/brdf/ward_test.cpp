#include "shadelab/brdf/ward.h"

#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {
using testing::dir;
using testing::make;

TEST(Ward, IsotropicMatchesLectureFormula) {
  const double a = 0.15;
  const auto f = make("ward", {{"kd", "0"}, {"ks", "0.4"}, {"alpha", "0.15"}});
  const Vec3 l = dir(35, 0);
  const Vec3 v = dir(45, 170);
  const double th = std::acos(normalize(l + v).z);
  const double expected = 0.4 / (4 * pi * a * a) * std::exp(-std::pow(std::tan(th), 2) / (a * a)) / std::sqrt(l.z * v.z);
  EXPECT_NEAR(f->eval(l, v).r, expected, 1e-13 * expected);
}

TEST(Ward, AnisotropicWithEqualAlphasIsIsotropic) {
  const auto iso = make("ward", {{"alpha", "0.3"}});
  const auto aniso = make("ward-anisotropic", {{"alpha_x", "0.3"}, {"alpha_y", "0.3"}});
  for (double phi : {0.0, 33.0, 101.0}) {
    const Rgb a = iso->eval(dir(40, phi), dir(20, 160));
    const Rgb b = aniso->eval(dir(40, phi), dir(20, 160));
    EXPECT_NEAR(a.r, b.r, 1e-15 * a.r);
  }
}

TEST(Ward, AnisotropicSlideTimesCosineForm) {
  // The lecture's slide: ks/(4 pi ax ay) sqrt(N.L/N.V) exp(-tan^2(th)(cos^2 ph/ax^2 + sin^2 ph/ay^2)) = f N.L.
  const double ax = 0.3;
  const double ay = 0.08;
  const auto f = make("ward-anisotropic", {{"kd", "0"}, {"ks", "1"}, {"alpha_x", "0.3"}, {"alpha_y", "0.08"}});
  const Vec3 l = dir(30, 60);
  const Vec3 v = dir(25, 250);
  const Vec3 h = normalize(l + v);
  const double th = std::acos(h.z);
  const double ph = std::atan2(h.y, h.x);
  const double e = std::pow(std::tan(th), 2) * (std::pow(std::cos(ph) / ax, 2) + std::pow(std::sin(ph) / ay, 2));
  const double slide = 1.0 / (4 * pi * ax * ay) * std::sqrt(l.z / v.z) * std::exp(-e);
  EXPECT_NEAR(f->eval(l, v).r * l.z, slide, 1e-12 * slide);
}

TEST(Ward, EfficientExponentAgreesOnlyNearTheNormal) {
  // Ward's cheaper exponent 2((h.x/ax)^2 + (h.y/ay)^2)/(1 + h.z) matches tan^2 to first order at H = N.
  const Ward w(Rgb{}, Rgb::gray(1), 0.2, 0.1);
  auto efficient = [](const Vec3& h) { return 2 * (std::pow(h.x / 0.2, 2) + std::pow(h.y / 0.1, 2)) / (1 + h.z); };
  const Vec3 near_n = dir(0.5, 40);
  EXPECT_NEAR(efficient(near_n), w.slope_term(near_n), 1e-4 * w.slope_term(near_n));
  const Vec3 far = dir(40, 40);
  EXPECT_GT(std::abs(efficient(far) - w.slope_term(far)), 0.1 * w.slope_term(far));
}

TEST(Ward, PdfIsZeroWhereTheHalfVectorLiesInTheTangentPlane) {
  // Walter 2005's density of h is zero for h.z <= 0, and the cosine lobe's is zero below the horizon: a wi
  // mirrored below the surface (wi.z = -wo.z, so h.z = 0 exactly) has pdf 0, not 0 / 0.
  for (const char* model : {"ward", "ward-anisotropic"}) {
    const auto f = testing::make(model);
    ASSERT_TRUE(f);
    const Vec3 wo{0.6, 0.0, 0.8};
    const Vec3 wi{0.6, 0.0, -0.8};
    EXPECT_EQ(f->pdf(wi, wo), 0.0) << model;
    EXPECT_EQ(f->pdf(Vec3{0.0, 0.28, -0.96}, Vec3{0.0, 0.28, 0.96}), 0.0) << model;
  }
}

}  // namespace
}  // namespace shadelab
