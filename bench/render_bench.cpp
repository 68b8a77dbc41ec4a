// The path tracer on the built-in default scene, 2 threads, against Embree's raw ray throughput on the same
// geometry measured in the same process (the ceiling: incoherent rtcIntersect1 rays between random points of
// the scene's bounds, the cost of a bounce ray without any shading).
//
//   ./build/release/bench/render_bench
// Report: render samples/s and rays/s, embree_rays rays/s, and the ratio of the two rays/s (the fraction of
// the ceiling the renderer reaches). A path sample with next-event estimation traces about 3 rays.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>

#include "shadelab/render/accel.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"
#include "shadelab/scene/default_scene.h"

namespace {

using namespace shadelab;

const Scene& bench_scene() {
  static const Scene s = [] {
    Scene scene = default_scene();
    scene.camera.width = 320;
    scene.camera.height = 180;
    return scene;
  }();
  return s;
}

void render(benchmark::State& state) {
  const Scene& scene = bench_scene();
  RenderOptions o;
  o.spp = 4;
  o.threads = 2;
  std::uint64_t rays = 0;
  double samples = 0.0;
  for (auto _ : state) {
    const auto r = render_scene(scene, o).value();
    rays += r.stats.rays;
    samples += static_cast<double>(scene.camera.width) * scene.camera.height * r.stats.spp_done;
  }
  state.counters["samples_per_second"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
  state.counters["rays_per_second"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(render)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

void embree_rays(benchmark::State& state) {
  const Scene& scene = bench_scene();
  const Accelerator accel(scene);
  constexpr int per_task = 4096;
  double total = 0.0;
  for (auto _ : state) {
    std::atomic<int> hits{0};
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
    tbb::parallel_for(0, 64, [&](int task) {
      Pcg32 rng(17, static_cast<std::uint64_t>(task));
      int local = 0;
      for (int i = 0; i < per_task; ++i) {
        // Origins just above the ground around the spheres, random directions: incoherent like bounces.
        const Vec3 o{-6.0 + 12.0 * rng.next_double(), 0.05 + 2.0 * rng.next_double(), -4.0 + 8.0 * rng.next_double()};
        const Vec3 d = sample_uniform_sphere({rng.next_double(), rng.next_double()});
        Hit h;
        local += accel.intersect(Ray{o, d}, h) ? 1 : 0;
      }
      hits += local;
    });
    benchmark::DoNotOptimize(hits.load());
    total += 64.0 * per_task;
  }
  state.counters["rays_per_second"] = benchmark::Counter(total, benchmark::Counter::kIsRate);
}
BENCHMARK(embree_rays)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
