// Tests of the renderers against bad input (issue 16): non-finite samples are counted, thread counts above
// the cores are served, a Scene built in code beyond the scene limits is an error instead of an Embree abort.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "shadelab/core/constants.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/render/test_scenes.h"
#include "shadelab/render/threads.h"

namespace shadelab {
namespace {

using testing::add_material;

// A BRDF that returns NaN where `bad` says so: a stand-in for any formula that breaks at some input.
class NanBrdf final : public Brdf {
 public:
  Rgb eval(const Vec3& wi, const Vec3&) const override {
    return wi.x > 0.0 ? Rgb::gray(std::numeric_limits<double>::quiet_NaN()) : Rgb::gray(inv_pi);
  }
  double pdf(const Vec3& wi, const Vec3&) const override { return wi.z > 0.0 ? wi.z * inv_pi : 0.0; }
  BrdfSample sample(const Vec3&, Vec2 u, double) const override {
    BrdfSample s;
    const double r = std::sqrt(u.x);
    s.wi = {r * std::cos(two_pi * u.y), r * std::sin(two_pi * u.y), std::sqrt(std::max(0.0, 1.0 - u.x))};
    s.pdf = s.wi.z * inv_pi;
    s.weight = s.wi.x > 0.0 ? Rgb::gray(std::numeric_limits<double>::quiet_NaN()) : Rgb::gray(1.0);
    return s;
  }
  Rgb diffuse_albedo() const override { return Rgb::gray(std::numeric_limits<double>::quiet_NaN()); }
};

Scene sphere_scene(bool nan) {
  Scene s;
  s.camera.position = {0.0, 0.0, 4.0};
  s.camera.look_at = {0.0, 0.0, 0.0};
  s.camera.width = 16;
  s.camera.height = 12;
  const int m = add_material(s, "lambert", {});
  if (nan) s.materials[static_cast<std::size_t>(m)].brdf = std::make_shared<NanBrdf>();
  s.spheres.push_back({{0.0, 0.0, 0.0}, 1.0, m});
  s.lights.push_back(DirectionalLight{normalize(Vec3{1.0, 1.0, 1.0}), Rgb::gray(2.0)});
  s.environment.kind = Environment::Kind::uniform;
  s.environment.uniform = Rgb::gray(0.5);
  s.settings.spp = 4;
  s.settings.max_depth = 2;
  return s;
}

// issue 16, 3: renders exited 0 with NaN pixels and said nothing. Both renderers count the samples whose
// radiance is not finite (RenderStats::nonfinite_samples); a sound scene has none.
TEST(RenderLimits, NonFiniteSamplesAreCounted) {
  const Scene good = sphere_scene(false);
  const Scene bad = sphere_scene(true);
  const auto ref_good = render_scene(good);
  ASSERT_TRUE(ref_good) << ref_good.error().message;
  EXPECT_EQ(ref_good->stats.nonfinite_samples, 0u);
  const auto ref_bad = render_scene(bad);
  ASSERT_TRUE(ref_bad) << ref_bad.error().message;
  // Samples that meet the NaN half of the lobe are counted: some, never more than all.
  std::size_t nan_pixels = 0;
  for (float v : ref_bad->beauty.data) nan_pixels += std::isfinite(v) ? 0 : 1;
  EXPECT_GT(ref_bad->stats.nonfinite_samples, 0u);
  EXPECT_GT(nan_pixels, 0u);
  EXPECT_LE(ref_bad->stats.nonfinite_samples, static_cast<std::uint64_t>(16 * 12 * 4));
  const auto game_good = render_game(good);
  ASSERT_TRUE(game_good);
  EXPECT_EQ(game_good->stats.nonfinite_samples, 0u);
  const auto game_bad = render_game(bad);
  ASSERT_TRUE(game_bad);
  EXPECT_GT(game_bad->stats.nonfinite_samples, 0u);
}

// issue 16, 1: --threads 100000 crashed inside TBB, and every count above the cores printed a TBB warning.
// The arena gets at most the cores; the image is the same as with one thread.
TEST(RenderLimits, ThreadCountsAboveTheCoresGiveTheSameImage) {
  EXPECT_EQ(arena_threads(100000), arena_threads(0));
  EXPECT_EQ(arena_threads(1), 1);
  EXPECT_GE(arena_threads(0), 1);
  const Scene s = sphere_scene(false);
  RenderOptions one;
  one.threads = 1;
  RenderOptions many;
  many.threads = 100000;
  const auto a = render_scene(s, one);
  const auto b = render_scene(s, many);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->beauty.data, b->beauty.data);
  GameOptions g;
  g.threads = 100000;
  EXPECT_TRUE(render_game(s, g));
}

// issue 16, 1: a camera 2e18 from the origin (or an up that does not normalize) failed Embree's ray.valid()
// assertion, SIGABRT. A Scene built in code is checked like a scene file: an error naming the field.
TEST(RenderLimits, SceneBeyondTheLimitsIsAnErrorNotAnAbort) {
  Scene s = sphere_scene(false);
  s.camera.position = {0.0, 0.0, 2e18};
  s.camera.look_at = {0.0, 0.0, 0.0};
  const auto r = render_scene(s);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("camera position"), std::string::npos) << r.error().message;
  const auto g = render_game(s);
  ASSERT_FALSE(g);
  Scene bright = sphere_scene(false);
  bright.environment.uniform = Rgb::gray(1e39);  // beyond float: the environment sampler's table overflowed
  const auto e = render_scene(bright);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("environment uniform"), std::string::npos) << e.error().message;
}

}  // namespace
}  // namespace shadelab
