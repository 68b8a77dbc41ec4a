// Environment baking against ceilings measured in this process (docs/performance.md; bench/run.sh prints
// the ratios):
// - memory_read_dram: the machine's memory-read ceiling: a vectorized sum with 8 independent 8-lane
//   accumulators per thread (AVX2 where the CPU has it) over a 256 MiB buffer, far above L3 (32 MiB);
// - memory_read_l3: the same over the 18 MiB of a 6 x 512^2 RGB float cube, which stays in L3;
// - memory_read_cube_cold: the same sum over that cube evicted from the caches first (one cold pass over
//   the projection's own bytes: what a single pass can read, ramp-up included). Buffers are 64-byte aligned
//   (FloatBuffer), as images are;
// - sh_projection_cold / _hot: SH9 projection of that cube in GB/s of input, with the cube evicted from the
//   caches before each iteration (read from memory, compare with memory_read_dram) or left in L3 (compare
//   with memory_read_l3);
// - sh_command / read_input: `bake sh` on a lat-long HDRI (read the EXR, project it) and the EXR read alone;
// - irradiance_from_latlong/N: the exact irradiance cube (6 x N^2) of a 1024 x 512 HDRI, from its own texels;
// - irradiance_from_cube/N: the same from its 6 x 256^2 cube;
// - latlong_to_cube_exact / _bilinear: the exact area-weighted lat-long -> 6 x 256^2 resampling against the
//   former 4 x 4 bilinear point samples;
// - irradiance_per_texel_sum/32: the per-texel sum over the same 6 x 256^2 input (the peer in this run);
// - prefilter_chain: the Phong chain 256 .. 1 (9 levels) from 6 x 256^2, with its error against the brute
//   force per level and the brute-force chain's time extrapolated from measured directions;
// - prefilter_ggx_chain: the same for the GGX chain (the default lobe sum) against its brute force;
// - split_sum_reads/N: the split sum's filtered taps (N per shading point) against one chain read (N = 0);
// - dfg_table/N, dfg_table_adaptive/N: the N x N DFG table (bake_dfg, 2 threads) by the fixed Gauss-Legendre
//   rule (the default, error estimate included) and by the former adaptive quadrature to 1e-6, in texels/s;
// - lobe_moments_gauss / lobe_moments_adaptive: the split-sum lobe table's moments (dfg_lobe_moments_gauss, and
//   dfg_lobe_moments at relative tolerance 1e-5 as the table used to take them) over the same 8 x 8 texels,
//   one thread, in texels/s.
//
//   ./build/release/bench/envmap_bench     (or bench/run.sh for everything with the table)
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "shadelab/envmap/diffuse/irradiance.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/envmap/specular/prefilter.h"
#include "shadelab/envmap/specular/prefilter_ggx.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/envmap/specular/split_sum_taps.h"
#include "shadelab/envmap/base/simd.h"
#include "shadelab/image/image_io.h"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace {

using namespace shadelab;

const CubeMap& cube512() {
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

double cube_bytes(const CubeMap& c) { return 6.0 * c.size * c.size * 3 * sizeof(float); }

// A real HDRI: Blender's sunrise.exr (1024 x 512, the map with the brightest low sun), or a synthetic map
// of the same size with a sun when blender-data is not installed.
std::filesystem::path hdri_path() {
  const char* env = std::getenv("SHADELAB_BENCH_HDRI");
  if (env != nullptr) return env;
  return "/usr/share/blender/datafiles/studiolights/world/sunrise.exr";
}
const Image& hdri() {
  static const Image img = [] {
    auto r = read_image(hdri_path());
    if (r) return std::move(r).value();
    Image s(1024, 512);
    for (int y = 0; y < 512; ++y)
      for (int x = 0; x < 1024; ++x) {
        const Vec3 d = latlong_direction((x + 0.5) / 1024, (y + 0.5) / 512);
        s.set(x, y, Rgb::gray(d.y > 0 ? 1.0 + 1e4 * std::pow(std::max(0.0, dot(d, normalize(Vec3{1, 0.05, 0}))), 4000.0) : 0.1));
      }
    return s;
  }();
  return img;
}
const CubeMap& hdri_cube() {
  static const CubeMap c = latlong_to_cube(hdri(), 256);
  return c;
}

// --- the memory-read ceiling --------------------------------------------------------------------------
using simd::f8;

SHADELAB_INLINE float sum_block(const float* p, std::size_t n) {
  f8 a0 = {}, a1 = {}, a2 = {}, a3 = {}, a4 = {}, a5 = {}, a6 = {}, a7 = {};
  std::size_t i = 0;
  for (; i + 64 <= n; i += 64) {
    a0 += simd::load8(p + i);
    a1 += simd::load8(p + i + 8);
    a2 += simd::load8(p + i + 16);
    a3 += simd::load8(p + i + 24);
    a4 += simd::load8(p + i + 32);
    a5 += simd::load8(p + i + 40);
    a6 += simd::load8(p + i + 48);
    a7 += simd::load8(p + i + 56);
  }
  float s = simd::hsum(((a0 + a1) + (a2 + a3)) + ((a4 + a5) + (a6 + a7)));
  for (; i < n; ++i) s += p[i];
  return s;
}
SHADELAB_TARGET_AVX2 float sum_block_avx2(const float* p, std::size_t n) { return sum_block(p, n); }
float sum_block_base(const float* p, std::size_t n) { return sum_block(p, n); }

double parallel_sum(const float* p, std::size_t n) {
  const bool avx = simd::cpu_has_avx2_fma();
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 1 << 16), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double acc) {
        const float* q = p + r.begin();
        return acc + static_cast<double>(avx ? sum_block_avx2(q, r.size()) : sum_block_base(q, r.size()));
      },
      [](double a, double b) { return a + b; });
}

FloatBuffer& big_buffer() {
  static FloatBuffer b(std::size_t{256} << 20 >> 2, 1.0f);  // 256 MiB
  return b;
}

void memory_read_dram(benchmark::State& state) {
  const auto& b = big_buffer();
  for (auto _ : state) benchmark::DoNotOptimize(parallel_sum(b.data(), b.size()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(b.size() * sizeof(float)));
}
BENCHMARK(memory_read_dram)->Unit(benchmark::kMillisecond)->UseRealTime();

void memory_read_l3(benchmark::State& state) {
  const CubeMap& c = cube512();
  for (auto _ : state) {
    double total = 0.0;
    for (const Image& face : c.faces) total += parallel_sum(face.data.data(), face.data.size());
    benchmark::DoNotOptimize(total);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(static_cast<double>(state.iterations()) * cube_bytes(c)));
}
BENCHMARK(memory_read_l3)->Unit(benchmark::kMillisecond)->UseRealTime();

// --- SH9 ---------------------------------------------------------------------------------------------
void evict_caches() {
  static FloatBuffer junk(std::size_t{64} << 20 >> 2, 1.0f);  // 64 MiB, twice the L3
  benchmark::DoNotOptimize(parallel_sum(junk.data(), junk.size()));
}

void sh_projection_cold(benchmark::State& state) {
  const CubeMap& c = cube512();
  benchmark::DoNotOptimize(project_sh9(c));  // tables built once per size
  for (auto _ : state) {
    state.PauseTiming();
    evict_caches();
    state.ResumeTiming();
    benchmark::DoNotOptimize(project_sh9(c));
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(static_cast<double>(state.iterations()) * cube_bytes(c)));
}
BENCHMARK(sh_projection_cold)->Unit(benchmark::kMillisecond)->UseRealTime();

void memory_read_cube_cold(benchmark::State& state) {
  const CubeMap& c = cube512();
  for (auto _ : state) {
    state.PauseTiming();
    evict_caches();
    state.ResumeTiming();
    double total = 0.0;
    for (const Image& face : c.faces) total += parallel_sum(face.data.data(), face.data.size());
    benchmark::DoNotOptimize(total);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(static_cast<double>(state.iterations()) * cube_bytes(c)));
}
BENCHMARK(memory_read_cube_cold)->Unit(benchmark::kMillisecond)->UseRealTime();

void sh_projection_hot(benchmark::State& state) {
  const CubeMap& c = cube512();
  for (auto _ : state) benchmark::DoNotOptimize(project_sh9(c));
  state.SetBytesProcessed(static_cast<std::int64_t>(static_cast<double>(state.iterations()) * cube_bytes(c)));
}
BENCHMARK(sh_projection_hot)->Unit(benchmark::kMillisecond)->UseRealTime();

void read_input(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(read_image(hdri_path()));
}
BENCHMARK(read_input)->Unit(benchmark::kMillisecond)->UseRealTime();

void sh_command(benchmark::State& state) {
  for (auto _ : state) {
    auto img = read_image(hdri_path());
    if (!img) {
      state.SkipWithError("the HDRI is missing (SHADELAB_BENCH_HDRI)");
      break;
    }
    benchmark::DoNotOptimize(project_sh9(*img));
  }
}
BENCHMARK(sh_command)->Unit(benchmark::kMillisecond)->UseRealTime();

// --- irradiance and resampling --------------------------------------------------------------------------
void irradiance_from_latlong(benchmark::State& state) {
  const Image& img = hdri();
  const int n = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(irradiance_cube(img, n, RadianceUnits::game));
  state.SetItemsProcessed(state.iterations() * 6 * n * n);  // items = output texels
}
BENCHMARK(irradiance_from_latlong)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();

void irradiance_from_cube(benchmark::State& state) {
  const CubeMap& c = hdri_cube();
  const int n = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(irradiance_cube(c, n, RadianceUnits::game));
  state.SetItemsProcessed(state.iterations() * 6 * n * n);
}
BENCHMARK(irradiance_from_cube)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();

// The per-texel sum E(n) = sum L max(0, n.w) dOmega over the same 6 x 256^2 input (what irradiance_from_cube
// is exact against), for 96 spread output directions on 2 threads; items = output texels, so the ratio of
// items_per_second to irradiance_from_cube's is the speed-up over summing every emitter per texel.
void irradiance_per_texel_sum(benchmark::State& state) {
  const CubeMap& c = hdri_cube();
  const int n = static_cast<int>(state.range(0));
  constexpr int count = 96;
  std::vector<Rgb> out(count);
  for (auto _ : state) {
    tbb::parallel_for(0, count, [&](int k) {
      out[static_cast<std::size_t>(k)] = irradiance_brute_force(c, texel_direction(k % 6, (k * 7) % n, (k * 13) % n, n));
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * count);
}
BENCHMARK(irradiance_per_texel_sum)->Arg(32)->Unit(benchmark::kMillisecond)->UseRealTime();

void latlong_to_cube_exact(benchmark::State& state) {
  const Image& img = hdri();
  for (auto _ : state) benchmark::DoNotOptimize(latlong_to_cube(img, 256));
}
BENCHMARK(latlong_to_cube_exact)->Unit(benchmark::kMillisecond)->UseRealTime();

void latlong_to_cube_bilinear(benchmark::State& state) {
  const Image& img = hdri();
  for (auto _ : state) benchmark::DoNotOptimize(latlong_to_cube(img, 256, 4));
}
BENCHMARK(latlong_to_cube_bilinear)->Unit(benchmark::kMillisecond)->UseRealTime();

// The Phong chain 256 .. 1 from 6 x 256^2 (9 levels, exponents 2048 .. 2), with its error against the
// brute-force lobe convolution of the same input (prefilter_brute_force, double, every texel) at 48 spread
// texels per level: counters max_err_<i> and mean_err_<i> (relative, green channel), max_err (over levels).
// brute_force_chain_ms: the brute-force chain's time on 2 threads, extrapolated from the measured time of 16
// directions per level to all 6 N^2 texels of each level.
struct ChainCheck {
  std::vector<double> max_err, mean_err;
  double brute_seconds = 0.0;
};
// Levels first .. of `levels` against ref(i, direction) (the brute force of level i) at 48 spread texels per
// level, and the brute force's time extrapolated from 16 directions per level.
template <class Ref>
ChainCheck check_chain(const std::vector<CubeMap>& levels, std::size_t first, const Ref& ref) {
  ChainCheck k;
  for (std::size_t i = first; i < levels.size(); ++i) {
    const CubeMap& level = levels[i];
    constexpr int samples = 48;
    std::vector<double> err(samples);
    tbb::parallel_for(0, samples, [&](int j) {
      const int f = j % 6, x = (j * 7 + 3) % level.size, y = (j * 11 + 5) % level.size;
      const Rgb want = ref(i, texel_direction(f, x, y, level.size));
      err[static_cast<std::size_t>(j)] = std::abs(level.texel(f, x, y).g - want.g) / want.g;
    });
    double mx = 0.0, mean = 0.0;
    for (double e : err) {
      mx = std::max(mx, e);
      mean += e / samples;
    }
    k.max_err.push_back(mx);
    k.mean_err.push_back(mean);
    constexpr int timed = 16;
    std::vector<Rgb> sink(timed);
    const auto t0 = std::chrono::steady_clock::now();
    tbb::parallel_for(0, timed, [&](int j) {
      sink[static_cast<std::size_t>(j)] = ref(i, texel_direction(j % 6, j % level.size, (3 * j) % level.size, level.size));
    });
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(sink.data());
    k.brute_seconds += s / timed * 6.0 * level.size * level.size;
  }
  return k;
}

void report_chain(benchmark::State& state, const ChainCheck& k, std::size_t first) {
  double worst = 0.0;
  for (std::size_t i = 0; i < k.max_err.size(); ++i) {
    state.counters["max_err_" + std::to_string(first + i)] = k.max_err[i];
    state.counters["mean_err_" + std::to_string(first + i)] = k.mean_err[i];
    worst = std::max(worst, k.max_err[i]);
  }
  state.counters["max_err"] = worst;
  state.counters["brute_force_chain_ms"] = 1e3 * k.brute_seconds;
}

void prefilter_chain(benchmark::State& state) {
  const CubeMap& c = hdri_cube();
  PrefilterOptions o;
  o.size = 256;
  std::optional<PrefilteredCube> last;
  for (auto _ : state) {
    auto p = prefilter_specular(c, o);
    if (!p) {
      state.SkipWithError(p.error().message.c_str());
      return;
    }
    last = std::move(p).value();
  }
  static const ChainCheck k = check_chain(last->levels, 0, [&](std::size_t i, const Vec3& r) {
    return prefilter_brute_force(c, r, last->exponents[i]);
  });
  report_chain(state, k, 0);
}
BENCHMARK(prefilter_chain)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// The GGX chain 256 .. 1 (9 levels, the default lobe sum: faces 128, 64, 32 near-far, 16 .. 1 exact) from
// the same 6 x 256^2 input, against prefilter_ggx_brute_force (double, every texel) from level 1 (level 0 is
// the input): the same counters as prefilter_chain.
void prefilter_ggx_chain(benchmark::State& state) {
  const CubeMap& c = hdri_cube();
  std::optional<GgxPrefilteredCube> last;
  for (auto _ : state) last = prefilter_ggx(c, GgxPrefilterOptions{});
  static const ChainCheck k = check_chain(last->levels, 1, [&](std::size_t i, const Vec3& r) {
    return prefilter_ggx_brute_force(c, r, last->roughness[i]);
  });
  report_chain(state, k, 1);
}
BENCHMARK(prefilter_ggx_chain)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// The split sum's chain reads per shading point on a 64^2 GGX chain of the HDRI (the game renderer's size):
// Arg 0, one read along R (Karis 2013 as published; the lobe reads are two such reads), against Arg N, the
// filtered taps of envmap/specular/split_sum_taps.h (N taps, both parts), over the same 4096 points (N.V, roughness
// and normal on a fixed grid); items = shading points.
void split_sum_reads(benchmark::State& state) {
  static const GgxPrefilteredCube chain = prefilter_ggx(latlong_to_cube(hdri(), 64), GgxPrefilterOptions{});
  const int taps = static_cast<int>(state.range(0));
  constexpr int points = 4096;
  for (auto _ : state) {
    Rgb sum;
    for (int i = 0; i < points; ++i) {
      const double mu = 0.02 + 0.96 * ((i % 64) + 0.5) / 64.0;
      const double r = 0.05 + 0.95 * ((i / 64) + 0.5) / 64.0;
      const double phi = 0.37 * i;
      const Frame frame = Frame::from_normal(normalize(Vec3{std::cos(phi), 0.3, std::sin(phi)}));
      const Vec3 wo{std::sqrt(1.0 - mu * mu), 0.0, mu};
      if (taps == 0) {
        sum += sample_ggx_chain(chain, frame.to_world(Vec3{-wo.x, -wo.y, wo.z}), r);
      } else {
        const SplitSumReads reads = split_sum_filtered_reads(chain, frame, wo, r, taps);
        sum += reads.a + reads.b;
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * points);
}
BENCHMARK(split_sum_reads)->Arg(0)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();

void dfg_table_of(benchmark::State& state, bool adaptive) {
  DfgOptions o;
  o.size = static_cast<int>(state.range(0));
  o.adaptive = adaptive;
  double error = 0.0;
  for (auto _ : state) {
    const DfgTable t = bake_dfg(o);
    error = t.max_error_estimate;
    benchmark::DoNotOptimize(t.texels.data());
  }
  state.SetItemsProcessed(state.iterations() * o.size * o.size);
  state.counters["error_estimate"] = error;
}
void dfg_table(benchmark::State& state) { dfg_table_of(state, false); }
void dfg_table_adaptive(benchmark::State& state) { dfg_table_of(state, true); }
BENCHMARK(dfg_table)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(dfg_table_adaptive)->Arg(16)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

void lobe_moments_of(benchmark::State& state, bool adaptive) {
  constexpr int n = 8;
  for (auto _ : state) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const double mu = (i + 0.5) / n, r = (j + 0.5) / n;
        const DfgLobeMoments m = adaptive ? dfg_lobe_moments(mu, r * r, 1e-5) : dfg_lobe_moments_gauss(mu, r * r);
        sum += m.spread[0] + m.angle[1];
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * n * n);
}
void lobe_moments_gauss(benchmark::State& state) { lobe_moments_of(state, false); }
void lobe_moments_adaptive(benchmark::State& state) { lobe_moments_of(state, true); }
BENCHMARK(lobe_moments_gauss)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(lobe_moments_adaptive)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
