// shadelab compare A B [--heatmap FILE.png] [--side-by-side FILE.png] [--exposure EV] [--json] ...: how far
// image A is from the reference B (RMSE, relative MSE, maximum error, mean-luminance ratio, SSIM), with an
// error heat map and an A | B | heat-map picture. Definitions: src/shadelab/image/metrics.h, docs/compare.md.
#include <fmt/core.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "cli_common.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/metrics.h"

namespace shadelab::cli {

namespace {

struct CompareCliOptions {
  std::string a;
  std::string b;
  std::string heatmap;
  std::string side_by_side;
  double exposure = 0.0;
  double scale = 0.0;
  std::string metric = "relative";
  double epsilon = default_relative_mse_epsilon;
  bool ignore_alpha = false;
  bool json = false;
};

std::string quoted(const std::string& path) { return "'" + path + "'"; }

// The colour layout of a file as read: grey or RGB, with or without alpha.
std::string layout_text(const ReadInfo& info) {
  if (info.grey) return info.had_alpha ? "grey + alpha" : "grey";
  return info.had_alpha ? "RGBA" : "RGB";
}

std::string channels_text(const ReadInfo& info) {
  return fmt::format("{} channel{} ({})", info.channels, info.channels == 1 ? "" : "s", layout_text(info));
}

void check_png_output(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png") throw UsageError(option + ": the picture is written as .png, got " + quoted(path));
}

const char* channel_name(int c) { return c == 0 ? "R" : (c == 1 ? "G" : "B"); }

// A number for the text table: 6 significant digits, "n/a" for NaN.
std::string num(double v) { return std::isnan(v) ? std::string("n/a") : fmt::format("{:.6g}", v); }

void run_compare(const CompareCliOptions& o) {
  if (!std::isfinite(o.exposure)) throw UsageError("--exposure: must be a finite number of stops");
  if (!std::isfinite(o.scale) || o.scale < 0.0) {
    throw UsageError(fmt::format("--scale: {} must be a finite error > 0 (0: automatic)", o.scale));
  }
  if (!std::isfinite(o.epsilon) || !(o.epsilon > 0.0)) {
    throw UsageError(fmt::format("--epsilon: {} must be a finite number > 0", o.epsilon));
  }
  ErrorMetric metric = ErrorMetric::absolute;
  if (o.metric == "absolute") metric = ErrorMetric::absolute;
  else if (o.metric == "relative") metric = ErrorMetric::relative;
  else throw UsageError("--heatmap-metric: '" + o.metric + "' is not one of absolute | relative");
  check_png_output("--heatmap", o.heatmap);
  check_png_output("--side-by-side", o.side_by_side);
  check_outputs({{"A", o.a}, {"B", o.b}}, {{"--heatmap", o.heatmap}, {"--side-by-side", o.side_by_side}});

  work_begins();
  ReadInfo info_a;
  ReadInfo info_b;
  const Image a = unwrap(read_image(o.a, &info_a));
  const Image b = unwrap(read_image(o.b, &info_b));
  // Channel layouts must agree: grey against colour, or alpha on one side only, is an error. Other EXR
  // channels (depth, extra layers) are not read and not compared.
  const bool grey_differs = info_a.grey != info_b.grey;
  const bool alpha_differs = info_a.had_alpha != info_b.had_alpha;
  if (grey_differs || (alpha_differs && !o.ignore_alpha)) {
    throw UsageError(fmt::format("compare: {} has {}, {} has {}: the channel layouts differ{}", quoted(o.a),
                                 channels_text(info_a), quoted(o.b), channels_text(info_b),
                                 grey_differs ? "" : " (--ignore-alpha compares the colour channels only)"));
  }
  CompareOptions co;
  co.name_a = quoted(o.a);
  co.name_b = quoted(o.b);
  co.relative_mse_epsilon = o.epsilon;
  co.exposure_stops = o.exposure;
  co.heatmap_metric = metric;
  co.heatmap_scale = o.scale;
  unwrap(check_comparable(a, b, co));
  for (const auto& [path, info] : {std::pair{o.a, info_a}, std::pair{o.b, info_b}}) {
    if (info.nonfinite_repaired > 0) {
      warn(quoted(path) + ": " + std::to_string(info.nonfinite_repaired) + " NaN/Inf values replaced by 0");
    }
  }

  const ImageDifference d = unwrap(compare_images(a, b, co));
  Heatmap heat;
  if (!o.heatmap.empty() || !o.side_by_side.empty()) heat = unwrap(error_heatmap(a, b, co));
  {  // the pictures are one output set (issue 40, finding 7): replaced together or not at all
    std::vector<std::pair<std::filesystem::path, std::vector<char>>> files;
    if (!o.heatmap.empty()) files.emplace_back(o.heatmap, unwrap(encode_image(heat.image, o.heatmap)));
    if (!o.side_by_side.empty()) {
      files.emplace_back(o.side_by_side, unwrap(encode_image(unwrap(side_by_side(a, b, heat.image, co)), o.side_by_side)));
    }
    unwrap(write_files_atomically(files));
  }

  if (o.json) {
    nlohmann::json j = {{"a", o.a},
                        {"b", o.b},
                        {"reference", "b"},
                        {"width", d.width},
                        {"height", d.height},
                        {"channels_a", info_a.channels},
                        {"channels_b", info_b.channels},
                        {"mse", d.mse},
                        {"rmse", d.rmse},
                        {"relative_mse", d.relative_mse},
                        {"relative_mse_epsilon", d.relative_mse_epsilon},
                        {"max_error", d.max_abs_error},
                        {"max_error_at", {d.max_x, d.max_y}},
                        {"max_error_channel", channel_name(d.max_channel)},
                        {"mean_luminance_a", d.mean_luminance_a},
                        {"mean_luminance_b", d.mean_luminance_b},
                        {"mean_luminance_ratio", d.mean_luminance_ratio},  // NaN is written as null
                        {"ssim", d.ssim},
                        {"ssim_windows", d.ssim_windows},
                        {"exposure", o.exposure}};
    if (!o.heatmap.empty() || !o.side_by_side.empty()) {
      j["heatmap_metric"] = o.metric;
      j["heatmap_scale"] = heat.scale;
      j["heatmap_scale_automatic"] = !(o.scale > 0.0);
      j["heatmap_max_error"] = heat.max_error;
    }
    if (!o.heatmap.empty()) j["heatmap"] = o.heatmap;
    if (!o.side_by_side.empty()) j["side_by_side"] = o.side_by_side;
    print_json(j);
    return;
  }
  const auto file_line = [](const char* label, const std::string& path, const Image& img, const ReadInfo& info,
                            const char* role) {
    fmt::print("{}  {}  {} x {}, {} {}, {}{}\n", label, path, img.width, img.height, info.format, info.sample_type,
               channels_text(info), role);
  };
  file_line("A", o.a, a, info_a, "");
  file_line("B", o.b, b, info_b, " - the reference");
  fmt::print("\n");
  fmt::print("  {:<22} {}\n", "rmse", num(d.rmse));
  fmt::print("  {:<22} {:<12} (a - b)^2 / (b^2 + {:g}), mean over pixels and channels\n", "relative mse",
             num(d.relative_mse), d.relative_mse_epsilon);
  fmt::print("  {:<22} {:<12} at ({}, {}), channel {}\n", "max error", num(d.max_abs_error), d.max_x, d.max_y,
             channel_name(d.max_channel));
  fmt::print("  {:<22} {:<12} A {} / B {}\n", "mean luminance ratio", num(d.mean_luminance_ratio),
             num(d.mean_luminance_a), num(d.mean_luminance_b));
  if (d.ssim_windows > 0) {
    fmt::print("  {:<22} {:<12} luminance at {:+g} EV, clamped, sRGB-encoded; {} windows of 11 x 11\n", "ssim",
               num(d.ssim), o.exposure, d.ssim_windows);
  } else {
    fmt::print("  {:<22} {:<12} the images are smaller than one 11 x 11 window\n", "ssim", "n/a");
  }
  if (!o.heatmap.empty()) {
    fmt::print("\nwrote {} ({} error, black 0 to white {}{})\n", o.heatmap, o.metric, num(heat.scale),
               o.scale > 0.0 ? "" : ", the 99th percentile");
  }
  if (!o.side_by_side.empty()) {
    fmt::print("{}wrote {} (A | B | heat map, A and B at {:+g} EV)\n", o.heatmap.empty() ? "\n" : "", o.side_by_side,
               o.exposure);
  }
}

void add_compare_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<CompareCliOptions>();
  auto* sub = app.add_subcommand("compare", "how far image A is from the reference B: RMSE, relative MSE, maximum "
                                            "error, mean-luminance ratio, SSIM; heat map and side-by-side PNGs");
  sub->add_option("A", o->a, "the image to measure (.exr, .hdr, .png)")->required();
  sub->add_option("B", o->b, "the reference image, same size and channel layout")->required();
  sub->add_option("--heatmap", o->heatmap, "write the per-pixel error through a black-to-white ramp (.png)");
  sub->add_option("--side-by-side", o->side_by_side, "write A | B | heat map (.png)");
  sub->add_option("--exposure", o->exposure, "stops applied to A and B in the side-by-side and before SSIM")
      ->capture_default_str();
  sub->add_option("--scale", o->scale, "the error drawn white in the heat map (default: the 99th percentile)");
  sub->add_option("--heatmap-metric", o->metric, "per-pixel error: absolute or relative")->capture_default_str();
  sub->add_option("--epsilon", o->epsilon, "eps in the relative MSE's (a - b)^2 / (b^2 + eps)")->capture_default_str();
  sub->add_flag("--ignore-alpha", o->ignore_alpha, "compare files that differ only in having an alpha channel");
  sub->add_flag("--json", o->json, "machine-readable output");
  sub->callback([o, &command] { command.run = [o] { run_compare(*o); }; });
}

}  // namespace

const CommandRegistration registration_compare(90, add_compare_command);

}  // namespace shadelab::cli
