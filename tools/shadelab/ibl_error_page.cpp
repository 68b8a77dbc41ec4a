// The files of an IBL error map (ibl_error_page.h).
#include "ibl_error_page.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cli_common.h"
#include "report_page.h"
#include "shadelab/core/text.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/metrics.h"
#include "shadelab/plot/plot.h"

namespace shadelab::cli {

namespace {

constexpr int cell_pixels = 24;
// A cell with no signal on the heat maps: dark blue, outside the heat ramp (black, red, yellow, white), so
// it cannot read as a small error; a cell with no pixels stays grey.
const Rgb no_signal_colour{0.05, 0.1, 0.45};

nlohmann::json cells_json(const IblErrorRow& row) {
  nlohmann::json cells = nlohmann::json::array();
  for (const IblErrorCell& c : row.cells) {
    cells.push_back({{"nv_lo", c.nv_lo}, {"nv_hi", c.nv_hi}, {"pixels", c.pixels}, {"shortcut", c.shortcut},
                     {"reference", c.reference}, {"reference_standard_error", c.reference_standard_error},
                     {"error", c.no_signal ? nlohmann::json(nullptr) : nlohmann::json(c.error)},
                     {"no_signal", c.no_signal}});
  }
  return cells;
}

nlohmann::json summary_json(const IblErrorSummary& s) {
  return {{"mean_abs_error", s.mean_abs}, {"max_abs_error", s.max_abs}, {"grazing_mean_abs_error", s.grazing_mean_abs},
          {"no_signal_cells", s.no_signal_cells}};
}

// |error| of each cell through the heat ramp, white at `scale`.
Image heat_grid(const std::vector<IblErrorRow>& rows, double scale) {
  const int cols = rows.empty() ? 1 : static_cast<int>(rows.front().cells.size());
  Image img(cols * cell_pixels, static_cast<int>(rows.size()) * cell_pixels);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (int k = 0; k < cols; ++k) {
      const IblErrorCell& c = rows[i].cells[static_cast<std::size_t>(k)];
      const Rgb colour = c.pixels == 0 ? Rgb::gray(0.2) : c.no_signal ? no_signal_colour : heat_ramp(std::abs(c.error) / scale);
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
      s.y.push_back(c.pixels > 0 && !c.no_signal ? c.error : std::nan(""));
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

std::string html_page(const IblErrorMap& map, const std::string& input, double scale) {
  std::ostringstream h;
  const auto pct = [](double v) { return fmt::format("{:+.2f}%", 100.0 * v); };
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>shadelab ibl-error: "
    << xml_escape(std::filesystem::path(input).filename().string()) << "</title>\n"
    << "<style>" << report_page_css() << "</style></head><body>\n"
    << "<h1>Image-based lighting: the shortcuts against the path tracer</h1>\n<p>Environment <code>"
    << xml_escape(input) << "</code>, model <code>" << xml_escape(map.model)
    << "</code>. A unit sphere lit by the environment alone; each cell is (shortcut - reference) / reference of "
       "the mean luminance over the pixels of that N.V bin (docs/envmap.md).</p>\n";
  const auto table = [&](const std::vector<IblErrorRow>& rows, const std::string& first) {
    h << "<table><tr><th>" << first << "</th>";
    for (const IblErrorCell& c : rows.front().cells) h << fmt::format("<th>N.V {:.3g}-{:.3g}</th>", c.nv_lo, c.nv_hi);
    h << "</tr>\n";
    for (const IblErrorRow& row : rows) {
      h << "<tr><th>" << (first == "roughness" ? fmt::format("{:.3g}", row.roughness) : std::string("Lambert")) << "</th>";
      for (const IblErrorCell& c : row.cells) {
        h << "<td>" << (c.pixels == 0 ? std::string("-") : c.no_signal ? std::string("no signal") : pct(c.error)) << "</td>";
      }
      h << "</tr>\n";
    }
    h << "</table>\n";
  };
  const auto summary = [&](const IblErrorSummary& s) {
    h << fmt::format("<p>mean |error| {:.2f}%, max {:.2f}%, mean at N.V &lt; 0.3 {:.2f}%", 100.0 * s.mean_abs,
                     100.0 * s.max_abs, 100.0 * s.grazing_mean_abs);
    if (s.no_signal_cells > 0) {
      h << fmt::format(" (over {} cells; {} cells with no signal, dark blue on the maps, are left out: their "
                       "reference is 0 or below 1e-6 of the map's mean)", s.signal_cells, s.no_signal_cells);
    }
    h << "</p>\n";
  };
  h << "<h2>Split sum (prefiltered GGX chain x DFG table)</h2>\n";
  table(map.split_sum, "roughness");
  summary(map.split_sum_summary);
  h << fmt::format("<div class=\"maps\"><figure><img src=\"split_sum_error.png\" alt=\"|error| per cell, white at {:.3g}\">"
                   "<figcaption>|error| per cell (rows: roughness, top the smoothest; columns: N.V from 0), white at {:.3g}"
                   "</figcaption></figure></div>\n", scale, scale)
    << colour_bar_html(scale, "|(shortcut - reference) / reference| per cell", "/split_sum/heat_scale");
  if (map.correction == GameSplitSumLookup::lobes) {
    h << "<h2>Split sum read per part at its lobe's first moments</h2>\n"
         "<p>The same chain and table (the same storage), read twice: f0 A along the mean direction of the A lobe "
         "and at the chain roughness of the same spread, f90 B likewise for the B (Fresnel) lobe "
         "(envmap/specular/split_sum_lobes.h, kernels/game_ambient.sl game_split_sum_lobe_direction).</p>\n";
  } else if (map.correction == GameSplitSumLookup::filtered) {
    h << fmt::format("<h2>Split sum with each part filtered over its own lobe ({} taps)</h2>\n"
                     "<p>The same chain and table (the same storage), read at {} taps drawn from the visible normals "
                     "of the true lobe, each with the footprint of its share of solid angle (filtered importance "
                     "sampling); f0 A and f90 B each the weighted mean of its own lobe's taps "
                     "(envmap/specular/split_sum_taps.h).</p>\n", map.taps, map.taps);
  } else {
    h << "<h2>Split sum read along the dominant direction normalize(mix(R, n, &alpha;<sup>2</sup>))</h2>\n"
         "<p>The same chain and table (the same storage), looked up toward the normal as the lobe leans at oblique "
         "view (kernels/game_ambient.sl game_split_sum_lookup).</p>\n";
  }
  table(map.corrected, "roughness");
  summary(map.corrected_summary);
  h << fmt::format("<p>At N.V &lt; 0.3 the mean |error| falls by {:.1f}% of the uncorrected split sum's.</p>\n",
                   100.0 * map.grazing_reduction);
  h << fmt::format("<div class=\"maps\"><figure><img src=\"corrected_error.png\" alt=\"|error| per cell, white at {:.3g}\">"
                   "<figcaption>the same scale</figcaption></figure></div>\n", scale)
    << colour_bar_html(scale, "|(shortcut - reference) / reference| per cell", "/split_sum/heat_scale");
  h << "<h2>SH9 irradiance (white Lambert sphere)</h2>\n";
  table({map.sh}, "");
  summary(map.sh_summary);
  h << "<p><img src=\"split_sum_error.svg\" alt=\"signed error against N.V\" width=\"800\"></p>\n</body></html>\n";
  return h.str();
}

}  // namespace

std::vector<std::string> ibl_error_file_names() {
  return {"ibl_error.json", "split_sum_error.png", "split_sum_error.svg", "index.html", "corrected_error.png"};
}

nlohmann::json ibl_error_files(const IblErrorMap& map, const IblErrorHeader& h, const std::filesystem::path& dir,
                               std::vector<std::pair<std::filesystem::path, std::vector<char>>>& out) {
  const double scale = std::max(0.01, map.split_sum_summary.max_abs);
  nlohmann::json rows = nlohmann::json::array();
  for (const IblErrorRow& row : map.split_sum) rows.push_back({{"roughness", row.roughness}, {"cells", cells_json(row)}});
  nlohmann::json corrected_rows = nlohmann::json::array();
  for (const IblErrorRow& row : map.corrected) {
    corrected_rows.push_back({{"roughness", row.roughness}, {"cells", cells_json(row)}});
  }
  nlohmann::json pj = nlohmann::json::object();
  for (const auto& [k, v] : h.params) pj[k] = v;
  nlohmann::json files = nlohmann::json::array();
  const std::vector<std::string> names = ibl_error_file_names();
  for (const auto& n : names) files.push_back((dir / n).string());
  const nlohmann::json j = {
      {"input", h.input}, {"model", map.model}, {"params", pj}, {"nv_bins", h.nv_bins}, {"size", h.size}, {"spp", h.spp},
      {"seed", h.seed}, {"specular_size", h.specular_size}, {"error", "(shortcut - reference) / reference of the mean luminance of a bin's pixels"},
      {"split_sum", {{"rows", rows}, {"summary", summary_json(map.split_sum_summary)}, {"heat_scale", scale}}},
      {"corrected", {{"direction", split_sum_correction_text(map.correction)}, {"taps", map.taps},
                     {"rows", corrected_rows}, {"summary", summary_json(map.corrected_summary)},
                     {"grazing_reduction", map.grazing_reduction}}},
      {"sh", {{"cells", cells_json(map.sh)}, {"summary", summary_json(map.sh_summary)}}},
      {"outputs", files}, {"seconds", map.seconds}};
  out.emplace_back(dir / names[0], json_file_bytes(j));
  out.emplace_back(dir / names[1], unwrap(encode_image(heat_grid(map.split_sum, scale), dir / names[1])));
  out.emplace_back(dir / names[2], unwrap(render_plot(error_plot(map, h.input), PlotFormat::svg)));
  const std::string page = html_page(map, h.input, scale);
  out.emplace_back(dir / names[3], std::vector<char>(page.begin(), page.end()));
  out.emplace_back(dir / names[4], unwrap(encode_image(heat_grid(map.corrected, scale), dir / names[4])));
  return j;
}

nlohmann::json write_ibl_error_files(const IblErrorMap& map, const IblErrorHeader& h, const std::filesystem::path& dir) {
  std::vector<std::pair<std::filesystem::path, std::vector<char>>> files;
  nlohmann::json j = ibl_error_files(map, h, dir, files);
  unwrap(write_files_atomically(files));  // one output set (issue 40, finding 7)
  return j;
}

}  // namespace shadelab::cli
