// shadelab merge PART... --out IMAGE.exr [--png IMAGE.png]: adds the parts of a render made with
// `shadelab render --shard I/N` (shard_file.h) into the image `shadelab render` writes on one machine, bit for
// bit. A missing, duplicated or foreign part, or a part that is not a shard, is one line naming the file and
// exit code 2, and nothing is written. --check only reports which shards are there (exit 0 all, 1 some missing).
#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "cli_common.h"
#include "progress.h"
#include "shadelab/render/film.h"
#include "shadelab/render/shard_file.h"

namespace shadelab::cli {

namespace {

struct MergeCliOptions {
  std::vector<std::string> parts;
  std::string out;
  std::string png;
  double exposure = 0.0;
  ViewCliOptions view;  // --view, --look, --ocio-config, --filmic
  bool check = false;
  bool json = false;
  bool progress = false;
};

std::string index_list(const std::vector<int>& v) {
  std::string s;
  for (std::size_t k = 0; k < v.size() && k < 32; ++k) s += (k ? "," : "") + std::to_string(v[k]);
  if (v.size() > 32) s += ",...";
  return s;
}

void run_merge(const MergeCliOptions& o) {
  std::vector<std::filesystem::path> parts(o.parts.begin(), o.parts.end());
  if (o.check) {
    if (!o.out.empty() || !o.png.empty()) throw UsageError("--check writes nothing: give no --out or --png");
    const auto status = unwrap(check_shards(parts));
    const ShardInfo& f = status.first;
    if (o.json) {
      print_json({{"scene", f.scene}, {"count", f.count}, {"split", f.split}, {"spp", f.spp}, {"present", status.present},
                  {"missing", status.missing}, {"complete", status.missing.empty()}, {"nonfinite_samples", status.nonfinite_samples}});
    } else {
      fmt::print("{}: {} of {} shards ({} split, {} spp){}{}\n", f.scene, status.present.size(), f.count, f.split, f.spp,
                 status.missing.empty() ? "" : "; missing ", index_list(status.missing));
    }
    std::fflush(stdout);
    if (!status.missing.empty()) std::exit(1);
    return;
  }
  if (o.out.empty()) throw UsageError("--out: the merged image (.exr) is required");
  require_extension("--out", o.out, {".exr"}, "the linear image");
  if (!o.png.empty()) require_extension("--png", o.png, {".png"}, "the tone-mapped image");
  if (!std::isfinite(o.exposure)) throw UsageError("--exposure: must be finite");
  const DisplayView view = parse_view_options(o.view, ViewTransform::standard);
  {
    std::vector<NamedPath> inputs;
    for (const auto& p : parts) inputs.push_back({"PART", p});
    std::vector<NamedPath> outputs{{"--out", o.out}};
    if (!o.png.empty()) outputs.push_back({"--png", o.png});
    check_outputs(inputs, outputs);
  }
  work_begins();
  ProgressBar bar("merge", o.progress);
  auto merged = merge_shards(parts, [&](double f) { bar.update(f); });
  bar.finish();
  if (!merged) throw UsageError(merged.error().message);
  FilmOutputs film;
  film.exr = o.out;
  if (!o.png.empty()) film.png = o.png;
  film.exposure_stops = o.exposure;
  film.view = view;
  const auto written = unwrap(write_film(merged->result, film));
  const ShardInfo& f = merged->status.first;
  if (o.json) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& p : written) files.push_back(p.string());
    print_json({{"scene", f.scene}, {"outputs", files}, {"width", f.width}, {"height", f.height}, {"spp", f.spp},
                {"count", f.count}, {"split", f.split}, {"nonfinite_samples", merged->status.nonfinite_samples}});
  } else {
    fmt::print("{}: {} parts ({} split) merged, {} x {}, {} spp\n", f.scene, f.count, f.split, f.width, f.height, f.spp);
    for (const auto& p : written) fmt::print("wrote {}\n", p.string());
  }
  std::fflush(stdout);
  if (merged->status.nonfinite_samples > 0) {
    std::cerr << "shadelab: " << f.scene << ": " << merged->status.nonfinite_samples
              << " samples were NaN or infinite (NaN pixels in the image); the render is wrong\n";
    std::exit(1);
  }
}

void add_merge_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<MergeCliOptions>();
  auto* sub = app.add_subcommand("merge", "merge the parts of `render --shard I/N` into the single-machine image");
  sub->add_option("PART", o->parts, "the parts (.exr), every shard 0 .. N-1 once, in any order")->required();
  sub->add_option("--out", o->out, "linear EXR output");
  sub->add_option("--png", o->png, "tone-mapped PNG output (default: none)");
  sub->add_option("--exposure", o->exposure, "PNG exposure in stops")->capture_default_str();
  add_view_options(sub, o->view, "standard", true);
  sub->add_flag("--check", o->check, "only report the shards present and missing (exit 1 while any is missing)");
  sub->add_flag("--json", o->json, "machine-readable summary");
  sub->add_flag("--progress", o->progress, "show the progress bar even when stderr is not a terminal");
  sub->callback([o, &command] { command.run = [o] { run_merge(*o); }; });
}

}  // namespace

const CommandRegistration registration_merge(15, add_merge_command);

}  // namespace shadelab::cli
