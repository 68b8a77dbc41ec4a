// Fuzz harness: the shard part reader and the merge (render/shard_file.h: read_shard_info, read_shard_sums,
// check_shards, merge_shards), what `shadelab merge` runs. Input: one part file, optionally a second after
// the separator line (harness.h), written as part-a.exr and part-b.exr. Contract checked: an error is one
// printable line naming a part (the file's name); an accepted part has a size within the limits, sums and
// non-finite counts of exactly width x height pixels, a shard index within its count and a sample range
// within [0, spp]; a merge that succeeds gives an image of the parts' size, finite where no sample was
// non-finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "harness.h"
#include "shadelab/render/shard_file.h"
#include "shadelab/scene/limits.h"

using namespace shadelab;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = fuzz::work_dir("shard");
  const auto [first, second] = fuzz::split_files(fuzz::as_text(data, size));
  const std::filesystem::path a = dir / "part-a.exr";
  const std::filesystem::path b = dir / "part-b.exr";
  fuzz::write_file(a, first);
  std::vector<std::filesystem::path> parts{a};
  if (!second.empty()) {
    fuzz::write_file(b, second);
    parts.push_back(b);
  }
  auto info = read_shard_info(a);
  if (!info) {
    fuzz::require_one_line(info.error().message, "part-a.exr");
  } else {
    if (info->width < 1 || info->height < 1 ||
        static_cast<long long>(info->width) * info->height > max_render_pixels) {
      fuzz::finding("part size", std::to_string(info->width) + " x " + std::to_string(info->height));
    }
    if (info->count < 1 || info->index < 0 || info->index >= info->count) {
      fuzz::finding("shard index", std::to_string(info->index) + "/" + std::to_string(info->count));
    }
    if (info->sample_begin < 0 || info->sample_begin > info->sample_end || info->sample_end > info->spp) {
      fuzz::finding("sample range", std::to_string(info->sample_begin) + ".." + std::to_string(info->sample_end));
    }
    auto sums = read_shard_sums(a, *info);
    if (!sums) {
      fuzz::require_one_line(sums.error().message, "part-a.exr");
    } else {
      const auto pixels = static_cast<std::size_t>(info->width) * static_cast<std::size_t>(info->height);
      if (sums->sums.size() != pixels || sums->nonfinite.size() != pixels) {
        fuzz::finding("sums size", std::to_string(sums->sums.size()) + " for " + std::to_string(pixels) + " pixels");
      }
    }
  }
  auto merged = merge_shards(parts);
  if (!merged) {
    fuzz::require_one_line(merged.error().message, "part-");
    return 0;
  }
  const ShardInfo& m = merged->status.first;
  const Image& img = merged->result.beauty;
  if (!img.is_valid() || img.width != m.width || img.height != m.height) fuzz::finding("merged image size", "");
  if (merged->status.nonfinite_samples == 0) {
    for (const float v : img.data) {
      if (!std::isfinite(v)) fuzz::finding("a non-finite pixel with no non-finite sample", "");
    }
  }
  return 0;
}
