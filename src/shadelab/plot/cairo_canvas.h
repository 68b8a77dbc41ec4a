// shadelab plot internals: a thin drawing layer over one Cairo context, shared by the line and the polar
// chart, and the one place that creates Cairo surfaces (SVG or PNG, written to memory).
//
// Contract: internal to the plot module (includes cairo.h, whose include path is private to the
// shadelab_plot target); nothing outside src/shadelab/plot includes it. Coordinates are pixels, origin top
// left, y down. Strings are UTF-8 (plot.cpp validates them before drawing). Drawing never fails halfway
// with an exception; a Cairo error is reported once, by render_with_cairo.
#pragma once

#include <cairo.h>

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "shadelab/color/rgb.h"
#include "shadelab/core/error.h"
#include "shadelab/plot/plot.h"

namespace shadelab::plot_detail {

struct Point {
  double x = 0.0;
  double y = 0.0;
};

struct Rect {
  double x0 = 0.0;
  double y0 = 0.0;
  double x1 = 0.0;
  double y1 = 0.0;

  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  bool intersects(const Rect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  bool contains(const Point& p) const { return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1; }
  Rect grown(double d) const { return {x0 - d, y0 - d, x1 + d, y1 + d}; }
};

enum class HAlign { left, centre, right };
enum class VAlign { top, centre, baseline, bottom };

// Colours of the chart furniture (linear RGB; sRGB-encoded 0.03 is 0.19, 0.7 is 0.85).
inline constexpr Rgb ink{0.0, 0.0, 0.0};                   // text
inline constexpr Rgb frame_grey{0.03, 0.03, 0.03};         // frame, ticks, horizon
inline constexpr Rgb grid_grey{0.70, 0.70, 0.70};          // major grid
inline constexpr Rgb minor_grid_grey{0.85, 0.85, 0.85};    // minor grid
inline constexpr Rgb reference_grey{0.06, 0.06, 0.06};     // reference lines and rays
inline constexpr Rgb white{1.0, 1.0, 1.0};

// Font and spacing sizes for one image size: the 800 x 600 values times scale().
struct Metrics {
  double scale = 1.0;
  double title = 18.0;
  double label = 14.0;
  double tick = 12.0;
  double legend = 12.5;
  double pad = 12.0;
  double tick_length = 5.0;
};

Metrics metrics_for(int width, int height);

class Canvas {
 public:
  Canvas(cairo_t* cr, int width, int height);

  int width() const { return m_width; }
  int height() const { return m_height; }
  const Metrics& metrics() const { return m_metrics; }
  cairo_t* cr() const { return m_cr; }

  void set_colour(const Rgb& linear, double alpha = 1.0);
  void set_font(double size, bool bold = false);
  double font_size() const { return m_font_size; }
  // Height of a capital letter of the current font (DejaVu Sans: 0.729 em), used to centre text vertically.
  double cap_height() const { return 0.729 * m_font_size; }

  // Text in the current font, as given. Alignment is of the text's advance box and its cap height.
  double text_width(std::string_view text) const { return width_of(text, false); }
  void text(std::string_view text, double x, double y, HAlign h, VAlign v) { draw(text, false, x, y, h, v); }
  // A number label (ticks.h): "a^b" draws b as a superscript (10^-3, 2×10^6), and a '-' that starts the
  // label or its superscript is typeset as U+2212.
  double number_width(std::string_view label) const { return width_of(label, true); }
  void number(std::string_view label, double x, double y, HAlign h, VAlign v) { draw(label, true, x, y, h, v); }
  // Centred on (x, y), rotated by `angle` radians (y axis label: -pi/2).
  void text_rotated(std::string_view text, double x, double y, double angle);

  void line(Point a, Point b, double width, const Rgb& colour, bool dashed = false);
  // A straight line snapped so that a 1-pixel line covers whole pixels in PNG.
  double snap(double coordinate, double line_width) const;

  // A polyline in pixels; a non-finite point is a gap. Segments are clipped to `bounds` in double precision
  // before Cairo sees them (Cairo's fixed point would wrap far-away coordinates); the caller sets the exact
  // clip. A point with gaps (or ends) on both sides is drawn as a dot.
  void polyline(const std::vector<Point>& points, const Rect& bounds, double width, const Rgb& colour, bool dashed);

  void fill_rect(const Rect& r, const Rgb& colour, double alpha = 1.0);
  void stroke_rect(const Rect& r, double width, const Rgb& colour);

 private:
  double width_of(std::string_view text, bool number) const;
  void draw(std::string_view text, bool number, double x, double y, HAlign h, VAlign v);
  void set_dash(bool dashed, double width);

  cairo_t* m_cr;
  int m_width;
  int m_height;
  Metrics m_metrics;
  double m_font_size = 12.0;
};

// Height of the title block (cap height + descent of the title font, and a gap); 0 without a title.
double title_block(const Metrics& m, const std::string& title);
// The title, bold, centred at the top; shrunk (down to 60%) when wider than the image.
void draw_title(Canvas& canvas, const std::string& title);

// The legend: a white box with one row per entry (a line sample and its label).
struct LegendEntry {
  std::string label;
  Rgb colour;
  double width = 1.5;
  bool dashed = false;
};

struct LegendBox {
  double width = 0.0;
  double height = 0.0;
};

LegendBox legend_size(Canvas& canvas, const std::vector<LegendEntry>& entries);
void draw_legend(Canvas& canvas, const std::vector<LegendEntry>& entries, double x, double y);

// The colour, dash and legend entries of series as drawn (palette, and dashes for palette repeats).
Rgb series_colour(const Series& series, std::size_t index);
bool series_dashed(const Series& series, std::size_t index);
std::vector<LegendEntry> legend_entries(const std::vector<Series>& series);

// Creates a Cairo surface of the format and size, calls draw, and returns the file. For SVG, `svg_title`
// and `svg_desc` become the document's <title> and <desc> (XML-escaped), and Cairo's per-process surface
// ids are renumbered so that the bytes depend only on the drawing.
Result<std::vector<char>> render_with_cairo(PlotFormat format, int width, int height,
                                            const std::function<void(Canvas&)>& draw, const std::string& svg_title,
                                            const std::string& svg_desc);

}  // namespace shadelab::plot_detail
