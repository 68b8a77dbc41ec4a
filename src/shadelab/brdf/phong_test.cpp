#include "shadelab/brdf/phong.h"

#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {
using testing::dir;
using testing::make;

// (R.L)^n computed independently: the angle between L and the mirror of V, from spherical coordinates.
double mirror_cos(double ti, double pi_, double to, double po) {
  // Mirror of V about the normal: same theta, phi + 180.
  const Vec3 l = dir(ti, pi_);
  const Vec3 r = dir(to, po + 180.0);
  return l.x * r.x + l.y * r.y + l.z * r.z;
}

TEST(Phong, OriginalFormMatchesFormula) {
  const double n = 12.0;
  const auto f = make("phong", {{"kd", "0"}, {"ks", "0.6"}, {"n", "12"}});
  const double c = mirror_cos(35, 170, 30, -5);
  const double expected = 0.6 * (n + 1.0) / (2.0 * pi) * std::pow(c, n) / std::cos(deg_to_rad(35));
  EXPECT_NEAR(f->eval(dir(35, 170), dir(30, -5)).r, expected, 1e-14 * expected);
  EXPECT_FALSE(f->is_reciprocal());
}

TEST(Phong, ModifiedFormMatchesFormula) {
  const double n = 7.5;
  const auto f = make("phong-modified", {{"kd", "0.25"}, {"ks", "0.6"}, {"n", "7.5"}});
  const double c = mirror_cos(50, 170, 20, -5);
  const double expected = 0.25 / pi + 0.6 * (n + 2.0) / (2.0 * pi) * std::pow(c, n);
  EXPECT_NEAR(f->eval(dir(50, 170), dir(20, -5)).r, expected, 1e-14 * expected);
  EXPECT_TRUE(f->is_reciprocal());
}

TEST(Phong, UnnormalizedIsTheLectureForm) {
  // Lecture 5: f = ks (R.L)^n / (N.L) + kd, with no pi anywhere.
  const auto f = make("phong", {{"kd", "0.3"}, {"ks", "0.5"}, {"n", "4"}, {"normalization", "none"}});
  const double c = mirror_cos(20, 180, 25, 0);
  const double expected = 0.3 + 0.5 * std::pow(c, 4.0) / std::cos(deg_to_rad(20));
  EXPECT_NEAR(f->eval(dir(20, 180), dir(25, 0)).r, expected, 1e-14);
}

TEST(Phong, NormalizationFactors) {
  for (double n : {0.0, 1.0, 10.0, 1000.0}) {
    EXPECT_DOUBLE_EQ(Phong::normalization_factor(n, Phong::Normalization::exact, false), (n + 1) / (2 * pi));
    EXPECT_DOUBLE_EQ(Phong::normalization_factor(n, Phong::Normalization::exact, true), (n + 2) / (2 * pi));
    EXPECT_DOUBLE_EQ(Phong::normalization_factor(n, Phong::Normalization::none, true), 1.0);
  }
}

TEST(Phong, LobeBehindMirrorIsZero) {
  const auto f = make("phong-modified", {{"kd", "0"}});
  // L on the same side as V, far from the mirror direction: R.L < 0.
  EXPECT_TRUE(f->eval(dir(80, 0), dir(80, 0)).is_black());
}

}  // namespace
}  // namespace shadelab
