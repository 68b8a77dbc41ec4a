// shadelab render threads: the concurrency of a render's TBB task arena from a requested thread count.
//
// 0 means all cores. A request above the cores is served with all cores: TBB ignores the extra workers
// anyway (with a warning on stderr), and an arena of 10^5 threads crashes it. Renders are bit-identical
// for any thread count (path_tracer.h), so the clamp changes no image.
#pragma once

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace shadelab {

// The largest thread count any option or scene setting accepts (scene "render.threads", --threads).
inline constexpr int max_render_threads = 4096;

inline int arena_threads(int requested) {
  const int cores = std::max(1, tbb::info::default_concurrency());
  return requested <= 0 ? cores : std::min(requested, cores);
}

}  // namespace shadelab
