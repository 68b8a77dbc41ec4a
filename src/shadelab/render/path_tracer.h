// shadelab reference renderer: a unidirectional path tracer that solves the rendering equation
//   L(x -> wo) = Le(x -> wo) + integral over the hemisphere of L(x <- wi) f_r(wi, wo) cos(theta_i) d(wi)
// (lecture 5) with the same BRDF code the analysis and the game renderer use.
//
// - Next-event estimation: one light per vertex, chosen uniformly among the scene's lights (delta lights,
//   sphere lights, emissive spheres, quads and disks, the environment), with a shadow ray; multiple
//   importance sampling with the power heuristic (Veach 1997) between that and BRDF sampling for every
//   light that BRDF sampling can hit. Delta lights are reached by light sampling only.
// - Russian roulette from RenderSettings::rr_depth on, with survival probability min(1, max(throughput)).
// - Paths start at the camera, so at each vertex wo points toward the camera and wi toward the light, the
//   orientation the published non-reciprocal forms (original Phong and Blinn-Phong, wrapped diffuse) are
//   defined for; no adjoint (light-to-camera) transport is done, so their non-reciprocity is never flipped.
// - Surfaces are two-sided: the shading frame faces the incoming ray. Quads and disks emit on the side their
//   normal points to, spheres outward.
// - Deterministic: sample s of pixel p draws from PCG32 seeded by (scene seed, p) on stream s, and each pixel's
//   samples are summed in order, so the image is bit-identical for any thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "shadelab/core/error.h"
#include "shadelab/image/image.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

enum class SamplingMode {
  mis,    // BRDF sampling and light sampling combined with the power heuristic
  brdf,   // BRDF sampling only (emitters count when hit; delta lights are invisible)
  light,  // light sampling only (emitters hit by BRDF rays after the camera ray do not count)
};

struct RenderOptions {
  SamplingMode mode = SamplingMode::mis;
  int spp = -1;        // -1: the scene's
  int max_depth = -1;  // -1: the scene's
  int threads = -1;    // -1: the scene's (0 there: all cores)
  bool aovs = false;   // albedo, normal and depth of the first hit
  std::function<void(double fraction, int spp_done)> progress;  // after each pass, on the calling thread
  const std::atomic<bool>* cancel = nullptr;  // checked between passes; the finished passes are kept
};

struct RenderStats {
  int spp_done = 0;
  std::uint64_t camera_rays = 0;
  std::uint64_t rays = 0;  // all rays traced: camera, bounce and shadow
  double seconds = 0.0;
  bool cancelled = false;
  // Samples whose radiance was NaN or infinite (kept in the image as they are): a render that has any is
  // wrong, and the CLI says so and exits with 1 (docs/cli.md).
  std::uint64_t nonfinite_samples = 0;
};

struct RenderResult {
  Image beauty;  // linear radiance, W m^-2 sr^-1
  Image albedo;  // first-hit directional albedo (one-sample estimates averaged), if aovs
  Image normal;  // first-hit shading normal, world space, components in [-1, 1], if aovs
  Image depth;   // first-hit distance along the camera ray (0 where nothing is hit), if aovs
  RenderStats stats;
};

// Errors: a material whose model cannot take a texture's parameter, or an invalid setting.
Result<RenderResult> render_scene(const Scene& scene, const RenderOptions& options = {});

// The radiance along one camera ray (for tests): `samples` independent paths averaged, and their standard
// error, from the given seed.
struct RadianceEstimate {
  Rgb mean;
  Rgb standard_error;
};
Result<RadianceEstimate> estimate_radiance(const Scene& scene, const Vec3& origin, const Vec3& direction, int samples,
                                           SamplingMode mode = SamplingMode::mis, int max_depth = -1,
                                           std::uint64_t seed = 1);

}  // namespace shadelab
