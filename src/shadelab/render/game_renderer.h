// shadelab game shading: the same scene shaded as a game engine shades it, per pixel, with no light
// transport beyond one bounce of punctual light and baked ambient, calling the same BRDF code as the path
// tracer.
//
// At the first hit of each camera ray (Lagarde 2012, "PI or not to PI"; the zoo article's shader form):
//   punctual lights, in game units c = E_perp / pi:   L += pi f(wi, wo) c cos(theta_i)   [x shadow ray]
//     sphere lights as their point-light limit I = pi L r0^2 (zoo article), the sky's sun as a directional
//     light of its irradiance;
//   diffuse ambient:   L += rho_d * (E / pi)(n) from SH9 (or the irradiance cube map) baked from the scene's
//     environment (hemisphere lights included, the sun excluded), with the wrapped band factors for
//     wrapped-diffuse materials;
//   specular ambient:  L += rho_s(wo) * prefiltered(R, n_phong), the prefiltered cube's level for the
//     material's lobe width and the specular lobe's directional albedo rho_s (a per-material table over
//     cos(theta_o), from the BRDF's own sampler, fixed seed);
//   emission of the surface seen; the environment seen directly.
// The formulas are the kernels shaders share (kernels/game_shading.sl: the punctual term and the inverse
// square law; game_ambient.sl: the ambient terms, the mirror direction, the albedo table lookup and the
// prefiltered level; sh9.sl), and the per-material numbers come from brdf/game_lobe.h, so the browser
// explorer's sphere (web/) shades with the same text.
// Directional lights marked game_sh (or all of them with directional_in_sh) are not shaded per pixel: each is
// added to the SH9 coefficients as D3DXSHEvalDirectionalLight does (sh9_directional_light, scaled so a white
// Lambert surface facing a light of game colour c shows exactly c), so they light the diffuse ambient only,
// with the order-3 ringing of a delta (3c/34 at 90 degrees), and cast no shadow. With GameAmbient other than
// sh9 there are no SH coefficients and they are shaded as punctual lights.
// No interreflection, no area lights besides the point limit of sphere lights: these are the approximations
// `shadelab report` measures against the reference.
// `drop_pi` is a debug switch that forgets the pi of the game unit (L += f c cos): the tests use it to show
// that the agreement test can fail.
#pragma once

#include "shadelab/envmap/prefilter.h"
#include "shadelab/envmap/sh.h"
#include "shadelab/render/env_light.h"
#include "shadelab/render/path_tracer.h"

namespace shadelab {

enum class GameAmbient { sh9, irradiance_map, none };

struct GameOptions {
  bool shadows = true;
  GameAmbient diffuse = GameAmbient::sh9;
  bool specular_ambient = true;
  bool punctual = true;
  bool drop_pi = false;   // debug: forget the pi of the game light unit
  bool directional_in_sh = false;  // every directional light into the SH9 ambient, as if marked game_sh
  int spp = 4;            // antialiasing samples per pixel (stratified, deterministic)
  int threads = -1;       // -1: the scene's
  int environment_size = 64;  // face size the environment is baked at
  int specular_size = 64;     // face size of the prefiltered cube's level 0
};

Result<RenderResult> render_game(const Scene& scene, const GameOptions& options = {});

// The environment as game shading bakes it: the radiance without the sky's sun (env_light.h), point-sampled
// at the texel centres of a cube of options.environment_size (kept as radiance); its SH9 projection (radiance units: evaluate
// with sh9_irradiance_game for E/pi); the irradiance cube in game units (GameAmbient::irradiance_map only);
// and the prefiltered specular chain of options.specular_size (options.specular_ambient only). has_light is
// false, and the rest empty, for a scene with neither an environment nor hemisphere lights. The browser
// explorer (web/) bakes its HDRIs with it, so its sphere is lit by exactly what `render --mode game` uses.
struct GameEnvironment {
  bool has_light = false;
  CubeMap radiance;  // the point-sampled cube of options.environment_size that the rest is baked from
  Sh9 sh;
  CubeMap irradiance;
  PrefilteredCube specular;
};
Result<GameEnvironment> bake_game_environment(const Scene& scene, const GameOptions& options = {});
Result<GameEnvironment> bake_game_environment(const EnvironmentLight& env, const GameOptions& options = {});

// The game-shaded radiance along one camera ray (for tests).
Result<Rgb> game_radiance(const Scene& scene, const Vec3& origin, const Vec3& direction, const GameOptions& options = {});

}  // namespace shadelab
