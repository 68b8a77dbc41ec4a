// The C++ baselines of bench/python_eval_overhead.py: the two plain ways a C++ user evaluates N direction
// pairs with the library, the output allocated once:
//   eval_batch/MODEL: f->eval_batch(wi, wo, out, n), the library's batch entry (one virtual call, the
//                     model's kernel inlined into the loop, no check): the fastest;
//   eval_loop/MODEL:  for each i, out[i] = f->eval(wi[i], wo[i]) (one virtual call per pair).
// and, for the record, eval_batch_checked/MODEL: the same batch with its unit-length check of every
// direction, the entry Python's Brdf.eval calls on the arrays in place.
// The like-for-like baselines of Python's plain eval (no out=), which returns a new (N, 3) array per call:
//   eval_batch_fresh/MODEL, eval_loop_fresh/MODEL: the same two loops with the output allocated and freed
//                     in every iteration, as NumPy allocates the result: malloc of 3N doubles, not
//                     initialized (first written by the model's loop), advised for transparent huge pages
//                     when >= 4 MiB as NumPy 1.22+ does on Linux (its default allocator), then free.
//   eval_checked_fresh/MODEL: eval_batch_checked with the output allocated per call: exactly the C++ call
//                     Python's plain eval makes, so eval / this is the binding's own overhead.
// Every column reports `faults`: the minor page faults per iteration (getrusage), so that a run shows
// whether the fresh output was paged in anew (glibc hands a freed block of this size back from its heap
// once its mmap threshold has risen; it then costs no page fault, on either side).
// The script writes the pairs it gives to Python's Brdf.eval into a file and runs this program on the same
// file, alternating the two in one run.
//
//   SHADELAB_BENCH_PAIRS=pairs.bin SHADELAB_BENCH_MODEL=cook-torrance ./build/release/bench/python_eval_baseline
// The file holds N wi then N wo, each as 3 float64 (x, y, z), unit length. Without it: 1e6 cosine-weighted
// pairs from a fixed seed. SHADELAB_BENCH_PARAMS: "name=value;name=value".
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <new>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <sys/mman.h>
#include <sys/resource.h>

#include "shadelab/brdf/registry.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"

namespace {

using namespace shadelab;

static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Rgb) == 3 * sizeof(double), "packed like (N, 3) arrays");

std::vector<Vec3> g_wi;
std::vector<Vec3> g_wo;
BrdfPtr g_brdf;

long minor_faults() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return r.ru_minflt;
}

// Minor page faults per iteration over the timed loop (the setup before it excluded).
void report_faults(benchmark::State& state, long before) {
  state.counters["faults"] = benchmark::Counter(static_cast<double>(minor_faults() - before),
                                                benchmark::Counter::kAvgIterations);
}

struct FreeDeleter {
  void operator()(void* p) const { std::free(p); }
};

// A new output of n rows as NumPy's np.empty((n, 3)) makes it (its default data allocator on Linux):
// malloc, no initialization, and for 4 MiB or more madvise(MADV_HUGEPAGE) from the block's first page
// boundary to its end.
std::unique_ptr<Rgb[], FreeDeleter> fresh_output(std::size_t n) {
  const std::size_t bytes = n * sizeof(Rgb);
  void* p = std::malloc(bytes);
  if (p == nullptr) throw std::bad_alloc();
  if (bytes >= (std::size_t{1} << 22)) {
    const std::uintptr_t offset = 4096 - reinterpret_cast<std::uintptr_t>(p) % 4096;
    madvise(static_cast<char*>(p) + offset, bytes - offset, MADV_HUGEPAGE);
  }
  return std::unique_ptr<Rgb[], FreeDeleter>(static_cast<Rgb*>(p));
}

// How a column fills the output: one virtual call per pair, the batch entry, or the batch entry with its
// unit-length check (false when a direction is not unit length).
struct PerPair {
  static bool fill(const Brdf& f, Rgb* out, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) out[i] = f.eval(g_wi[i], g_wo[i]);
    return true;
  }
};
struct Batch {
  static bool fill(const Brdf& f, Rgb* out, std::size_t n) {
    f.eval_batch(g_wi.data(), g_wo.data(), out, n);
    return true;
  }
};
struct BatchChecked {
  static bool fill(const Brdf& f, Rgb* out, std::size_t n) {
    return f.eval_batch_checked(g_wi.data(), g_wo.data(), out, n) == n;
  }
};

// How a column gets its output: allocated once before the timed loop (Reused), or anew in every iteration
// as NumPy allocates a result (Fresh).
struct Reused {};
struct Fresh {};

// One body for every column: the output obtained as Output says, filled as Fill says.
template <class Output, class Fill>
void eval_column(benchmark::State& state) {
  const Brdf& f = *g_brdf;
  const std::size_t n = g_wi.size();
  std::vector<Rgb> reused(std::is_same_v<Output, Reused> ? n : 0);
  const long faults = minor_faults();
  for (auto _ : state) {
    std::unique_ptr<Rgb[], FreeDeleter> fresh;
    Rgb* out = reused.data();
    if constexpr (std::is_same_v<Output, Fresh>) {
      fresh = fresh_output(n);
      out = fresh.get();
    }
    if (!Fill::fill(f, out, n)) {
      state.SkipWithError("a direction of the pairs is not unit length");
      break;
    }
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  report_faults(state, faults);
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
  const std::pair<const char*, void (*)(benchmark::State&)> columns[] = {
      {"eval_batch/", eval_column<Reused, Batch>},
      {"eval_loop/", eval_column<Reused, PerPair>},
      {"eval_batch_checked/", eval_column<Reused, BatchChecked>},
      {"eval_batch_fresh/", eval_column<Fresh, Batch>},
      {"eval_loop_fresh/", eval_column<Fresh, PerPair>},
      {"eval_checked_fresh/", eval_column<Fresh, BatchChecked>},
  };
  for (const auto& [prefix, column] : columns) {
    benchmark::RegisterBenchmark((prefix + model).c_str(), column)->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
