// shadelab plots: the palette, input checks, choosing the format from a path, atomic writes (see plot.h).
// The two charts are drawn in line_plot.cpp and polar_plot.cpp.
#include "shadelab/plot/plot.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <system_error>

#include "shadelab/image/image_io.h"
#include "shadelab/image/srgb.h"
#include "shadelab/plot/plot_internal.h"

namespace shadelab {

Rgb plot_palette(std::size_t index) {
  // Okabe & Ito (2008), "Color Universal Design": distinguishable with every common colour-vision
  // deficiency and, with the dashes of repeats, in greyscale print. 8-bit sRGB codes.
  static constexpr std::array<std::array<int, 3>, plot_palette_size> srgb{{
      {0, 114, 178},    // blue
      {213, 94, 0},     // vermillion
      {0, 158, 115},    // bluish green
      {204, 121, 167},  // reddish purple
      {230, 159, 0},    // orange
      {86, 180, 233},   // sky blue
      {0, 0, 0},        // black
      {240, 228, 66},   // yellow (last: weak on white)
  }};
  const auto& c = srgb[index % plot_palette_size];
  return {srgb_to_linear(c[0] / 255.0), srgb_to_linear(c[1] / 255.0), srgb_to_linear(c[2] / 255.0)};
}

Result<PlotFormat> plot_format_from_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".svg") {
    return PlotFormat::svg;
  }
  if (ext == ".png") {
    return PlotFormat::png;
  }
  return make_error("plot file '" + path.string() + "': unknown extension '" + path.extension().string() +
                    "' (use .svg or .png)");
}

namespace {

template <typename Plot>
Result<bool> write_any(const Plot& plot, const std::filesystem::path& path, int width, int height) {
  const Result<PlotFormat> format = plot_format_from_path(path);
  if (!format) {
    return format.error();
  }
  Result<std::vector<char>> bytes = render_plot(plot, *format, width, height);
  if (!bytes) {
    return bytes.error();
  }
  return write_file_atomically(path, *bytes);
}

}  // namespace

Result<bool> write_plot(const LinePlot& plot, const std::filesystem::path& path, int width, int height) {
  return write_any(plot, path, width, height);
}

Result<bool> write_plot(const PolarPlot& plot, const std::filesystem::path& path, int width, int height) {
  return write_any(plot, path, width, height);
}

namespace plot_detail {

bool is_valid_utf8(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t n = 0;
    std::uint32_t cp = 0;
    if (c < 0x80) {
      ++i;
      continue;
    }
    if ((c & 0xE0) == 0xC0) {
      n = 1;
      cp = c & 0x1Fu;
    } else if ((c & 0xF0) == 0xE0) {
      n = 2;
      cp = c & 0x0Fu;
    } else if ((c & 0xF8) == 0xF0) {
      n = 3;
      cp = c & 0x07u;
    } else {
      return false;
    }
    if (i + n >= text.size()) {
      return false;
    }
    for (std::size_t k = 1; k <= n; ++k) {
      const auto cc = static_cast<unsigned char>(text[i + k]);
      if ((cc & 0xC0) != 0x80) {
        return false;
      }
      cp = (cp << 6) | (cc & 0x3Fu);
    }
    static constexpr std::array<std::uint32_t, 4> min_code{0, 0x80, 0x800, 0x10000};
    if (cp < min_code[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
      return false;  // overlong, beyond Unicode, or a surrogate
    }
    i += n + 1;
  }
  return true;
}

std::string plot_name(std::string_view kind, const std::string& title) {
  std::string name(kind);
  if (!title.empty()) {
    name += " '" + title + "'";
  }
  return name;
}

Result<bool> check_size(const std::string& name, int width, int height) {
  const auto bad = [](int v) { return v < plot_min_size || v > plot_max_size; };
  if (bad(width) || bad(height)) {
    return make_error(name + ": size " + std::to_string(width) + " x " + std::to_string(height) +
                      " is out of range [" + std::to_string(plot_min_size) + ", " + std::to_string(plot_max_size) +
                      "] pixels");
  }
  return true;
}

Result<bool> check_text(const std::string& name, std::string_view field, const std::string& text) {
  if (!is_valid_utf8(text)) {
    return make_error(name + ": " + std::string(field) + " is not valid UTF-8");
  }
  return true;
}

std::string number(double v) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return result.ec == std::errc() ? std::string(buffer.data(), result.ptr) : std::string("?");
}

std::string series_name(const Series& series, std::size_t index) {
  std::string s = "series " + std::to_string(index + 1);
  if (!series.label.empty()) {
    s += " '" + series.label + "'";
  }
  return s;
}

Result<bool> check_series(const std::string& name, const std::vector<Series>& series) {
  if (series.empty()) {
    return make_error(name + ": no series to draw");
  }
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    const std::string where = name + ": " + series_name(s, i);
    if (!is_valid_utf8(s.label)) {
      return make_error(name + ": the label of series " + std::to_string(i + 1) + " is not valid UTF-8");
    }
    if (s.x.size() != s.y.size()) {
      return make_error(where + " has " + std::to_string(s.x.size()) + " x values but " +
                        std::to_string(s.y.size()) + " y values");
    }
    if (s.x.empty()) {
      return make_error(where + " has no points");
    }
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (std::isinf(s.x[k]) || std::isinf(s.y[k])) {
        return make_error(where + ": point " + std::to_string(k) + " is infinite (" + (std::isinf(s.x[k]) ? "x" : "y") +
                          "); use NaN for a gap");
      }
    }
    if (!std::isfinite(s.width) || !(s.width > 0.0) || s.width > 50.0) {
      return make_error(where + ": line width " + number(s.width) + " is out of range (0, 50]");
    }
    if (s.colour && !is_finite(*s.colour)) {
      return make_error(where + ": colour is not finite");
    }
  }
  return true;
}

}  // namespace plot_detail
}  // namespace shadelab
