#include "shadelab/brdf/lafortune.h"

#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {
using testing::dir;
using testing::make;

TEST(Lafortune, MirrorLobeIsUnnormalizedModifiedPhong) {
  // Cx = Cy = -1, Cz = 1: the dot product becomes R.L, R the mirror of V (Lafortune 1997, section 4).
  const auto laf = make("lafortune", {{"kd", "0"}, {"ks", "1"}, {"lobes", "-1,-1,1,15"}});
  const auto phong = make("phong-modified", {{"kd", "0"}, {"ks", "1"}, {"n", "15"}, {"normalization", "none"}});
  for (double t : {10.0, 40.0, 70.0}) {
    const Rgb a = laf->eval(dir(t, 175), dir(35, 0));
    const Rgb b = phong->eval(dir(t, 175), dir(35, 0));
    EXPECT_NEAR(a.r, b.r, 1e-14 * std::max(1e-300, b.r)) << t;
  }
}

TEST(Lafortune, SeveralLobesAdd) {
  const auto f = make("lafortune", {{"kd", "0.1"}, {"ks", "0.5"}, {"lobes", "-1,-1,1,10;0.8,0.8,0.6,3"}});
  const Vec3 l = dir(30, 10);
  const Vec3 v = dir(50, 20);
  const double c1 = -l.x * v.x - l.y * v.y + l.z * v.z;
  const double c2 = 0.8 * l.x * v.x + 0.8 * l.y * v.y + 0.6 * l.z * v.z;
  const double expected = 0.1 / pi + 0.5 * ((c1 > 0 ? std::pow(c1, 10.0) : 0.0) + std::pow(c2, 3.0));
  EXPECT_NEAR(f->eval(l, v).r, expected, 1e-14 * expected);
}

TEST(Lafortune, BadLobesAreRejected) {
  EXPECT_FALSE(make_brdf("lafortune", {{"lobes", "1,2,3"}}).has_value());
  EXPECT_FALSE(make_brdf("lafortune", {{"lobes", "-1,-1,1,-2"}}).has_value());
  EXPECT_FALSE(make_brdf("lafortune", {{"lobes", "-1,-1,1,nan"}}).has_value());
}

}  // namespace
}  // namespace shadelab
