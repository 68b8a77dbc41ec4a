// Environment baking on a 6 x 512^2 RGB float cube map (18 MiB), the size the issue names:
// - memory_read: the ceiling, a TBB-parallel sum over the same bytes, measured in this process;
// - sh_projection: SH9 projection, reported in GB/s of input, so sh_projection / memory_read is the
//   fraction of the bandwidth ceiling reached (compare the two rows, not absolute figures);
// - irradiance: brute-force convolution to 6 x 32^2, reported per output texel;
// - prefilter: the specular mip chain from 128^2 down to 1^2.
//
//   ./build/release/bench/envmap_bench
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cmath>

#include "shadelab/envmap/irradiance.h"
#include "shadelab/envmap/prefilter.h"
#include "shadelab/envmap/sh.h"

namespace {

using namespace shadelab;

const CubeMap& input() {
  static const CubeMap cube = [] {
    CubeMap c(512);
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < 512; ++y)
        for (int x = 0; x < 512; ++x) {
          const Vec3 d = texel_direction(f, x, y, 512);
          c.set(f, x, y, {std::exp(4.0 * d.y), 0.5 + 0.5 * d.x, 1.0 + std::sin(20.0 * d.z)});
        }
    return c;
  }();
  return cube;
}

double input_bytes() { return 6.0 * 512 * 512 * 3 * sizeof(float); }

void memory_read(benchmark::State& state) {
  const CubeMap& c = input();
  for (auto _ : state) {
    double total = 0.0;
    for (const Image& face : c.faces) {
      total += tbb::parallel_reduce(
          tbb::blocked_range<std::size_t>(0, face.data.size(), 1 << 14), 0.0,
          [&](const tbb::blocked_range<std::size_t>& r, double acc) {
            float s = 0.0f;
            for (std::size_t i = r.begin(); i != r.end(); ++i) s += face.data[i];
            return acc + static_cast<double>(s);
          },
          [](double a, double b) { return a + b; });
    }
    benchmark::DoNotOptimize(total);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(static_cast<double>(state.iterations()) * input_bytes()));
}
BENCHMARK(memory_read)->Unit(benchmark::kMillisecond)->UseRealTime();

void sh_projection(benchmark::State& state) {
  const CubeMap& c = input();
  for (auto _ : state) benchmark::DoNotOptimize(project_sh9(c));
  state.SetBytesProcessed(static_cast<std::int64_t>(static_cast<double>(state.iterations()) * input_bytes()));
}
BENCHMARK(sh_projection)->Unit(benchmark::kMillisecond)->UseRealTime();

void irradiance(benchmark::State& state) {
  const CubeMap& c = input();
  ConvolveOptions o;
  o.max_input_size = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(irradiance_cube(c, 32, RadianceUnits::game, o));
  state.SetItemsProcessed(state.iterations() * 6 * 32 * 32);  // items = output texels
  state.counters["input_face"] = static_cast<double>(state.range(0));
}
BENCHMARK(irradiance)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();

void prefilter(benchmark::State& state) {
  const CubeMap& c = input();
  PrefilterOptions o;
  o.size = 128;
  for (auto _ : state) benchmark::DoNotOptimize(prefilter_specular(c, o));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(prefilter)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
