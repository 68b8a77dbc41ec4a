// shadelab report SCENE [--out DIR] [--spp N] [--ibl-error]: renders the scene with the reference path tracer and with game
// shading, in three lightings that isolate the approximations, compares them per material, and writes one
// HTML page (DIR/index.html) with the images, heat maps and a table. --ibl-error adds the IBL error map of the
// scene's environment (render/ibl_error.h, `shadelab ibl-error`'s defaults at the report's --spp) in
// DIR/ibl_error/ and a section that links it.
//
//   punctual:     only the punctual lights (and the sky's sun), direct light (reference depth 1): the game
//                 shading equation should agree within noise;
//   environment:  only the environment (sky without sun, HDRI, hemisphere lights), direct light: SH9 diffuse
//                 and prefiltered specular against the exact integral;
//   full:         the scene as given, reference at full depth: adds interreflection and area lights, which
//                 game shading leaves out or approximates.
//
// Each material's row names the specular ambient the game renderer gave it (split-sum, phong-chain, none); the
// materials the split sum shades (the default for ggx and filament since 2026-12-07) also get, from a second
// game render in the same run, their figures with the Phong chain they had before ("phong_chain" in the JSON,
// the last column of the page's tables).
// Each wrapped-diffuse material gets its expected environment mismatch stated beside the measured one: the
// SH wrap factors (1, (2 - w)/3, (1 - w)^2/4) are the bands of the wrap kernel (cos + w)/(pi (1 + w)^2) over
// every direction with cos > -w, but the BRDF is 0 below the horizon, so under a uniform environment game
// shading gives kd and the reference kd (1 + 2w)/(1 + w)^2 (docs/envmap.md). A render with NaN or infinite
// samples is reported (stderr, "nonfinite_samples") and the command exits with 1.
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include "cli_common.h"
#include "shadelab/core/text.h"
#include "ibl_error_page.h"
#include "progress.h"
#include "report_page.h"
#include "shadelab/brdf/wrapped_diffuse.h"
#include "shadelab/image/flip.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/metrics.h"
#include "shadelab/render/accel.h"
#include "shadelab/render/film.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/render/ibl_error.h"
#include "shadelab/scene/scene_json.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;

struct ReportOptions {
  std::string scene;
  std::string out = "report";
  int spp = 64;
  int width = 0;
  bool ibl_error = false;
  bool json = false;
  double exposure = 0.0;
  ViewCliOptions view;  // --view (default filmic, the report's view before --view), --look, --ocio-config
};

// Reference / game exit radiance of wrapped diffuse under a uniform environment: the hemisphere integral of
// (cos + w)/(pi (1 + w)^2) is (1 + 2w)/(1 + w)^2, while the SH wrap factors' band 0 (1) counts the whole
// kernel, below the horizon included (wrapped_diffuse.h).
double wrap_uniform_reference_over_game(double w) { return (1.0 + 2.0 * w) / ((1.0 + w) * (1.0 + w)); }

Scene variant(const Scene& base, const std::string& kind) {
  Scene s = base;
  if (kind == "full") return s;
  for (auto& m : s.materials) m.emission = {};  // emitters are neither punctual nor environment
  std::vector<SceneLight> lights;
  if (kind == "punctual") {
    for (const auto& l : s.lights) {
      if (!std::holds_alternative<HemisphereLight>(l)) lights.push_back(l);
    }
    if (s.environment.kind == Environment::Kind::sky) {
      lights.push_back(DirectionalLight{s.environment.sky.sun_direction, s.environment.sky.sun_irradiance});
    }
    s.environment.kind = Environment::Kind::none;
  } else {  // environment
    for (const auto& l : s.lights) {
      if (std::holds_alternative<HemisphereLight>(l)) lights.push_back(l);
    }
    s.environment.sky.sun_irradiance = {};
  }
  s.lights = lights;
  s.settings.max_depth = 1;
  return s;
}

// Per-pixel material index of the primary hit through each pixel's centre (-1: background).
std::vector<int> material_ids(const Scene& s) {
  const Accelerator accel(s);
  const Vec3 forward = normalize(s.camera.look_at - s.camera.position);
  const Vec3 right = normalize(cross(forward, s.camera.up));
  const Vec3 up = cross(right, forward);
  const double t = std::tan(0.5 * deg_to_rad(s.camera.vfov_deg));
  const double aspect = static_cast<double>(s.camera.width) / s.camera.height;
  std::vector<int> ids(static_cast<std::size_t>(s.camera.width) * static_cast<std::size_t>(s.camera.height), -1);
  for (int y = 0; y < s.camera.height; ++y) {
    for (int x = 0; x < s.camera.width; ++x) {
      const double sx = (2.0 * (x + 0.5) / s.camera.width - 1.0) * t * aspect;
      const double sy = (1.0 - 2.0 * (y + 0.5) / s.camera.height) * t;
      Hit h;
      if (accel.intersect(Ray{s.camera.position, normalize(forward + right * sx + up * sy)}, h)) {
        ids[static_cast<std::size_t>(y) * static_cast<std::size_t>(s.camera.width) + static_cast<std::size_t>(x)] = h.material;
      }
    }
  }
  return ids;
}

struct MaskedFigures {
  int pixels = 0;
  double rmse = 0.0;
  double relative_mse = 0.0;
  double luminance_ratio = 1.0;  // game / reference
};

MaskedFigures masked(const Image& game, const Image& ref, const std::vector<int>& ids, int material) {
  MaskedFigures m;
  double se = 0.0, rel = 0.0, lg = 0.0, lr = 0.0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] != material) continue;
    ++m.pixels;
    for (int c = 0; c < 3; ++c) {
      const double a = static_cast<double>(game.data[3 * i + static_cast<std::size_t>(c)]);
      const double b = static_cast<double>(ref.data[3 * i + static_cast<std::size_t>(c)]);
      se += (a - b) * (a - b);
      rel += (a - b) * (a - b) / (b * b + default_relative_mse_epsilon);  // as compare_images (metrics.h)
    }
    const auto pixel = [i](const Image& img) {
      return Rgb{static_cast<double>(img.data[3 * i]), static_cast<double>(img.data[3 * i + 1]),
                 static_cast<double>(img.data[3 * i + 2])};
    };
    lg += luminance(pixel(game));
    lr += luminance(pixel(ref));
  }
  if (m.pixels > 0) {
    m.rmse = std::sqrt(se / (3.0 * m.pixels));
    m.relative_mse = rel / (3.0 * m.pixels);
    m.luminance_ratio = lr > 0.0 ? lg / lr : (lg > 0.0 ? std::numeric_limits<double>::infinity() : 1.0);
  }
  return m;
}

void run_report(const ReportOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!std::isfinite(o.exposure)) throw UsageError("--exposure: must be finite");
  const DisplayView view = parse_view_options(o.view, ViewTransform::filmic);
  Scene scene = o.scene.empty() ? built_in_scene() : unwrap(load_scene(o.scene));
  for (const std::string& w : scene.warnings) std::cerr << "shadelab: warning: " << w << '\n';  // one line each
  if (o.spp < 1) throw UsageError(fmt::format("--spp: {} must be >= 1", o.spp));
  if (o.width < 0 || o.width > 4096) throw UsageError(fmt::format("--width: {} is out of range [16, 4096]", o.width));
  if (o.width > 0) {
    if (o.width < 16) throw UsageError(fmt::format("--width: {} is out of range [16, 4096]", o.width));
    scene.camera.height = std::max(1, scene.camera.height * o.width / scene.camera.width);
    scene.camera.width = o.width;
  }
  const fs::path dir(o.out);
  {
    std::vector<NamedPath> outputs{{"--out", dir / "index.html"}};
    for (const char* kind : {"punctual", "environment", "full"}) {
      for (const char* file : {"_reference.png", "_reference.exr", "_game.png", "_game.exr", "_heatmap.png", "_flip.png"}) {
        outputs.push_back({"--out", dir / (std::string(kind) + file)});
      }
    }
    if (o.ibl_error) {
      if (scene.environment.kind == Environment::Kind::none) {
        throw UsageError("--ibl-error: the scene '" + scene.source + "' has no environment to measure");
      }
      for (const auto& n : ibl_error_file_names()) outputs.push_back({"--out", dir / "ibl_error" / n});
    }
    check_outputs(scene_inputs(scene), outputs, OutputFolders::created);
  }
  work_begins();
  std::error_code ec;
  // Every file of the report is encoded first and published at the end as one output set (issue 40, 7).
  std::vector<std::pair<fs::path, std::vector<char>>> files;
  const std::vector<int> ids = material_ids(scene);
  nlohmann::json sections = nlohmann::json::array();
  std::string body;
  std::vector<std::string> wrap_lines;
  ProgressBar bar("report", false);
  std::uint64_t nonfinite = 0;
  const char* kinds[3] = {"punctual", "environment", "full"};
  for (int k = 0; k < 3; ++k) {
    const std::string kind = kinds[k];
    const Scene s = variant(scene, kind);
    RenderOptions ro;
    ro.spp = o.spp;
    auto ref = render_scene(s, ro);
    if (!ref) throw UsageError(scene.source + ": " + ref.error().message);
    GameOptions go;
    auto game = render_game(s, go);
    if (!game) throw UsageError(scene.source + ": " + game.error().message);
    // The materials the split sum shades by default, shown beside what the Phong chain gave them (the default
    // before 2026-12-07): the same game render with GameGgxSpecular::phong, in the same run.
    const auto ambients = unwrap(game_specular_ambients(s, go));
    std::optional<RenderResult> before;
    if (std::find(ambients.begin(), ambients.end(), GameSpecularAmbient::split_sum) != ambients.end()) {
      GameOptions phong = go;
      phong.ggx_specular = GameGgxSpecular::phong;
      auto r = render_game(s, phong);
      if (!r) throw UsageError(scene.source + ": " + r.error().message);
      nonfinite += r->stats.nonfinite_samples;
      before = std::move(r).value();
    }
    nonfinite += ref->stats.nonfinite_samples + game->stats.nonfinite_samples;
    bar.update((k + 1) / 3.0);
    CompareOptions co;
    co.name_a = kind + " game";
    co.name_b = kind + " reference";
    const ImageDifference d = unwrap(compare_images(game->beauty, ref->beauty, co));
    const Heatmap heat = unwrap(error_heatmap(game->beauty, ref->beauty, co));
    // The display values the PNGs show (--view, --exposure), once per image: FLIP below reads the same ones.
    const Image ref_display = unwrap(apply_view(ref->beauty, o.exposure, view));
    const Image game_display = unwrap(apply_view(game->beauty, o.exposure, view));
    for (const auto& [img, shown, name] : {std::tuple{&ref->beauty, &ref_display, "reference"},
                                           std::tuple{&game->beauty, &game_display, "game"}}) {
      const fs::path png = dir / (kind + "_" + name + ".png"), exr = dir / (kind + "_" + name + ".exr");
      files.emplace_back(png, unwrap(encode_image(*shown, png)));
      files.emplace_back(exr, unwrap(encode_image(*img, exr)));
    }
    const fs::path heat_png = dir / (kind + "_heatmap.png");
    files.emplace_back(heat_png, unwrap(encode_image(heat.image, heat_png)));
    // LDR-FLIP (image/flip.h) of what the PNGs show: the same view and exposure (--view, --exposure; filmic at 0
    // by default), before the sRGB encoding; its map through the heat ramp, white at 1.
    FlipOptions fo;
    fo.name_test = kind + " game";
    fo.name_reference = kind + " reference";
    const FlipResult fl = unwrap(flip(game_display, ref_display, fo));
    {
      Image flip_img(fl.map.width, fl.map.height);
      for (int y = 0; y < fl.map.height; ++y)
        for (int x = 0; x < fl.map.width; ++x) flip_img.set(x, y, heat_ramp(fl.map.at(x, y)));
      const fs::path flip_png = dir / (kind + "_flip.png");
      files.emplace_back(flip_png, unwrap(encode_image(flip_img, flip_png)));
    }
    const auto masked_flip = [&fl, &ids](int material) {
      double total = 0.0;
      long long n = 0;
      for (std::size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] != material) continue;
        total += fl.map.values[i];
        ++n;
      }
      return n > 0 ? total / static_cast<double>(n) : 0.0;
    };
    nlohmann::json materials = nlohmann::json::array();
    std::string rows;
    const std::string ptr = fmt::format("/sections/{}", k);
    // A figure of the page: its exact value (data-value) and the JSON pointer of the same value in --json's
    // output (data-json), for the page's browser test; the text shows `shown` digits.
    const auto cell = [](double v, const std::string& pointer, const std::string& shown) {
      return fmt::format("<td data-json=\"{}\" data-value=\"{}\">{}</td>", pointer, exact_number(v),
                         std::isfinite(v) ? fmt::format(fmt::runtime("{:" + shown + "}"), v) : std::string("-"));
    };
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
      const MaskedFigures f = masked(game->beauty, ref->beauty, ids, static_cast<int>(m));
      if (f.pixels == 0) continue;
      const std::string mp = fmt::format("{}/materials/{}", ptr, materials.size());
      const double mflip = masked_flip(static_cast<int>(m));
      nlohmann::json entry = {{"material", scene.materials[m].name}, {"model", scene.materials[m].model}, {"pixels", f.pixels},
                              {"rmse", f.rmse}, {"relative_mse", f.relative_mse}, {"luminance_ratio", f.luminance_ratio}};
      entry["specular_ambient"] = game_specular_ambient_name(ambients[m]);
      entry["flip"] = mflip;
      std::string phong_cell = "<td></td>";
      if (before && ambients[m] == GameSpecularAmbient::split_sum) {
        const MaskedFigures b = masked(before->beauty, ref->beauty, ids, static_cast<int>(m));
        entry["phong_chain"] = {{"rmse", b.rmse}, {"relative_mse", b.relative_mse}, {"luminance_ratio", b.luminance_ratio}};
        phong_cell = cell(b.luminance_ratio, mp + "/phong_chain/luminance_ratio", ".4f");
      }
      std::string note;
      const Brdf* material_brdf = scene.materials[m].brdf.get();
      if (material_brdf != nullptr && material_brdf->game_wrap() > 0.0 && kind == "environment") {
        const double w = material_brdf->game_wrap();
        const double ratio = wrap_uniform_reference_over_game(w);
        entry["wrap"] = {{"w", w}, {"uniform_reference_over_game", ratio}, {"uniform_luminance_ratio", 1.0 / ratio}};
        note = fmt::format(" (wrap w = {:.3g}: under a uniform environment game kd, reference kd (1+2w)/(1+w)^2 = {:.4f} kd; "
                           "expected game/ref {:.4f})",
                           w, ratio, 1.0 / ratio);
        wrap_lines.push_back(fmt::format("'{}' (w = {:.3g}): under a uniform environment game kd, reference {:.4f} kd, "
                                         "expected luminance game/ref {:.4f} (measured {:.4f})",
                                         scene.materials[m].name, w, ratio, 1.0 / ratio, f.luminance_ratio));
      }
      materials.push_back(entry);
      rows += fmt::format("<tr class=\"material\" data-material=\"{}\" title=\"click: show its pixels\"><td>{}</td><td>{}</td><td>{}</td>"
                          "<td data-json=\"{}/pixels\" data-value=\"{}\">{}</td>{}{}{}{}<td>{}</td>{}</tr>\n",
                          m, xml_escape(scene.materials[m].name), xml_escape(scene.materials[m].model),
                          game_specular_ambient_name(ambients[m]), mp, f.pixels, f.pixels, cell(f.rmse, mp + "/rmse", ".4g"),
                          cell(f.relative_mse, mp + "/relative_mse", ".4g"), cell(mflip, mp + "/flip", ".4f"),
                          cell(f.luminance_ratio, mp + "/luminance_ratio", ".4f"), xml_escape(note), phong_cell);
    }
    sections.push_back({{"lighting", kind}, {"rmse", d.rmse}, {"relative_mse", d.relative_mse}, {"max_error", d.max_abs_error},
                        {"luminance_ratio", d.mean_luminance_ratio}, {"ssim", std::isfinite(d.ssim) ? nlohmann::json(d.ssim) : nlohmann::json(nullptr)},
                        {"reference_spp", ref->stats.spp_done}, {"materials", materials}, {"flip", fl.mean},
                        {"flip_pixels_per_degree", fo.pixels_per_degree}, {"heat_scale", heat.scale}});
    const std::string id = "view-" + kind;
    body += fmt::format(
        "<section id=\"{0}\"><h2>{0}</h2>\n<table class=\"figures\"><tr><th>RMSE</th><th>relative MSE</th><th>max error</th>"
        "<th>luminance game/reference</th><th>SSIM</th><th>FLIP (mean)</th><th>reference spp</th></tr>\n<tr>{1}{2}{3}{4}{5}{6}"
        "<td data-json=\"{7}/reference_spp\" data-value=\"{8}\">{8}</td></tr></table>\n",
        kind, cell(d.rmse, ptr + "/rmse", ".4g"), cell(d.relative_mse, ptr + "/relative_mse", ".4g"),
        cell(d.max_abs_error, ptr + "/max_error", ".4g"), cell(d.mean_luminance_ratio, ptr + "/luminance_ratio", ".4f"),
        cell(d.ssim, ptr + "/ssim", ".4f"), cell(fl.mean, ptr + "/flip", ".4f"), ptr, ref->stats.spp_done);
    body += viewer_html(id, s.camera.width, s.camera.height,
                        {{kind + "_reference.png", "reference", "reference (path tracer)"},
                         {kind + "_game.png", "game", "game shading"},
                         {kind + "_heatmap.png", "heat", "relative error"},
                         {kind + "_flip.png", "flip", "FLIP"}},
                        colour_bar_html(heat.scale, "relative error max_c |game - ref| / sqrt(ref^2 + 0.01), white at the 99th percentile",
                                        ptr + "/heat_scale"),
                        colour_bar_html(1.0, "LDR-FLIP (Andersson et al. 2020) at 67 pixels per degree", ""));
    body += fmt::format(
        "<div data-viewer=\"{}\"><table><tr><th>material</th><th>model</th><th>specular ambient</th><th>pixels</th><th>RMSE</th>"
        "<th>relative MSE</th><th>FLIP</th><th>luminance game/ref</th><th>note</th>"
        "<th>luminance game/ref with the Phong chain (before 2026-12-07)</th></tr>\n{}</table></div></section>\n",
        id, rows);
  }
  bar.finish();
  nlohmann::json ibl_json;
  if (o.ibl_error) {
    // The IBL error map of the scene's environment (render/ibl_error.h): a ggx sphere lit by it alone, the
    // defaults of `shadelab ibl-error` but the reference's spp, which is the report's.
    IblErrorOptions io;
    io.spp = o.spp;
    io.threads = scene.settings.threads;
    const IblErrorMap map = unwrap(ibl_error_map(scene, "ggx", {}, io));
    const fs::path sub = dir / "ibl_error";
    IblErrorHeader header;
    header.input = scene.source + " (environment)";
    header.nv_bins = io.nv_bins;
    header.size = io.size;
    header.spp = io.spp;
    header.specular_size = io.game.specular_size;
    header.seed = io.seed;
    const nlohmann::json written = ibl_error_files(map, header, sub, files);
    const double ibl_scale = written["split_sum"]["heat_scale"].get<double>();
    // A figure in per cent: data-value holds the fraction as --json writes it (data-unit="percent").
    const auto pct = [](double v, const std::string& pointer) {
      return fmt::format("<span data-json=\"{}\" data-value=\"{}\" data-unit=\"percent\">{:.2f}%</span>", pointer, exact_number(v), 100.0 * v);
    };
    body += fmt::format(
        "<section id=\"ibl\"><h2>Image-based lighting: the shortcuts against the path tracer</h2>\n<p>A ggx sphere lit by this scene's "
        "environment alone, per roughness and N.V (<a href=\"ibl_error/index.html\">the whole map</a>). Split sum "
        "read along R: mean |error| {}, max {}, at N.V &lt; 0.3 {}; each part read at its lobe's moments: mean "
        "{}, max {}, at N.V &lt; 0.3 {}; SH9 irradiance on a white Lambert sphere: mean {}, max "
        "{}.</p>\n<div class=\"maps\"><figure><img src=\"ibl_error/split_sum_error.png\" alt=\"split sum |error|\"><figcaption>split sum |error| "
        "(rows: roughness, the smoothest at the top; columns: N.V from 0)</figcaption></figure><figure><img src=\"ibl_error/corrected_error.png\" "
        "alt=\"read per lobe\"><figcaption>read per lobe, the same scale</figcaption></figure></div>\n{}</section>\n",
        pct(map.split_sum_summary.mean_abs, "/ibl_error/split_sum/mean_abs_error"),
        pct(map.split_sum_summary.max_abs, "/ibl_error/split_sum/max_abs_error"),
        pct(map.split_sum_summary.grazing_mean_abs, "/ibl_error/split_sum/grazing_mean_abs_error"),
        pct(map.corrected_summary.mean_abs, "/ibl_error/corrected/mean_abs_error"),
        pct(map.corrected_summary.max_abs, "/ibl_error/corrected/max_abs_error"),
        pct(map.corrected_summary.grazing_mean_abs, "/ibl_error/corrected/grazing_mean_abs_error"),
        pct(map.sh_summary.mean_abs, "/ibl_error/sh/mean_abs_error"), pct(map.sh_summary.max_abs, "/ibl_error/sh/max_abs_error"),
        colour_bar_html(ibl_scale, "|(shortcut - reference) / reference| per cell, white at the split sum's largest (at least 0.01)",
                        "/ibl_error/heat_scale"));
    // The summaries as ibl_error.json holds them.
    ibl_json = {{"page", (sub / "index.html").string()}, {"split_sum", written["split_sum"]["summary"]},
                {"corrected", written["corrected"]["summary"]}, {"grazing_reduction", map.grazing_reduction},
                {"sh", written["sh"]["summary"]}, {"seconds", map.seconds}, {"heat_scale", ibl_scale}};
  }
  nlohmann::json page_data = {{"width", scene.camera.width}, {"height", scene.camera.height}, {"material_ids", run_lengths(ids)}};
  std::string page_json = page_data.dump();
  // Inside <script>, "</" would end the element early; JSON allows "<\/".
  for (std::size_t p = page_json.find("</"); p != std::string::npos; p = page_json.find("</", p + 2)) page_json.insert(p + 1, "\\");
  const std::string html = fmt::format(
      "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>shadelab report: {0}</title>\n<style>{2}</style></head><body>\n"
      "<h1>Game shading against the reference: {0}</h1>\n"
      "<p><b>punctual</b>: only punctual lights, direct light: the game shading equation (pi f c cos with c the game colour) should match the "
      "path tracer within its noise. <b>environment</b>: only the environment, direct light: SH9 diffuse and prefiltered specular against the exact "
      "integral. <b>full</b>: everything, the reference at full depth: adds interreflection and area lights, which game shading leaves out.</p>\n"
      "<p>Each viewer shows the game and reference images at full size and the same exposure (0 EV, the filmic curve of <code>render</code>): "
      "<b>swipe</b> (the game left of the line), <b>flip</b> (the button or key F alternates them), the relative <b>error heat map</b> and the "
      "<b>FLIP map</b> (LDR-FLIP, Andersson et al. 2020, 0 = no visible difference, 1 = the largest), each with its colour bar. Zoom keeps "
      "pixels square (nearest neighbour); drag to pan. Click a material's row to show its pixels.</p>\n"
      "<p><b>wrapped diffuse</b>: the SH wrap factors 1, (2-w)/3, (1-w)^2/4 are the bands of (cos+w)/(pi (1+w)^2) over every direction with "
      "cos &gt; -w; the BRDF is 0 below the horizon, so under a uniform environment game shading gives kd and the reference kd (1+2w)/(1+w)^2 "
      "(0.889 kd at w = 0.5). Wrapped materials show the expected ratio beside the measured one.</p>\n{1}"
      "<script type=\"application/json\" id=\"report-data\">{3}</script>\n<script>{4}</script>\n</body></html>\n",
      xml_escape(scene.source), body, report_page_css(), page_json, report_page_script());
  files.emplace_back(dir / "index.html", std::vector<char>(html.begin(), html.end()));
  fs::create_directories(o.ibl_error ? dir / "ibl_error" : dir, ec);
  if (ec) throw UsageError("--out: cannot create the folder '" + o.out + "': " + ec.message());
  unwrap(write_files_atomically(files));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (o.json) {
    nlohmann::json j = {{"scene", scene.source}, {"report", (dir / "index.html").string()}, {"sections", sections},
                        {"nonfinite_samples", nonfinite}, {"seconds", seconds}};
    if (o.ibl_error) j["ibl_error"] = ibl_json;
    print_json(j);
  } else {
    for (const auto& s : sections) {
      fmt::print("{:<12} RMSE {:.4g}  relative MSE {:.4g}  luminance game/ref {:.4f}\n", s["lighting"].get<std::string>(),
                 s["rmse"].get<double>(), s["relative_mse"].get<double>(), s["luminance_ratio"].get<double>());
    }
    for (const auto& line : wrap_lines) fmt::print("wrapped diffuse: {}\n", line);
    if (o.ibl_error) {
      fmt::print("ibl error: split sum mean |error| {:.2f}%, read per lobe {:.2f}%; SH9 {:.2f}% ({})\n",
                 100.0 * ibl_json["split_sum"]["mean_abs_error"].get<double>(),
                 100.0 * ibl_json["corrected"]["mean_abs_error"].get<double>(),
                 100.0 * ibl_json["sh"]["mean_abs_error"].get<double>(), ibl_json["page"].get<std::string>());
    }
    fmt::print("wrote {}\n", (dir / "index.html").string());
  }
  if (nonfinite > 0) {
    std::fflush(stdout);
    std::cerr << "shadelab: " << scene.source << ": " << nonfinite
              << " samples were NaN or infinite (kept in the images); the report is wrong\n";
    std::exit(1);
  }
}

void add_report_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<ReportOptions>();
  auto* sub = app.add_subcommand("report", "game shading against the reference, per lighting and material, as an HTML page");
  sub->add_option("SCENE", o->scene, "scene file (default: the built-in scene)");
  sub->add_option("--out", o->out, "output folder (index.html and images)")->capture_default_str();
  sub->add_option("--spp", o->spp, "reference samples per pixel")->capture_default_str();
  sub->add_option("--width", o->width, "render width (the height follows the camera's aspect)");
  sub->add_flag("--ibl-error", o->ibl_error, "add the IBL error map of the scene's environment (shadelab ibl-error's "
                                            "defaults at --spp) as ibl_error/ and a section");
  sub->add_flag("--json", o->json, "machine-readable summary");
  sub->add_option("--exposure", o->exposure, "exposure of the game and reference PNGs, in stops")->capture_default_str();
  add_view_options(sub, o->view, "filmic", false);
  sub->callback([o, &command] { command.run = [o] { run_report(*o); }; });
}

}  // namespace

const CommandRegistration registration_report(100, add_report_command);

}  // namespace shadelab::cli
