// shadelab ibl-error INPUT --out DIR [--model ggx|filament] [--param K=V ...] [--roughness R,...] [--bins N]
// [--size N] [--spp N] [--seed S] [--threads N] [--json]: the error of the engine-side IBL shortcuts against
// the path tracer (render/ibl_error.h, docs/envmap.md "The error of the shortcuts"): a sphere lit by the
// lat-long INPUT alone, the split sum per roughness x N.V bin and SH9 irradiance per N.V bin. Writes into
// DIR: ibl_error.json (every cell), split_sum_error.png (|error| per cell through the heat ramp, rows
// roughness from the top, columns N.V from the left), split_sum_error.svg (signed error against N.V, one
// line per roughness, and the SH9 line) and index.html (the tables and both pictures), each atomically.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "cli_common.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/metrics.h"
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
  bool json = false;
};

constexpr int cell_pixels = 24;

nlohmann::json cells_json(const IblErrorRow& row) {
  nlohmann::json cells = nlohmann::json::array();
  for (const IblErrorCell& c : row.cells) {
    cells.push_back({{"nv_lo", c.nv_lo}, {"nv_hi", c.nv_hi}, {"pixels", c.pixels}, {"shortcut", c.shortcut},
                     {"reference", c.reference}, {"reference_standard_error", c.reference_standard_error},
                     {"error", c.error}});
  }
  return cells;
}

nlohmann::json summary_json(const IblErrorSummary& s) {
  return {{"mean_abs_error", s.mean_abs}, {"max_abs_error", s.max_abs}, {"grazing_mean_abs_error", s.grazing_mean_abs}};
}

// |error| of each cell through the heat ramp, white at `scale`.
Image heat_grid(const std::vector<IblErrorRow>& rows, double scale) {
  const int cols = rows.empty() ? 1 : static_cast<int>(rows.front().cells.size());
  Image img(cols * cell_pixels, static_cast<int>(rows.size()) * cell_pixels);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (int k = 0; k < cols; ++k) {
      const IblErrorCell& c = rows[i].cells[static_cast<std::size_t>(k)];
      const Rgb colour = c.pixels > 0 ? heat_ramp(std::abs(c.error) / scale) : Rgb::gray(0.2);
      for (int y = 0; y < cell_pixels; ++y)
        for (int x = 0; x < cell_pixels; ++x) img.set(k * cell_pixels + x, static_cast<int>(i) * cell_pixels + y, colour);
    }
  }
  return img;
}

LinePlot error_plot(const IblErrorMap& map, const std::string& input) {
  LinePlot p;
  p.title = "IBL shortcuts vs path tracer: " + std::filesystem::path(input).filename().string() + ", " + map.model;
  p.x.label = "N.V (bin centre)";
  p.y.label = "(shortcut - reference) / reference";
  const auto series = [](const IblErrorRow& row, const std::string& label) {
    Series s;
    s.label = label;
    for (const IblErrorCell& c : row.cells) {
      s.x.push_back(0.5 * (c.nv_lo + c.nv_hi));
      s.y.push_back(c.pixels > 0 ? c.error : std::nan(""));
    }
    return s;
  };
  for (const IblErrorRow& row : map.split_sum) p.series.push_back(series(row, fmt::format("split sum, r = {:.2f}", row.roughness)));
  Series sh = series(map.sh, "SH9 irradiance (Lambert)");
  sh.dashed = true;
  p.series.push_back(std::move(sh));
  p.lines.push_back({0.0, "", std::nullopt});
  return p;
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string html_page(const IblErrorMap& map, const std::string& input, double scale) {
  std::ostringstream h;
  const auto pct = [](double v) { return fmt::format("{:+.2f}%", 100.0 * v); };
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>shadelab ibl-error: "
    << html_escape(std::filesystem::path(input).filename().string()) << "</title>\n"
    << "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}td,th{border:1px solid #999;"
       "padding:2px 6px;text-align:right}</style></head><body>\n"
    << "<h1>Image-based lighting: the shortcuts against the path tracer</h1>\n<p>Environment <code>"
    << html_escape(input) << "</code>, model <code>" << html_escape(map.model)
    << "</code>. A unit sphere lit by the environment alone; each cell is (shortcut - reference) / reference of "
       "the mean luminance over the pixels of that N.V bin (docs/envmap.md).</p>\n";
  const auto table = [&](const std::vector<IblErrorRow>& rows, const std::string& first) {
    h << "<table><tr><th>" << first << "</th>";
    for (const IblErrorCell& c : rows.front().cells) h << fmt::format("<th>N.V {:.3g}-{:.3g}</th>", c.nv_lo, c.nv_hi);
    h << "</tr>\n";
    for (const IblErrorRow& row : rows) {
      h << "<tr><th>" << (first == "roughness" ? fmt::format("{:.3g}", row.roughness) : std::string("Lambert")) << "</th>";
      for (const IblErrorCell& c : row.cells) h << "<td>" << (c.pixels > 0 ? pct(c.error) : std::string("-")) << "</td>";
      h << "</tr>\n";
    }
    h << "</table>\n";
  };
  const auto summary = [&](const IblErrorSummary& s) {
    h << fmt::format("<p>mean |error| {:.2f}%, max {:.2f}%, mean at N.V &lt; 0.3 {:.2f}%</p>\n", 100.0 * s.mean_abs,
                     100.0 * s.max_abs, 100.0 * s.grazing_mean_abs);
  };
  h << "<h2>Split sum (prefiltered GGX chain x DFG table)</h2>\n";
  table(map.split_sum, "roughness");
  summary(map.split_sum_summary);
  h << fmt::format("<p><img src=\"split_sum_error.png\" alt=\"|error| per cell, white at {:.3g}\"> |error| per cell "
                   "(rows: roughness, top the smoothest; columns: N.V from 0), white at {:.3g}.</p>\n", scale, scale);
  h << "<h2>SH9 irradiance (white Lambert sphere)</h2>\n";
  table({map.sh}, "");
  summary(map.sh_summary);
  h << "<p><img src=\"split_sum_error.svg\" alt=\"signed error against N.V\" width=\"800\"></p>\n</body></html>\n";
  return h.str();
}

void run_ibl_error(const IblErrorCliOptions& o) {
  check_range("--bins", true, o.bins, 1, 64);
  check_range("--size", true, o.size, 16, 2048);
  check_range("--spp", true, o.spp, 1, 65536);
  check_range("--threads", true, o.threads, 0, max_render_threads);
  if (o.roughness.empty()) throw UsageError("--roughness: give at least one value");
  for (const double r : o.roughness) {
    if (!(r > 0.0 && r <= 1.0)) throw UsageError(fmt::format("--roughness: {} is not in (0, 1]", r));
  }
  if (o.model != "ggx" && o.model != "filament") {
    throw UsageError("--model: '" + o.model + "' has no split-sum specular ambient (ggx, filament)");
  }
  const std::uint64_t seed = parse_seed("--seed", o.seed);
  const std::filesystem::path dir(o.out);
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw UsageError("--out: '" + dir.string() + "' exists and is not a folder");
  }
  const std::vector<std::string> names{"ibl_error.json", "split_sum_error.png", "split_sum_error.svg", "index.html"};
  std::vector<NamedPath> outputs;
  for (const auto& n : names) outputs.push_back({"--out", dir / n});
  check_outputs({{"INPUT", o.input}}, outputs);
  Image latlong = unwrap(read_image(o.input));
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
  const double scale = std::max(0.01, map.split_sum_summary.max_abs);
  nlohmann::json rows = nlohmann::json::array();
  for (const IblErrorRow& row : map.split_sum) rows.push_back({{"roughness", row.roughness}, {"cells", cells_json(row)}});
  nlohmann::json pj = nlohmann::json::object();
  for (const auto& [k, v] : params) pj[k] = v;
  nlohmann::json files = nlohmann::json::array();
  for (const auto& n : names) files.push_back((dir / n).string());
  const nlohmann::json j = {
      {"input", o.input}, {"model", o.model}, {"params", pj}, {"nv_bins", o.bins}, {"size", o.size}, {"spp", o.spp},
      {"seed", seed}, {"error", "(shortcut - reference) / reference of the mean luminance of a bin's pixels"},
      {"split_sum", {{"rows", rows}, {"summary", summary_json(map.split_sum_summary)}, {"heat_scale", scale}}},
      {"sh", {{"cells", cells_json(map.sh)}, {"summary", summary_json(map.sh_summary)}}},
      {"outputs", files}, {"seconds", map.seconds}};
  const std::string text = j.dump(2) + "\n";
  unwrap(write_file_atomically(dir / names[0], std::vector<char>(text.begin(), text.end())));
  unwrap(write_image(heat_grid(map.split_sum, scale), dir / names[1]));
  unwrap(write_plot(error_plot(map, o.input), dir / names[2]));
  const std::string page = html_page(map, o.input, scale);
  unwrap(write_file_atomically(dir / names[3], std::vector<char>(page.begin(), page.end())));
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("{}: {} sphere, {} roughness x {} N.V bins, {} spp reference, {:.1f} s\n", o.input, o.model,
             map.split_sum.size(), o.bins, o.spp, map.seconds);
  fmt::print("split sum: mean |error| {:.2f}%, max {:.2f}%, at N.V < 0.3 {:.2f}%\n", 100.0 * map.split_sum_summary.mean_abs,
             100.0 * map.split_sum_summary.max_abs, 100.0 * map.split_sum_summary.grazing_mean_abs);
  fmt::print("SH9 irradiance: mean |error| {:.2f}%, max {:.2f}%\n", 100.0 * map.sh_summary.mean_abs,
             100.0 * map.sh_summary.max_abs);
  for (const auto& f : files) fmt::print("wrote {}\n", f.get<std::string>());
}

void add_ibl_error_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<IblErrorCliOptions>();
  auto* sub = app.add_subcommand("ibl-error", "the error of the split sum and of SH9 irradiance against the path "
                                              "tracer, per roughness and N.V, for a lat-long environment");
  sub->add_option("INPUT", o->input, "lat-long environment (.exr, .hdr), 2:1")->required();
  sub->add_option("--out", o->out, "folder for ibl_error.json, split_sum_error.png/.svg, index.html")->required();
  sub->add_option("--model", o->model, "ggx or filament (the split-sum models)")->capture_default_str();
  sub->add_option("--param", o->params, "NAME=VALUE, repeatable (see brdf list); not the roughness, not ggx's kd "
                                        "or filament's metallic (the map is of the specular lobe)");
  sub->add_option("--roughness", o->roughness, "perceptual roughness of the rows")->delimiter(',')->capture_default_str();
  sub->add_option("--bins", o->bins, "N.V bins over (0, 1]")->capture_default_str();
  sub->add_option("--size", o->size, "pixels across each sphere image")->capture_default_str();
  sub->add_option("--spp", o->spp, "path-traced samples per pixel of the reference")->capture_default_str();
  sub->add_option("--seed", o->seed, "seed of the reference renders")->capture_default_str();
  sub->add_option("--threads", o->threads, "0: all cores")->capture_default_str();
  sub->add_flag("--json", o->json, "machine-readable output (the file ibl_error.json)");
  sub->callback([o, &command] { command.run = [o] { run_ibl_error(*o); }; });
}

}  // namespace

const CommandRegistration registration_ibl_error(98, add_ibl_error_command);

}  // namespace shadelab::cli
