#include "shadelab/brdf/blinn_phong.h"

#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {
using testing::dir;
using testing::make;
using N = BlinnPhong::Normalization;

double half_cos(const Vec3& a, const Vec3& b) {
  const Vec3 h = normalize(a + b);
  return h.z;
}

TEST(BlinnPhong, OriginalFormMatchesFormula) {
  const double n = 30.0;
  const auto f = make("blinn-phong", {{"kd", "0"}, {"ks", "1"}, {"n", "30"}});
  const Vec3 l = dir(40, 10);
  const Vec3 v = dir(25, 200);
  const double norm = (n + 2) / (4 * pi * (2 - std::pow(2.0, -n / 2)));
  const double expected = norm * std::pow(half_cos(l, v), n) / l.z;
  EXPECT_NEAR(f->eval(l, v).g, expected, 1e-13 * expected);
  EXPECT_FALSE(f->is_reciprocal());
}

TEST(BlinnPhong, ModifiedFormMatchesFormula) {
  const double n = 3.0;
  const auto f = make("blinn-phong-modified", {{"kd", "0.5"}, {"ks", "0.25"}, {"n", "3"}});
  const Vec3 l = dir(70, 10);
  const Vec3 v = dir(15, 120);
  const double norm = (n + 2) * (n + 4) / (8 * pi * (std::pow(2.0, -n / 2) + n));
  const double expected = 0.5 / pi + 0.25 * norm * std::pow(half_cos(l, v), n);
  EXPECT_NEAR(f->eval(l, v).b, expected, 1e-13 * expected);
  EXPECT_TRUE(f->is_reciprocal());
}

TEST(BlinnPhong, ZooBoundsBracketTheExactFactor) {
  for (double n : {0.0, 0.5, 1.0, 2.0, 5.0, 10.0, 100.0, 1000.0, 10000.0}) {
    for (bool modified : {false, true}) {
      const double lo = BlinnPhong::normalization_factor(n, N::lower, modified);
      const double ex = BlinnPhong::normalization_factor(n, N::exact, modified);
      const double hi = BlinnPhong::normalization_factor(n, N::upper, modified);
      EXPECT_LE(lo, ex * (1 + 1e-15)) << n << " " << modified;
      EXPECT_LE(ex, hi * (1 + 1e-15)) << n << " " << modified;
    }
  }
  // At n = 0 the exact factor meets the upper bound: 1/(2 pi) and 1/pi.
  EXPECT_NEAR(BlinnPhong::normalization_factor(0, N::exact, false), 1 / (2 * pi), 1e-16);
  EXPECT_NEAR(BlinnPhong::normalization_factor(0, N::exact, true), 1 / pi, 1e-16);
}

TEST(BlinnPhong, LargeExponentApproachesLowerBoundOfModifiedAndMidOfOriginal) {
  // For large n, 2^(-n/2) -> 0: original -> (n+2)/(8 pi), modified -> (n+2)(n+4)/(8 pi n).
  const double n = 200.0;
  EXPECT_NEAR(BlinnPhong::normalization_factor(n, N::exact, false), (n + 2) / (8 * pi), 1e-12);
  EXPECT_NEAR(BlinnPhong::normalization_factor(n, N::exact, true), (n + 2) * (n + 4) / (8 * pi * n), 1e-12);
}

}  // namespace
}  // namespace shadelab
