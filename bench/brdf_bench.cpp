// Cost per call of eval, pdf and sample for every registered model, at default parameters, on a fixed
// set of random direction pairs (so the branch mix is the same for every model). The baseline measured in
// the same run is "lambert", the cheapest model: compare models as ratios to it, not as absolute times.
// Variants beside the defaults (issue 10, section 4): ggx with each sampler (ndf, vndf, vndf-caps, vndf-bounded)
// and with Kulla-Conty, cook-torrance with d = ggx, filament with Burley diffuse and without compensation; they
// are named model/param=value (docs/performance.md has a table).
// eval_batch/MODEL: Brdf::eval_batch over all the pairs per iteration, reported per pair (items_per_second),
// against eval/MODEL, one virtual call per pair.
//
//   ./build/release/bench/brdf_bench --benchmark_filter=eval
#include <benchmark/benchmark.h>

#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"

namespace {

using namespace shadelab;

constexpr std::size_t kPairs = 4096;  // fits in L1/L2 with the model state

struct Inputs {
  std::vector<Vec3> wi;
  std::vector<Vec3> wo;
  std::vector<Vec2> u;
  std::vector<double> u_lobe;
};

const Inputs& inputs() {
  static const Inputs in = [] {
    Inputs r;
    Pcg32 rng(12345);
    for (std::size_t i = 0; i < kPairs; ++i) {
      r.wi.push_back(sample_cosine_hemisphere({rng.next_double(), rng.next_double()}));
      r.wo.push_back(sample_cosine_hemisphere({rng.next_double(), rng.next_double()}));
      r.u.push_back({rng.next_double(), rng.next_double()});
      r.u_lobe.push_back(rng.next_double());
    }
    return r;
  }();
  return in;
}

void bench_eval(benchmark::State& state, const std::string& model, const ParamAssignments& params) {
  const auto f = make_brdf(model, params).value();
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f->eval(in.wi[i], in.wo[i]));
    i = (i + 1) % kPairs;
  }
  state.SetItemsProcessed(state.iterations());
}

void bench_eval_batch(benchmark::State& state, const std::string& model, const ParamAssignments& params) {
  const auto f = make_brdf(model, params).value();
  const auto& in = inputs();
  std::vector<Rgb> out(kPairs);
  for (auto _ : state) {
    f->eval_batch(in.wi.data(), in.wo.data(), out.data(), kPairs);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kPairs));
}

void bench_pdf(benchmark::State& state, const std::string& model, const ParamAssignments& params) {
  const auto f = make_brdf(model, params).value();
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f->pdf(in.wi[i], in.wo[i]));
    i = (i + 1) % kPairs;
  }
  state.SetItemsProcessed(state.iterations());
}

void bench_sample(benchmark::State& state, const std::string& model, const ParamAssignments& params) {
  const auto f = make_brdf(model, params).value();
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f->sample(in.wo[i], in.u[i], in.u_lobe[i]));
    i = (i + 1) % kPairs;
  }
  state.SetItemsProcessed(state.iterations());
}

const bool registered = [] {
  struct Variant {
    std::string model;
    ParamAssignments params;
  };
  std::vector<Variant> variants;
  for (const auto& m : brdf_models()) {
    if (!needs_input_file(m)) variants.push_back({m.name, {}});  // measured needs a file (bench/README: not here)
  }
  for (const char* s : {"ndf", "vndf", "vndf-caps", "vndf-bounded"}) variants.push_back({"ggx", {{"sampling", s}}});
  variants.push_back({"ggx", {{"ms", "kulla-conty"}}});
  variants.push_back({"cook-torrance", {{"d", "ggx"}}});
  variants.push_back({"filament", {{"diffuse", "burley"}}});
  variants.push_back({"filament", {{"energy_compensation", "off"}}});
  for (const auto& v : variants) {
    std::string name = v.model;
    for (const auto& [key, value] : v.params) name += "/" + key + "=" + value;
    benchmark::RegisterBenchmark(("eval/" + name).c_str(), bench_eval, v.model, v.params);
    benchmark::RegisterBenchmark(("eval_batch/" + name).c_str(), bench_eval_batch, v.model, v.params);
    benchmark::RegisterBenchmark(("pdf/" + name).c_str(), bench_pdf, v.model, v.params);
    benchmark::RegisterBenchmark(("sample/" + name).c_str(), bench_sample, v.model, v.params);
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
