#include "shadelab/brdf/wrapped_diffuse.h"

#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {
using testing::dir;
using testing::make;

TEST(WrappedDiffuse, ZeroWrapIsLambert) {
  const auto w = make("wrapped-diffuse", {{"kd", "0.6"}, {"w", "0"}});
  const auto l = make("lambert", {{"kd", "0.6"}});
  EXPECT_DOUBLE_EQ(w->eval(dir(33, 0), dir(10, 0)).r, l->eval(dir(33, 0), dir(10, 0)).r);
  EXPECT_TRUE(w->is_reciprocal());
}

TEST(WrappedDiffuse, ResponseIsMcAuleyForm) {
  // f cos = kd (N.L + w) / (pi (1 + w)^2)
  const auto f = make("wrapped-diffuse", {{"kd", "0.8"}, {"w", "0.5"}});
  const Vec3 l = dir(80, 0);
  EXPECT_NEAR(f->eval(l, dir(0, 0)).r * l.z, 0.8 * (l.z + 0.5) / (pi * 2.25), 1e-15);
  EXPECT_FALSE(f->is_reciprocal());
}

TEST(WrappedDiffuse, SampleWeightIsConstant) {
  const auto f = make("wrapped-diffuse", {{"kd", "1"}, {"w", "0.5"}});
  for (double u : {0.1, 0.5, 0.9}) {
    const auto s = f->sample(dir(20, 0), {u, 0.3}, u);
    EXPECT_NEAR(s.weight.r, 2.0 / 2.25, 1e-14);  // (1 + 2w)/(1 + w)^2
  }
}

}  // namespace
}  // namespace shadelab
