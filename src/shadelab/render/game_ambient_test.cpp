// Game-mode ambient against closed forms: D3DX-style SH9 directional lights (issue 16, 7) and the wrapped-
// diffuse SH factors under a uniform environment, where game shading and the reference differ by design.
#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/light/units.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/render/test_scenes.h"

namespace shadelab {
namespace {

using testing::add_material;

// A unit sphere of white-ish Lambert lit by one directional light toward +Y of game colour c.
Scene sh_light_scene(bool game_sh, const Rgb& colour_game) {
  Scene s;
  s.spheres.push_back({{0.0, 0.0, 0.0}, 1.0, add_material(s, "lambert", {{"kd", "0.8"}})});
  DirectionalLight l{{0.0, 1.0, 0.0}, irradiance_from_game(colour_game)};
  l.game_sh = game_sh;
  s.lights.emplace_back(l);
  return s;
}

// The order-3 SH truncation of a delta light, in the game convention (E/pi) and scaled by 16/17
// (D3DXSHEvalDirectionalLight), seen by a normal at angle theta from the light:
//   (16/17) c (1/4 + (1/2) cos + (5/16) P2(cos)),  P2(t) = (3 t^2 - 1)/2  (Ramamoorthi & Hanrahan 2001 bands
// 1, 2/3, 1/4 times the delta's coefficients (2l + 1)/(4 pi) pi c). Facing: c; at 90 degrees: 3c/34.
double d3dx_truncated(double cos_theta) {
  const double p2 = 0.5 * (3.0 * cos_theta * cos_theta - 1.0);
  return 16.0 / 17.0 * (0.25 + 0.5 * cos_theta + 5.0 / 16.0 * p2);
}

TEST(GameAmbient, DirectionalLightInShGivesTheColourFacingIt) {
  const Rgb c{1.0, 0.5, 0.25};
  const Scene sh = sh_light_scene(true, c);
  const Scene punctual = sh_light_scene(false, c);
  struct Case {
    Vec3 eye, dir;
    double cos_theta;
  };
  const Case cases[] = {{{0.0, 3.0, 0.0}, {0.0, -1.0, 0.0}, 1.0},                            // facing the light
                        {{3.0, 0.0, 0.0}, {-1.0, 0.0, 0.0}, 0.0},                            // 90 degrees
                        {{0.0, -3.0, 0.0}, {0.0, 1.0, 0.0}, -1.0},                           // facing away
                        {{3.0, 3.0, 0.0}, normalize(Vec3{-1.0, -1.0, 0.0}), std::sqrt(0.5)}};  // 45 degrees
  for (const Case& k : cases) {
    const Rgb game = game_radiance(sh, k.eye, k.dir).value();
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(game[ch], 0.8 * c[ch] * d3dx_truncated(k.cos_theta), 1e-9) << "cos " << k.cos_theta << " channel " << ch;
    }
  }
  // Facing it, exactly the Lambert value of the punctual light (kd c); at 90 degrees the punctual light gives
  // 0 and the SH light its ringing, 3/34 of kd c.
  EXPECT_NEAR(game_radiance(sh, cases[0].eye, cases[0].dir).value().r, game_radiance(punctual, cases[0].eye, cases[0].dir).value().r, 1e-9);
  EXPECT_NEAR(d3dx_truncated(0.0), 3.0 / 34.0, 1e-15);
  EXPECT_EQ(game_radiance(punctual, cases[1].eye, cases[1].dir).value().r, 0.0);
  // The option does for every directional light what the mark does for one.
  GameOptions all;
  all.directional_in_sh = true;
  EXPECT_NEAR(game_radiance(punctual, cases[3].eye, cases[3].dir, all).value().g,
              game_radiance(sh, cases[3].eye, cases[3].dir).value().g, 1e-12);
  // Without SH ambient there are no coefficients: the light is shaded per pixel.
  GameOptions map;
  map.diffuse = GameAmbient::none;
  EXPECT_EQ(game_radiance(sh, cases[1].eye, cases[1].dir, map).value().r, 0.0);
}

// issue 16, 7: the SH wrap factors (1, (2 - w)/3, (1 - w)^2/4) are the bands of the kernel
// max(0, cos + w)/(pi (1 + w)^2) over the whole sphere, which reaches below the horizon to cos = -w; the
// wrapped-diffuse BRDF is 0 there. Under a uniform environment L the game value is kd L and the reference
// kd L (1 + 2w)/(1 + w)^2: 0.889 kd L at w = 0.5. Checked three ways against a midpoint rule written here.
TEST(GameAmbient, WrappedDiffuseUnderAUniformEnvironmentDiffersByTheHorizon) {
  const double kd = 0.8;
  const double L = 0.5;
  for (double w : {0.0, 0.25, 0.5, 1.0}) {
    // Hemisphere and whole-kernel integrals by a midpoint rule in cos(theta) (the kernel has no phi).
    const int n = 200000;
    double hemisphere = 0.0, kernel = 0.0;
    for (int i = 0; i < n; ++i) {
      const double t = -1.0 + (i + 0.5) * 2.0 / n;
      const double k = std::max(0.0, t + w) / (pi * (1.0 + w) * (1.0 + w));
      kernel += two_pi * k * 2.0 / n;
      if (t > 0.0) hemisphere += two_pi * k * 2.0 / n;
    }
    const double expected_ratio = (1.0 + 2.0 * w) / ((1.0 + w) * (1.0 + w));
    EXPECT_NEAR(kernel, 1.0, 1e-6) << w;
    EXPECT_NEAR(hemisphere, expected_ratio, 1e-6) << w;
    // The BRDF's own eval over the upper hemisphere (f cos by the same rule).
    auto brdf = make_brdf("wrapped-diffuse", {{"kd", "0.8"}, {"w", std::to_string(w)}}).value();
    double f_cos = 0.0;
    for (int i = 0; i < n; ++i) {
      const double t = (i + 0.5) / n;
      f_cos += two_pi * brdf->eval({std::sqrt(1.0 - t * t), 0.0, t}, {0.0, 0.0, 1.0}).r * t / n;
    }
    EXPECT_NEAR(f_cos, kd * expected_ratio, 1e-6) << w;

    // The renderers: game shading (SH9 with the wrap factors) gives kd L, the reference kd L x the ratio
    // (BRDF sampling: the wrapped sampler's weight is the constant kd (1+2w)/(1+w)^2, so no noise).
    Scene s;
    s.spheres.push_back({{0.0, 0.0, 0.0}, 1.0, add_material(s, "wrapped-diffuse", {{"kd", "0.8"}, {"w", std::to_string(w)}})});
    s.environment.kind = Environment::Kind::uniform;
    s.environment.uniform = Rgb::gray(L);
    GameOptions diffuse_only;
    diffuse_only.specular_ambient = false;
    const Vec3 eye{0.3, 0.2, 3.0};
    const Vec3 dir = normalize(Vec3{0.0, 0.0, 0.0} - eye);
    const double game = game_radiance(s, eye, dir, diffuse_only).value().g;
    const auto ref = estimate_radiance(s, eye, dir, 64, SamplingMode::brdf, 1).value();
    EXPECT_NEAR(game, kd * L, 1e-6) << w;
    EXPECT_NEAR(ref.mean.g, kd * L * expected_ratio, 1e-9) << w;
    EXPECT_NEAR(game / ref.mean.g, 1.0 / expected_ratio, 1e-5) << w;
  }
  EXPECT_NEAR((1.0 + 2.0 * 0.5) / (1.5 * 1.5), 0.8889, 1e-4);
}

}  // namespace
}  // namespace shadelab
