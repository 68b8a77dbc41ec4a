// The C++ baselines of bench/python_eval_overhead.py: the two plain ways a C++ user evaluates N direction
// pairs with the library, the output allocated once:
//   eval_batch/MODEL: f->eval_batch(wi, wo, out, n), the library's batch entry (one virtual call, the
//                     model's kernel inlined into the loop, no check): the fastest;
//   eval_loop/MODEL:  for each i, out[i] = f->eval(wi[i], wo[i]) (one virtual call per pair).
// and, for the record, eval_batch_checked/MODEL: the same batch with its unit-length check of every
// direction, the entry Python's Brdf.eval calls on the arrays in place.
// The script writes the pairs it gives to Python's Brdf.eval into a file and runs this program on the same
// file, alternating the two in one run.
//
//   SHADELAB_BENCH_PAIRS=pairs.bin SHADELAB_BENCH_MODEL=cook-torrance ./build/release/bench/python_eval_baseline
// The file holds N wi then N wo, each as 3 float64 (x, y, z), unit length. Without it: 1e6 cosine-weighted
// pairs from a fixed seed. SHADELAB_BENCH_PARAMS: "name=value;name=value".
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"

namespace {

using namespace shadelab;

static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Rgb) == 3 * sizeof(double), "packed like (N, 3) arrays");

std::vector<Vec3> g_wi;
std::vector<Vec3> g_wo;
BrdfPtr g_brdf;

void eval_loop(benchmark::State& state) {
  const Brdf& f = *g_brdf;
  const std::size_t n = g_wi.size();
  std::vector<Rgb> out(n);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) out[i] = f.eval(g_wi[i], g_wo[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

void eval_batch(benchmark::State& state) {
  const Brdf& f = *g_brdf;
  const std::size_t n = g_wi.size();
  std::vector<Rgb> out(n);
  for (auto _ : state) {
    f.eval_batch(g_wi.data(), g_wo.data(), out.data(), n);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

void eval_batch_checked(benchmark::State& state) {
  const Brdf& f = *g_brdf;
  const std::size_t n = g_wi.size();
  std::vector<Rgb> out(n);
  for (auto _ : state) {
    if (f.eval_batch_checked(g_wi.data(), g_wo.data(), out.data(), n) != n) {
      state.SkipWithError("a direction of the pairs is not unit length");
      break;
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

bool load_pairs(const char* path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const auto bytes = static_cast<std::size_t>(in.tellg());
  if (bytes == 0 || bytes % (6 * sizeof(double)) != 0) return false;
  const std::size_t n = bytes / (6 * sizeof(double));
  g_wi.resize(n);
  g_wo.resize(n);
  in.seekg(0);
  in.read(reinterpret_cast<char*>(g_wi.data()), static_cast<std::streamsize>(n * sizeof(Vec3)));
  in.read(reinterpret_cast<char*>(g_wo.data()), static_cast<std::streamsize>(n * sizeof(Vec3)));
  return static_cast<bool>(in);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  const char* pairs = std::getenv("SHADELAB_BENCH_PAIRS");
  const char* model_env = std::getenv("SHADELAB_BENCH_MODEL");
  const char* params_env = std::getenv("SHADELAB_BENCH_PARAMS");
  const std::string model = model_env != nullptr ? model_env : "cook-torrance";
  ParamAssignments params;
  if (params_env != nullptr && *params_env != '\0') {
    std::string text = params_env;
    std::size_t start = 0;
    while (start <= text.size()) {
      const std::size_t end = std::min(text.find(';', start), text.size());
      auto kv = split_assignment(text.substr(start, end - start));
      if (!kv) {
        std::cerr << "python_eval_baseline: " << kv.error().message << "\n";
        return 2;
      }
      params.push_back(*kv);
      start = end + 1;
    }
  }
  auto brdf = make_brdf(model, params);
  if (!brdf) {
    std::cerr << "python_eval_baseline: " << brdf.error().message << "\n";
    return 2;
  }
  g_brdf = std::move(brdf).value();
  if (pairs != nullptr) {
    if (!load_pairs(pairs)) {
      std::cerr << "python_eval_baseline: " << pairs << ": cannot read N wi then N wo as float64 triples\n";
      return 2;
    }
  } else {
    Pcg32 rng(2024);
    for (int i = 0; i < 1'000'000; ++i) {
      g_wi.push_back(sample_cosine_hemisphere({rng.next_double(), rng.next_double()}));
      g_wo.push_back(sample_cosine_hemisphere({rng.next_double(), rng.next_double()}));
    }
  }
  benchmark::RegisterBenchmark(("eval_batch/" + model).c_str(), eval_batch)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(("eval_loop/" + model).c_str(), eval_loop)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(("eval_batch_checked/" + model).c_str(), eval_batch_checked)
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
