// Throughput of the exported shaders on Mesa's lavapipe (Vulkan on the CPU) beside the C++ scalar eval, on the
// same 2^20 direction pairs (the verifier's mix), measured in the same iterations so that the ratio holds
// however loaded the machine is. Per iteration: one compute dispatch over all pairs (timed as the benchmark's
// time) and one pass of Brdf::eval over the same pairs (timed separately). Counters: shader_evals_per_s,
// cpp_evals_per_s and ratio = shader / cpp. lavapipe runs on every core (LP_NUM_THREADS, default the core
// count) with 8-wide SIMD; the C++ baseline is one thread in double precision. Pipeline creation (LLVM) and
// the upload are outside the timing; the result readback is inside (mapped memory: no copy).
//
//   ./build/release/bench/shader_bench
#include <benchmark/benchmark.h>

#include <chrono>

#include "export.h"
#include "glslang.h"
#include "shadelab/brdf/registry.h"
#include "verify.h"
#include "vulkan_compute.h"

namespace {

using namespace shadelab;
using namespace shadelab::shaders;

constexpr std::size_t kPairs = std::size_t{1} << 20;

const std::vector<float>& pairs() {
  static const std::vector<float> p = verification_pairs(kPairs, kDefaultSeed);
  return p;
}

void bench_shader(benchmark::State& state, const std::string& model, Lang lang) {
  static auto device = VulkanDevice::open();
  if (!device) {
    state.SkipWithError(device.error().message.c_str());
    return;
  }
  ExportOptions o;
  o.lang = lang;
  auto ex = export_model(model, {}, o);
  auto brdf = make_brdf(model);
  if (!ex || !brdf) {
    state.SkipWithError("export failed");
    return;
  }
  auto spirv = compile_compute(lang, compute_harness(lang, ex->text, ex->entry + "(wi, wo)"), model);
  if (!spirv) {
    state.SkipWithError(spirv.error().message.c_str());
    return;
  }
  auto job = (*device)->prepare(*spirv, pairs(), {});
  if (!job) {
    state.SkipWithError(job.error().message.c_str());
    return;
  }
  const auto& in = pairs();
  double cpp_seconds = 0.0;
  double shader_seconds = 0.0;
  double sink = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    if (auto ok = (*job)->execute(); !ok) {
      state.SkipWithError(ok.error().message.c_str());
      return;
    }
    const auto t1 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < kPairs; ++i) {
      const float* p = &in[8 * i];
      sink += (*brdf)->eval({p[0], p[1], p[2]}, {p[4], p[5], p[6]}).g;
    }
    const auto t2 = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(t1 - t0).count();
    shader_seconds += s;
    cpp_seconds += std::chrono::duration<double>(t2 - t1).count();
    state.SetIterationTime(s);
  }
  benchmark::DoNotOptimize(sink);
  const double evals = static_cast<double>(kPairs) * static_cast<double>(state.iterations());
  state.SetItemsProcessed(static_cast<std::int64_t>(evals));
  state.counters["shader_evals_per_s"] = evals / shader_seconds;
  state.counters["cpp_evals_per_s"] = evals / cpp_seconds;
  state.counters["ratio"] = cpp_seconds / shader_seconds;
  state.SetLabel((*device)->name());
}

const bool registered = [] {
  for (const auto& m : brdf_models()) {
    if (!m.no_shader.empty() || make_brdf(m.name).value()->is_stochastic()) continue;  // no shader: openpbr, measured; layered
    benchmark::RegisterBenchmark(("lavapipe/glsl/" + m.name).c_str(), bench_shader, m.name, Lang::glsl)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  for (const char* m : {"phong", "cook-torrance"}) {
    for (Lang lang : {Lang::essl, Lang::hlsl}) {
      benchmark::RegisterBenchmark((std::string("lavapipe/") + lang_name(lang) + "/" + m).c_str(), bench_shader,
                                   std::string(m), lang)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
