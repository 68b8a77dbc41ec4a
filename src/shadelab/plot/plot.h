// shadelab plots: line charts and in-plane polar (lobe) charts, drawn with Cairo to SVG or PNG in memory.
// A general charting layer; it knows nothing about BRDFs (the CLI turns BRDF data into Series).
//
// Contract (details and reasons in docs/plots.md):
// - Value types in, bytes out: render_plot returns the whole SVG or PNG file; write_plot picks the format
//   from the extension (.svg or .png, case-insensitive) and writes atomically (write_file_atomically).
// - Deterministic: the same plot, size and format give the same bytes, call after call, on the same
//   machine (same Cairo and fonts). Cairo's SVG has no timestamp; its one per-process counter (the
//   id="surfaceN" of the root group) is renumbered from 1.
// - Text: DejaVu Sans through fontconfig; sizes for 800 x 600 scaled by sqrt(width / 800 * height / 600)
//   (at most 1.5 times the smaller ratio), clamped to [0.5, 4].
//   Strings must be valid UTF-8. In SVG, Cairo draws text as glyph outlines; the title, axis labels, series
//   labels and reference-line labels are also written as <title> and <desc> text for search and screen readers.
// - Colours are linear RGB (shadelab's convention), encoded to sRGB for drawing. A series without a colour
//   takes palette colour i (plot_palette), the Okabe-Ito colour-blind-safe set; after 8 series the
//   palette repeats and the repeats are drawn dashed.
// - Data: a series needs at least one point and as many y as x values. NaN (in x or y) is a gap: it ends the
//   line, which starts again at the next point. +-Inf is an Error. On a log axis, values <= 0 are not drawn
//   and break the line like NaN. Points outside an axis range set by the caller are clipped at the frame.
// - Polar plots: series x is the angle from the normal in radians (positive to the right, 0 straight up),
//   y the radius (>= 0; negative is an Error). The chart is the upper half-disc, -90..+90 degrees; what
//   falls outside it is clipped. log_radius draws radius log10(y / top) + log_floor_decades, clamped at 0,
//   where top is the decade at or above the largest y (or radius_max): values of 0 sit at the centre.
// - Errors (one line, naming the plot title and the series or field): empty or mismatched series, Inf,
//   negative polar radius, no plottable point, bad axis range (non-finite, min >= max, <= 0 on a log
//   axis), bad line width, width or height outside [64, 8192], unknown extension, Cairo failure. Nothing
//   throws, nothing prints. Different plots may be rendered from different threads at once.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "shadelab/color/rgb.h"
#include "shadelab/core/error.h"

namespace shadelab {

struct Series {
  std::string label;  // shown in the legend; empty: not in the legend
  std::vector<double> x;
  std::vector<double> y;
  std::optional<Rgb> colour;  // linear RGB; none: plot_palette(index of the series)
  double width = 1.5;         // line width in pixels at 800 x 600 (scaled with the text), in (0, 50]
  bool dashed = false;
};

struct Axis {
  std::string label;  // with units, e.g. "incidence angle (degrees)"
  std::optional<double> min;  // none: from the data, widened to a tick
  std::optional<double> max;
  bool log = false;  // log10 scale; the range must be > 0
};

// A horizontal reference line across the whole chart, e.g. y = 1 "energy conservation".
struct HorizontalLine {
  double y = 0.0;
  std::string label;  // drawn above the line at the right end; may be empty
  std::optional<Rgb> colour;  // none: dark grey
  bool dashed = true;
};

struct LinePlot {
  std::string title;
  Axis x;
  Axis y;
  std::vector<Series> series;
  std::vector<HorizontalLine> lines;  // their y is included in the automatic y range
  bool legend = true;  // placed in the corner of the chart that covers the fewest data points
};

// A marked direction on a polar plot, e.g. the incident or the mirror direction.
struct PolarRay {
  double angle = 0.0;  // radians from the normal, positive to the right
  std::string label;   // drawn near the end of the ray; may be empty
};

struct PolarPlot {
  std::string title;
  std::vector<Series> series;  // x: angle from the normal in radians, y: radius
  bool log_radius = false;
  double log_floor_decades = 4.0;  // log_radius: decades shown below the top decade, in (0, 30]
  std::optional<double> radius_max;  // none: from the data (linear: widened to a tick; log: to a decade)
  std::string radius_label;  // what the radius is, with units, e.g. "f_r cos (1/sr)"
  std::vector<PolarRay> rays;
  bool legend = true;  // top right, outside the half-disc
};

enum class PlotFormat { svg, png };

inline constexpr int plot_min_size = 64;
inline constexpr int plot_max_size = 8192;
inline constexpr std::size_t plot_palette_size = 8;

// Palette colour i (mod plot_palette_size), linear RGB: Okabe & Ito's colour-blind-safe set ordered blue,
// vermillion, bluish green, reddish purple, orange, sky blue, black, yellow.
Rgb plot_palette(std::size_t index);

Result<std::vector<char>> render_plot(const LinePlot& plot, PlotFormat format, int width = 800, int height = 600);
Result<std::vector<char>> render_plot(const PolarPlot& plot, PlotFormat format, int width = 800, int height = 600);

// The format from the extension of `path` (.svg or .png, any case); an Error names the path otherwise.
Result<PlotFormat> plot_format_from_path(const std::filesystem::path& path);

// Renders and writes atomically. Returns true or an Error naming the path.
Result<bool> write_plot(const LinePlot& plot, const std::filesystem::path& path, int width = 800, int height = 600);
Result<bool> write_plot(const PolarPlot& plot, const std::filesystem::path& path, int width = 800, int height = 600);

}  // namespace shadelab
