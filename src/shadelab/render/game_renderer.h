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
//     cos(theta_o), from the BRDF's own sampler, fixed seed) -- the Phong-family models;
//   split-sum specular ambient for the microfacet-GGX models (ggx, filament; GameGgxSpecular::split_sum,
//     opt-in for now), as engines ship it (Karis 2013; Filament's documentation, "Image based lights"):
//     L += prefiltered_ggx(R, r) (f0 A(N.V, r) + f90 B(N.V, r)), the GGX chain of envmap/prefilter_ggx.h
//     (linear roughness-to-lod mapping, options.specular_size) read at the hit's perceptual roughness r and
//     A, B from a DFG table (envmap/dfg.h, options.dfg_size, read bilinearly by dfg_lookup); f0, f90 and the
//     energy terms from brdf/game_lobe.h ggx_split_sum_lobe: filament's compensation multiplies by
//     1 + f0 (1/E - 1), ggx's Kulla-Conty lobe adds ks F_ms (1 - E) (E/pi)(n), E = A + B of the same table.
//     For a constant environment L and the model's Schlick Fresnel and height-correlated G2 this is exact up
//     to the table's interpolation: integral L f cos = L (f0 A + f90 B) by the definition of A and B.
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

#include <atomic>

#include <memory>

#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/envmap/specular/prefilter.h"
#include "shadelab/envmap/specular/prefilter_ggx.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/envmap/specular/split_sum_lobes.h"
#include "shadelab/render/env_light.h"
#include "shadelab/render/path_tracer.h"

namespace shadelab {

enum class GameAmbient { sh9, irradiance_map, none };

// The specular ambient of the microfacet-GGX models (those whose BRDF answers split_sum_inputs(): ggx,
// filament): the split sum with a GGX-prefiltered chain and a DFG table (the default since 2026-12-07, as
// engines ship it), or the Phong chain the Phong-family models use (`render --ggx-specular phong`; the
// browser explorer's WebGL sphere still shades GGX on it: docs/renderer.md).
enum class GameGgxSpecular { split_sum, phong };

// The split-sum lookup (the one name for the concept: C++ GameSplitSumLookup, `render --split-sum-lookup`,
// `ibl-error --split-sum-lookup` (alias --correction), JSON split_sum_lookup, kernels/game_ibl.sl
// SPLIT_SUM_LOOKUP_*): where and how rough the split sum reads its GGX chain. The mirror direction R (Karis 2013 as published), or
// the dominant direction normalize(mix(R, n, alpha^2)) (kernels/game_ambient.sl game_split_sum_lookup),
// which `shadelab ibl-error` measured to cut the split sum's mean error at N.V < 0.3 on sunrise.exr from
// 26.6% to 15.8% (docs/envmap.md). The same storage: the same chain and DFG table.
// `lobes` (the default since 2026-12-04): each part of the split sum (f0 A, f90 B) read once, along and at the
// roughness that match the first moments of its true lobe (envmap/split_sum_lobes.h): two reads of the same
// chain, the same storage; on all eight blender-data maps its mean error over the map is below R's, for a
// dielectric and for a metal (docs/envmap.md).
// `filtered`: each part averaged over its own true lobe by split_sum_taps taps of the same chain, each read
// with the footprint of its share of solid angle (envmap/split_sum_taps.h): the same storage, N reads.
enum class GameSplitSumLookup { mirror, dominant, lobes, filtered };
static_assert(static_cast<int>(GameSplitSumLookup::mirror) == kernel::SPLIT_SUM_LOOKUP_MIRROR &&
              static_cast<int>(GameSplitSumLookup::dominant) == kernel::SPLIT_SUM_LOOKUP_DOMINANT &&
              static_cast<int>(GameSplitSumLookup::lobes) == kernel::SPLIT_SUM_LOOKUP_LOBES);

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
  // Each baked texel is the solid-angle-weighted mean of environment_supersample^2 directions over it
  // (1: its centre's radiance, as before 2026-12-03; a point-sampled 64^2 cube held 0.889 of sunrise's
  // luminous flux, 8 x 8 holds 0.993: docs/envmap.md, ibl-error). In [1, 32].
  int environment_supersample = 8;
  int specular_size = 64;     // face size of the prefiltered cube's level 0
  GameGgxSpecular ggx_specular = GameGgxSpecular::split_sum;
  // The GGX chain's method (prefilter_ggx.h): sum (every level of a 64 chain an exact sum) or sampled, with
  // ggx_samples Hammersley half vectors per texel (with 1024 its faces of 16 and below are exact sums).
  GgxFilterMethod ggx_method = GgxFilterMethod::sum;
  int ggx_samples = 1024;
  int dfg_size = 64;          // the split sum's DFG table (dfg.h), baked once per process per size
  GameSplitSumLookup split_sum_lookup = GameSplitSumLookup::lobes;
  int split_sum_taps = 64;  // split_sum_lookup filtered: taps per pixel, in [1, 1024]
  // Checked after the environment bake and before each 16 x 16 tile: once set, the tiles not yet begun are
  // skipped (black) and RenderStats::cancelled is true (the Python module's Ctrl-C, render.cpp).
  const std::atomic<bool>* cancel = nullptr;
};

Result<RenderResult> render_game(const Scene& scene, const GameOptions& options = {});

// The environment as game shading bakes it: the radiance without the sky's sun (env_light.h), resampled to a
// cube of options.environment_size, each texel the mean over options.environment_supersample^2 directions
// (kept as radiance); its SH9 projection (radiance units: evaluate
// with sh9_irradiance_game for E/pi); the irradiance cube in game units (GameAmbient::irradiance_map only);
// and the prefiltered specular chain of options.specular_size (options.specular_ambient only), and its GGX
// chain (options.specular_ambient with ggx_specular = split_sum; render_game bakes it only for a scene with
// a ggx or filament material). has_light is
// false, and the rest empty, for a scene with neither an environment nor hemisphere lights. The browser
// explorer (web/) bakes its HDRIs with it, so its sphere is lit by exactly what `render --mode game` uses.
struct GameEnvironment {
  bool has_light = false;
  CubeMap radiance;  // the resampled cube of options.environment_size that the rest is baked from
  Sh9 sh;
  CubeMap irradiance;
  PrefilteredCube specular;
  GgxPrefilteredCube specular_ggx;
  // The split sum's tables when they come from files (`shader verify --ibl` shades with exactly the files
  // `bake ibl` wrote): null, the renderer's own, game_dfg_table(options.dfg_size) and split_sum_lobe_table().
  std::shared_ptr<const DfgTable> dfg;
  std::shared_ptr<const SplitSumLobeTable> lobes;
};
Result<GameEnvironment> bake_game_environment(const Scene& scene, const GameOptions& options = {});
Result<GameEnvironment> bake_game_environment(const EnvironmentLight& env, const GameOptions& options = {});

// render_game with the environment already baked: `baked` must be bake_game_environment(scene, o) for options
// o that agree with `options` in every field the bake reads (environment_size, environment_supersample,
// diffuse, specular_ambient, specular_size, ggx_specular, ggx_method, ggx_samples), so that several renders of one
// environment (ibl-error's rows, a sweep) bake it once. An error if `baked` lacks what `options` reads: an
// environment while the scene has one, the irradiance cube for GameAmbient::irradiance_map, the Phong chain
// with specular_ambient, the GGX chain for a split-sum material.
Result<RenderResult> render_game(const Scene& scene, const GameOptions& options, const GameEnvironment& baked);

// The specular ambient each of the scene's materials gets under these options, in the scene's material order:
// split_sum (its BRDF answers split_sum_inputs() and options.ggx_specular is split_sum), phong_chain (a
// specular lobe, game_phong_exponent() > 0, on the Phong chain), or none (no specular lobe, no environment or
// hemisphere light to reflect, or options.specular_ambient off). `render --mode game --json` reports it.
enum class GameSpecularAmbient { split_sum, phong_chain, none };
const char* game_specular_ambient_name(GameSpecularAmbient a);  // "split-sum", "phong-chain", "none"
Result<std::vector<GameSpecularAmbient>> game_specular_ambients(const Scene& scene, const GameOptions& options = {});

// The DFG table the split sum reads (height-correlated, single scattering, quadrature), baked on first use
// for each size and kept for the process (thread-safe). size in [1, 4096].
const DfgTable& game_dfg_table(int size);

// The game-shaded radiance along one camera ray (for tests).
Result<Rgb> game_radiance(const Scene& scene, const Vec3& origin, const Vec3& direction, const GameOptions& options = {});

}  // namespace shadelab
