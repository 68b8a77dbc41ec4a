// shadelab ibl-error INPUT --out DIR [--model ggx|filament] [--param K=V ...] [--roughness R,...] [--bins N]
// [--size N] [--spp N] [--seed S] [--threads N] [--specular-size N] [--json]: the error of the engine-side IBL
// shortcuts against the path tracer (render/ibl_error.h, docs/envmap.md "The error of the shortcuts"): a sphere
// lit by the lat-long INPUT alone, the split sum (along R and along the dominant direction) per roughness x N.V
// bin and SH9 irradiance per N.V bin. The files in DIR: ibl_error_page.h.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "cli_common.h"
#include "ibl_error_page.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/metrics.h"
#include "shadelab/envmap/specular/split_sum_taps.h"
#include "shadelab/plot/plot.h"
#include "shadelab/render/ibl_error.h"
#include "shadelab/render/threads.h"

namespace shadelab::cli {

namespace {

struct IblErrorCliOptions {
  std::string input;
  std::string out;
  std::string model = "ggx";
  std::vector<std::string> params;
  std::vector<double> roughness{0.1, 0.25, 0.4, 0.55, 0.7, 0.85, 1.0};
  int bins = 8;
  int size = 192;
  int spp = 256;
  std::string seed = "7";
  int threads = 0;
  int specular_size = 64;  // GameOptions::specular_size, the game renderer's
  std::string correction = "lobes";
  int taps = 64;  // --correction filtered: GameOptions::split_sum_taps
  bool json = false;
};

void run_ibl_error(const IblErrorCliOptions& o) {
  check_range("--bins", true, o.bins, 1, 64);
  check_range("--size", true, o.size, 16, 2048);
  check_range("--spp", true, o.spp, 1, 65536);
  check_range("--threads", true, o.threads, 0, max_render_threads);
  check_range("--specular-size", true, o.specular_size, 4, 1024);
  if ((o.specular_size & (o.specular_size - 1)) != 0) {
    throw UsageError(fmt::format("--specular-size: {} is not a power of two (the chain halves down to 1 x 1)",
                                 o.specular_size));
  }
  if (o.correction != "lobes" && o.correction != "dominant" && o.correction != "filtered") {
    throw UsageError("--correction: '" + o.correction + "' is not lobes, dominant or filtered (--split-sum-lookup)");
  }
  check_range("--taps", true, o.taps, 1, split_sum_taps_max);
  if (o.roughness.empty()) throw UsageError("--roughness: give at least one value");
  for (const double r : o.roughness) {
    if (!(r > 0.0 && r <= 1.0)) throw UsageError(fmt::format("--roughness: {} is not in (0, 1]", r));
  }
  if (const ModelInfo* m = find_brdf_model(o.model); m == nullptr || !m->split_sum_sweep) {
    throw UsageError("--model: '" + o.model + "' has no split-sum specular ambient (" + split_sum_model_names() + ")");
  }
  const std::uint64_t seed = parse_seed("--seed", o.seed);
  const std::filesystem::path dir(o.out);
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw UsageError("--out: '" + dir.string() + "' exists and is not a folder");
  }
  const std::vector<std::string> names = ibl_error_file_names();
  std::vector<NamedPath> outputs;
  for (const auto& n : names) outputs.push_back({"--out", dir / n});
  check_outputs({{"INPUT", o.input}}, outputs, OutputFolders::created);
  Image latlong = unwrap(read_radiance_image(o.input));  // NaN, Inf or negative: exit 2
  if (latlong.width != 2 * latlong.height) {
    throw UsageError(fmt::format("'{}': {} x {} is not a 2:1 lat-long environment", o.input, latlong.width, latlong.height));
  }
  Scene scene;
  scene.source = o.input;
  scene.environment.kind = Environment::Kind::image;
  scene.environment.source = o.input;
  scene.environment.latlong = std::move(latlong);
  IblErrorOptions io;
  io.roughness = o.roughness;
  io.nv_bins = o.bins;
  io.size = o.size;
  io.spp = o.spp;
  io.seed = seed;
  io.threads = o.threads;
  io.game.specular_size = o.specular_size;
  io.correction = o.correction == "dominant"   ? GameSplitSumLookup::dominant
                  : o.correction == "filtered" ? GameSplitSumLookup::filtered
                                               : GameSplitSumLookup::lobes;
  io.game.split_sum_taps = o.taps;
  const ParamAssignments params = parse_assignments(o.params);
  for (const auto& [key, value] : params) {  // the map's own rules first, then the model's (a test build)
    if (key == "roughness" || key == "perceptual_roughness" || key == "kd" || key == "metallic") continue;
    ParamAssignments one{{key, value}};
    (void)unwrap(make_brdf(o.model, one));
  }
  work_begins();
  const IblErrorMap map = unwrap(ibl_error_map(scene, o.model, params, io));

  std::filesystem::create_directories(dir, ec);
  if (ec) throw UsageError("--out: cannot create '" + dir.string() + "': " + ec.message());
  IblErrorHeader header;
  header.input = o.input;
  header.params = params;
  header.nv_bins = o.bins;
  header.size = o.size;
  header.spp = o.spp;
  header.specular_size = o.specular_size;
  header.seed = seed;
  const nlohmann::json j = write_ibl_error_files(map, header, dir);
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} sphere, {} roughness x {} N.V bins, {} spp reference, {:.1f} s\n", o.input, o.model,
             map.split_sum.size(), o.bins, o.spp, map.seconds);
  fmt::print("split sum: mean |error| {:.2f}%, max {:.2f}%, at N.V < 0.3 {:.2f}%\n", 100.0 * map.split_sum_summary.mean_abs,
             100.0 * map.split_sum_summary.max_abs, 100.0 * map.split_sum_summary.grazing_mean_abs);
  fmt::print("split sum {}: mean |error| {:.2f}%, max {:.2f}%, at N.V < 0.3 {:.2f}% ({:.1f}% less)\n",
             o.correction == "dominant" ? "along the dominant direction"
             : o.correction == "filtered" ? fmt::format("filtered over each lobe ({} taps)", o.taps)
                                          : std::string("read per lobe"), 100.0 * map.corrected_summary.mean_abs, 100.0 * map.corrected_summary.max_abs,
             100.0 * map.corrected_summary.grazing_mean_abs, 100.0 * map.grazing_reduction);
  fmt::print("SH9 irradiance: mean |error| {:.2f}%, max {:.2f}%\n", 100.0 * map.sh_summary.mean_abs,
             100.0 * map.sh_summary.max_abs);
  const int no_signal = map.split_sum_summary.no_signal_cells + map.sh_summary.no_signal_cells;
  if (no_signal > 0) {
    fmt::print("no signal (reference 0 or below 1e-6 of the mean, left out of the figures): {} of {} split-sum cells, "
               "{} of {} SH9 cells\n", map.split_sum_summary.no_signal_cells,
               map.split_sum_summary.no_signal_cells + map.split_sum_summary.signal_cells, map.sh_summary.no_signal_cells,
               map.sh_summary.no_signal_cells + map.sh_summary.signal_cells);
  }
  for (const auto& f : j["outputs"]) fmt::print("wrote {}\n", f.get<std::string>());
}

void add_ibl_error_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<IblErrorCliOptions>();
  auto* sub = app.add_subcommand("ibl-error", "the error of the split sum and of SH9 irradiance against the path "
                                              "tracer, per roughness and N.V, for a lat-long environment");
  sub->add_option("INPUT", o->input, "lat-long environment (.exr, .hdr), 2:1")->required();
  sub->add_option("--out", o->out, "folder for ibl_error.json, split_sum_error.png/.svg, corrected_error.png, index.html")->required();
  sub->add_option("--model", o->model, "ggx or filament (the split-sum models)")->capture_default_str();
  sub->add_option("--param", o->params, "NAME=VALUE, repeatable (see brdf list); not the roughness, not ggx's kd "
                                        "or filament's metallic (the map is of the specular lobe)");
  sub->add_option("--roughness", o->roughness, "perceptual roughness of the rows")->delimiter(',')->capture_default_str();
  sub->add_option("--bins", o->bins, "N.V bins over (0, 1]")->capture_default_str();
  sub->add_option("--size", o->size, "pixels across each sphere image")->capture_default_str();
  sub->add_option("--spp", o->spp, "path-traced samples per pixel of the reference")->capture_default_str();
  sub->add_option("--seed", o->seed, "seed of the reference renders")->capture_default_str();
  sub->add_option("--threads", o->threads, "0: all cores")->capture_default_str();
  sub->add_option("--split-sum-lookup,--correction", o->correction, "the corrected map's split-sum lookup (--correction: "
                                                "its older name): lobes (each part at its lobe's first "
                                                "moments), dominant (normalize(mix(R, n, alpha^2))) or filtered (each part the mean "
                                                "of --taps reads over its own lobe)")
      ->capture_default_str();
  sub->add_option("--taps", o->taps, "--correction filtered: chain reads per pixel, in [1, 1024]")->capture_default_str();
  sub->add_option("--specular-size", o->specular_size, "face size of the prefiltered GGX chain's level 0 (a power "
                                                       "of two; the game renderer's default)")->capture_default_str();
  sub->add_flag("--json", o->json, "machine-readable output (the file ibl_error.json)");
  sub->callback([o, &command] { command.run = [o] { run_ibl_error(*o); }; });
}

}  // namespace

const CommandRegistration registration_ibl_error(98, add_ibl_error_command);

}  // namespace shadelab::cli
