#include "shadelab/brdf/minimalist_cook_torrance.h"

#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {
using testing::dir;
using testing::make;

TEST(MinimalistCookTorrance, MatchesShaderX7Formula) {
  const double n = 64.0;
  const auto f = make("minimalist-cook-torrance", {{"kd", "0.3"}, {"ks", "0.05"}, {"n", "64"}});
  const Vec3 l = dir(50, 0);
  const Vec3 v = dir(40, 175);
  const Vec3 h = normalize(l + v);
  const double expected = 0.3 / pi + 0.05 * (n + 1) * std::pow(h.z, n) / (8 * pi * std::pow(dot(l, h), 3));
  EXPECT_NEAR(f->eval(l, v).r, expected, 1e-13 * expected);
}

TEST(MinimalistCookTorrance, IsNdfTimesCombinedFV) {
  // f_spec = D F V with D = (n+1)/(2pi) (N.H)^n and FV = 1/(4 (L.H)^3) (zoo article decomposition).
  const double n = 10.0;
  const auto f = make("minimalist-cook-torrance", {{"kd", "0"}, {"ks", "1"}, {"n", "10"}});
  const Vec3 l = dir(75, 20);
  const Vec3 v = dir(5, 90);
  const Vec3 h = normalize(l + v);
  const double d = (n + 1) / (2 * pi) * std::pow(h.z, n);
  const double fv = 0.25 / std::pow(dot(v, h), 3);
  EXPECT_NEAR(f->eval(l, v).g, d * fv, 1e-13 * d * fv);
  EXPECT_TRUE(f->is_reciprocal());
}

}  // namespace
}  // namespace shadelab
