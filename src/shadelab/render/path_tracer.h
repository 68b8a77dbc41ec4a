// shadelab reference renderer: a unidirectional path tracer that solves the rendering equation
//   L(x -> wo) = Le(x -> wo) + integral over the hemisphere of L(x <- wi) f_r(wi, wo) cos(theta_i) d(wi)
// (lecture 5) with the same BRDF code the analysis and the game renderer use.
//
// - Next-event estimation: one light per vertex, chosen uniformly among the scene's lights (delta lights,
//   sphere lights, emissive spheres, quads and disks, the environment), with a shadow ray; multiple
//   importance sampling with the power heuristic (Veach 1997) between that and BRDF sampling for every
//   light that BRDF sampling can hit. Delta lights are reached by light sampling only. A constant environment
//   (no sun, no hemisphere light) is not light-sampled: BRDF sampling reaches it with weight 1 (as Cycles with a
//   constant world), and the light samples go to the other lights.
// - Russian roulette from RenderSettings::rr_depth on, with survival probability min(1, sqrt(max(throughput)))
//   (Cycles' rule).
// - Paths start at the camera, so at each vertex wo points toward the camera and wi toward the light, the
//   orientation the published non-reciprocal forms (original Phong and Blinn-Phong, wrapped diffuse) are
//   defined for; no adjoint (light-to-camera) transport is done, so their non-reciprocity is never flipped.
// - Surfaces are two-sided: the shading frame faces the incoming ray. Quads and disks emit on the side their
//   normal points to, spheres outward.
// - Sampling: Owen-scrambled Sobol points (sampling/owen.h), indexed by (pixel, sample index, dimension): the
//   camera jitter is group 0 and vertex v uses group 2v - 1 for its light sample and group 2v for its BRDF
//   sample and Russian roulette. Any sample of any pixel can be computed alone, so the image does not depend
//   on the thread count (and a sample range or a tile can be rendered anywhere); each pixel's samples are
//   summed exactly (fixed_sum.h), so the sum does not depend on the grouping of samples either: a render split
//   into shards and merged gives the same bits as one render.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/image/image.h"
#include "shadelab/render/fixed_sum.h"
#include "shadelab/sampling/owen.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

// A part of a render for scale-out (docs/scale-out.md): shard `index` of `count`, split by samples (every
// pixel, the sample indices [spp index / count, spp (index + 1) / count)) or by tiles (every sample of the
// 16 x 16 tiles t, numbered row-major, with t % count == index). count 1 is the whole render.
enum class ShardSplit { samples, tiles };
struct ShardSpec {
  int index = 0;
  int count = 1;
  ShardSplit split = ShardSplit::samples;
};
inline constexpr int render_tile_size = 16;

// The sample indices [first, second) shard `shard` renders of every pixel it covers.
std::pair<int, int> shard_sample_range(int spp, const ShardSpec& shard);
// Whether shard `shard` renders tile `tile` (row-major index of the 16 x 16 tiles).
bool shard_owns_tile(int tile, const ShardSpec& shard);

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
  SamplerKind sampler = SamplerKind::owen_sobol;
  ShardSpec shard;     // the whole render by default
  bool aovs = false;   // albedo, normal and depth of the first hit
  std::function<void(double fraction, int spp_done)> progress;  // after each pass, on the calling thread
  const std::atomic<bool>* cancel = nullptr;  // checked between passes; the finished passes are kept
  // Checked before each tile of each pass: once set, the render stops within a tile and returns the error
  // "render stopped" with no image (the Python module's Ctrl-C: a pass of a large image takes seconds).
  const std::atomic<bool>* abort = nullptr;
};

struct RenderStats {
  int spp_done = 0;
  std::uint64_t camera_rays = 0;
  std::uint64_t rays = 0;  // all rays traced: camera, bounce and shadow
  double seconds = 0.0;         // the whole call: preparation (BVH, light tables) and sampling
  double render_seconds = 0.0;  // sampling only (what Cycles calls render time without synchronisation)
  bool cancelled = false;
  // Samples whose radiance was NaN or infinite: a render that has any is wrong, and the CLI says so and exits
  // with 1 (docs/cli.md). They cannot enter the exact sums (fixed_sum.h): they are counted per pixel
  // (RenderResult::nonfinite) and a pixel with any is NaN in the image, so they can be found.
  std::uint64_t nonfinite_samples = 0;
};

struct RenderResult {
  // Exact per-pixel sums of the samples rendered (row-major; zero for pixels a tile shard does not cover):
  // beauty = sums / samples. What a shard writes and `shadelab merge` adds.
  std::vector<FixedRgb> sums;
  std::vector<std::uint32_t> nonfinite;  // per pixel, the samples that were NaN or infinite (not in sums)
  int sample_begin = 0, sample_end = 0;  // the sample indices rendered of every covered pixel
  Image beauty;  // linear radiance, W m^-2 sr^-1
  Image albedo;  // first-hit directional albedo (one-sample estimates averaged), if aovs
  Image normal;  // first-hit shading normal, world space, components in [-1, 1], if aovs
  Image depth;   // first-hit distance along the camera ray (0 where nothing is hit), if aovs
  RenderStats stats;
};

// The image of exact per-pixel sums (row-major): sums / samples, then rounded to float; NaN where the pixel had
// a non-finite sample (nonfinite[p] > 0; nonfinite may be empty: none). render_scene and the shard merge both
// produce their images with it.
Image image_from_sums(const std::vector<FixedRgb>& sums, const std::vector<std::uint32_t>& nonfinite, int width, int height,
                      std::uint64_t samples);

// Errors: a material whose model cannot take a texture's parameter, or an invalid setting.
Result<RenderResult> render_scene(const Scene& scene, const RenderOptions& options = {});

// The radiance along one camera ray (for tests): `samples` paths averaged, and their standard error, from the
// given seed. The paths are 64 (or `samples`, if fewer) independent randomizations of the sampler (replicas,
// each with its own pixel seed) of samples / 64 paths each; the standard error is that of the replicas' means,
// which is honest for stratified samples (the per-path variance would overstate it).
struct RadianceEstimate {
  Rgb mean;
  Rgb standard_error;
};
Result<RadianceEstimate> estimate_radiance(const Scene& scene, const Vec3& origin, const Vec3& direction, int samples,
                                           SamplingMode mode = SamplingMode::mis, int max_depth = -1,
                                           std::uint64_t seed = 1, SamplerKind sampler = SamplerKind::owen_sobol);

}  // namespace shadelab
