#include "shadelab/brdf/lambert.h"

#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {
using testing::dir;
using testing::make;

TEST(Lambert, ValueIsAlbedoOverPi) {
  const auto f = make("lambert", {{"kd", "0.2,0.5,0.9"}});
  const Rgb v = f->eval(dir(30, 10), dir(60, 200));
  EXPECT_DOUBLE_EQ(v.r, 0.2 / pi);
  EXPECT_DOUBLE_EQ(v.g, 0.5 / pi);
  EXPECT_DOUBLE_EQ(v.b, 0.9 / pi);
}

TEST(Lambert, BelowHorizonIsZero) {
  const auto f = make("lambert");
  EXPECT_TRUE(f->eval(dir(100, 0), dir(30, 0)).is_black());
  EXPECT_TRUE(f->eval(dir(30, 0), dir(95, 0)).is_black());
  EXPECT_TRUE(f->eval(Vec3{1.0, 0.0, 0.0}, dir(30, 0)).is_black());  // exactly on the horizon
}

TEST(Lambert, SampleWeightIsAlbedo) {
  const auto f = make("lambert", {{"kd", "0.7"}});
  const auto s = f->sample(dir(40, 0), {0.3, 0.6}, 0.5);
  EXPECT_NEAR(s.pdf, s.wi.z / pi, 1e-15);
  EXPECT_NEAR(s.weight.r, 0.7, 1e-15);
}

}  // namespace
}  // namespace shadelab
