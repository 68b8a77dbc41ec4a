// shadelab shard files: one part of a render split over processes or machines, and their merge
// (docs/scale-out.md).
//
// A shard file is an OpenEXR file with
// - the channels R, G, B (float): the shard's own mean over the samples it rendered, 0 where it rendered
//   nothing, so that any EXR viewer shows the part;
// - the channels sum.R.w0 .. sum.B.w3 (uint): the exact per-pixel sums (fixed_sum.h), each 128-bit channel
//   sum as four 32-bit words, least significant first, two's complement;
// - the channel nonfinite (uint): per pixel, the samples that were NaN or infinite (not in the sums);
// - the header attribute "shadelab.shard" (string): JSON with everything a merge must check (ShardInfo).
// The merge adds the parts' integer sums (exact, so the order of the parts does not matter) and divides by
// the scene's spp once: bit for bit the image `shadelab render` writes for the same scene on one machine.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/image/image.h"
#include "shadelab/render/fixed_sum.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

// Changes whenever the same scene, settings and sample indices could give other sample values (sampler,
// integrator, accumulation): parts from different versions are never merged.
inline constexpr const char* render_algorithm_version = "shadelab-pt-2 owen-sobol-4d fixed-40";

// A hash (16 hex digits) of everything in the Scene that changes the image, as the renderer sees it after
// loading: the camera, every field of every material (model, parameters, every texture binding), every
// texture texel by texel, every shape, meshes vertex by vertex, every light, the environment (map texels
// included) and rr_depth. So two scene files give the same hash only when they render the same, and a file a
// scene reads (mesh, texture, environment) is covered by its content, not its name. Not the paths, nor spp,
// max_depth, seed (separate fields of ShardInfo) or threads. Every struct is walked by a structured binding
// (shard_file.cpp), so a member added to Scene or any struct in it does not compile until it is hashed or
// named as left out. Deterministic across runs and machines; one pass over the texels and vertices.
std::string scene_fingerprint(const Scene& scene);

struct ShardInfo {
  std::string scene_hash;
  std::string scene;  // the scene's source, for messages only
  std::string renderer = render_algorithm_version;
  std::uint64_t seed = 0;
  int spp = 0;
  int max_depth = 0;
  std::string sampling;  // mis | brdf | light
  std::string sampler;   // sobol | independent
  int width = 0, height = 0;
  std::string split;  // samples | tiles
  int index = 0, count = 1;
  int sample_begin = 0, sample_end = 0;
  int tile_size = render_tile_size;
  int fixed_point_bits = shadelab::fixed_point_bits;
  std::uint64_t nonfinite_samples = 0;

  // The fields every part of one render shares (all but index, sample range and nonfinite_samples), as
  // "name=value" pairs; the first that differs is what a merge reports.
  std::vector<std::pair<std::string, std::string>> render_identity() const;
  ShardSpec spec() const;
};

// The description of the shard options.shard of the scene at spp and max_depth (the resolved values); a
// finished render's nonfinite count is set by the caller. A resumed run compares an existing part with it.
ShardInfo make_shard_info(const Scene& scene, const RenderOptions& options, int spp, int max_depth);
// The first identity field in which `got` differs from `want`, as "NAME GOT, but WANT" (for scene_hash with
// the two scenes' names); empty when both are parts of one render.
std::string identity_difference(const ShardInfo& got, const ShardInfo& want);
// Whether two descriptions are of the same shard of the same render (identity, index and sample range).
bool same_shard(const ShardInfo& a, const ShardInfo& b);

// Writes the part atomically (temporary file, then rename).
Result<bool> write_shard(const std::filesystem::path& path, const ShardInfo& info, const RenderResult& result);

// Reads and checks a part's header (a shadelab shard of this format, consistent fields, the sum channels
// present as uint, the data window the whole image). Errors name the file.
Result<ShardInfo> read_shard_info(const std::filesystem::path& path);
// Reads the part's exact sums and non-finite counts (after read_shard_info succeeded on it).
struct ShardSums {
  std::vector<FixedRgb> sums;
  std::vector<std::uint32_t> nonfinite;
};
Result<ShardSums> read_shard_sums(const std::filesystem::path& path, const ShardInfo& info);

struct MergeStatus {
  ShardInfo first;               // the render the parts belong to
  std::vector<int> present;      // shard indices found, ascending
  std::vector<int> missing;      // shard indices of 0 .. count - 1 not found
  std::uint64_t nonfinite_samples = 0;
};
// Checks that the parts belong to one render (same identity) and that no shard is given twice; the first
// problem is an Error naming the file. Missing shards are listed, not an error (merge_shards makes them one).
Result<MergeStatus> check_shards(const std::vector<std::filesystem::path>& parts);

// check_shards, an Error naming the first missing shard, then the sum of the parts' sums and the image:
// beauty = image_from_sums(sums, nonfinite, spp), the function render_scene uses.
struct MergedRender {
  MergeStatus status;
  RenderResult result;  // sums, beauty, stats.spp_done = spp, stats.nonfinite_samples
};
Result<MergedRender> merge_shards(const std::vector<std::filesystem::path>& parts,
                                  const std::function<void(double)>& progress = {});

}  // namespace shadelab
