// shadelab plots: the line chart (contract in plot.h).
//
// Layout, from the outside in: the title on top; the y axis label (rotated) and the y tick labels on the
// left; the x tick labels and the x axis label below; the frame with grid lines at the ticks inside. The
// margins are measured from the text, so long tick labels push the frame in rather than being clipped.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "shadelab/core/constants.h"
#include "shadelab/plot/cairo_canvas.h"
#include "shadelab/plot/plot.h"
#include "shadelab/plot/plot_internal.h"
#include "shadelab/plot/ticks.h"

namespace shadelab {
namespace {

using plot_detail::Canvas;
using plot_detail::HAlign;
using plot_detail::Point;
using plot_detail::Rect;
using plot_detail::VAlign;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

bool plottable(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }

// An axis range before tick expansion: which ends the caller fixed, which came from the data.
struct Range {
  double lo = 0.0;
  double hi = 1.0;
  bool expand_lo = true;
  bool expand_hi = true;
};

Result<Range> axis_range(const std::string& name, const std::string& which, const Axis& axis,
                         const std::vector<double>& values, bool any_log) {
  const std::string where = name + ": " + which + " axis";
  for (const auto& [end, value] : {std::pair{"min", axis.min}, std::pair{"max", axis.max}}) {
    if (!value) {
      continue;
    }
    if (!std::isfinite(*value)) {
      return make_error(where + " " + end + " is not finite");
    }
    if (axis.log && !(*value > 0.0)) {
      return make_error(where + " " + end + " = " + plot_detail::number(*value) + " is not > 0 on a log axis");
    }
  }
  if (axis.min && axis.max && !(*axis.min < *axis.max)) {
    return make_error(where + ": min " + plot_detail::number(*axis.min) + " is not below max " +
                      plot_detail::number(*axis.max));
  }
  Range r;
  r.expand_lo = !axis.min;
  r.expand_hi = !axis.max;
  if ((r.expand_lo || r.expand_hi) && values.empty()) {
    return make_error(where + ": no data point can be drawn (each has a NaN coordinate" +
                      std::string(any_log ? ", or one <= 0 on a log axis" : "") +
                      "); set the axis min and max to draw an empty chart");
  }
  const auto [data_lo, data_hi] = values.empty() ? std::pair{1.0, 1.0} : [&] {
    const auto mm = std::minmax_element(values.begin(), values.end());
    return std::pair{*mm.first, *mm.second};
  }();
  r.lo = axis.min ? *axis.min : data_lo;
  r.hi = axis.max ? *axis.max : data_hi;
  if (!(r.lo < r.hi)) {
    // A single value (or data beyond a fixed end): widen the automatic end(s) by a decade or by 10%.
    if (axis.log) {
      r.lo = r.expand_lo ? (r.expand_hi ? r.lo / 10.0 : r.hi / 10.0) : r.lo;
      r.hi = r.expand_hi ? (r.expand_lo ? r.hi * 10.0 : r.lo * 10.0) : r.hi;
    } else {
      const double anchor = r.expand_lo ? r.hi : r.lo;
      const double d = anchor == 0.0 ? 1.0 : 0.1 * std::abs(anchor);
      if (r.expand_lo && r.expand_hi) {
        r.lo = anchor - d;
        r.hi = anchor + d;
      } else if (r.expand_lo) {
        r.lo = r.hi - d;
      } else {
        r.hi = r.lo + d;
      }
    }
  }
  if (!(r.lo < r.hi) || !std::isfinite(r.hi - r.lo) || (!axis.log && r.hi - r.lo < 1e-300)) {
    return make_error(where + ": cannot make a range from " + plot_detail::number(r.lo) + " to " +
                      plot_detail::number(r.hi));
  }
  return r;
}

// Value -> pixel along one axis. NaN for values a log axis cannot show. Far-away values are held at 1e12
// axis lengths, which keeps the direction of a clipped segment exact to well below a pixel.
struct Scale {
  double min = 0.0;
  double max = 1.0;
  bool log = false;
  double p0 = 0.0;  // pixel of min
  double p1 = 1.0;  // pixel of max

  double operator()(double v) const {
    double t = 0.0;
    if (log) {
      if (!(v > 0.0)) {
        return nan;
      }
      t = (std::log10(v) - std::log10(min)) / (std::log10(max) - std::log10(min));
    } else {
      t = (v - min) / (max - min);
    }
    if (std::isnan(t)) {
      return nan;
    }
    return p0 + std::clamp(t, -1e12, 1e12) * (p1 - p0);
  }
};

TickSet make_ticks(const Range& r, bool log, int max_count) {
  return log ? log_ticks(r.lo, r.hi, max_count, r.expand_lo, r.expand_hi)
             : linear_ticks(r.lo, r.hi, max_count, r.expand_lo, r.expand_hi);
}

double widest_label(Canvas& canvas, const TickSet& ticks, int* labelled = nullptr) {
  double w = 0.0;
  int n = 0;
  for (const Tick& t : ticks.ticks) {
    if (!t.minor) {
      w = std::max(w, canvas.number_width(t.label));
      ++n;
    }
  }
  if (labelled != nullptr) {
    *labelled = n;
  }
  return w;
}

// Samples of everything drawn inside the frame (points and every few pixels along segments), to find the
// legend corner that hides the least.
std::vector<Point> coverage_samples(const std::vector<std::vector<Point>>& lines, double spacing) {
  std::vector<Point> out;
  for (const auto& line : lines) {
    for (std::size_t i = 0; i < line.size(); ++i) {
      const Point& b = line[i];
      if (!std::isfinite(b.x) || !std::isfinite(b.y)) {
        continue;
      }
      out.push_back(b);
      if (i == 0 || !std::isfinite(line[i - 1].x) || !std::isfinite(line[i - 1].y)) {
        continue;
      }
      const Point& a = line[i - 1];
      const double length = std::hypot(b.x - a.x, b.y - a.y);
      const int steps = static_cast<int>(std::min(1000.0, length / spacing));
      for (int k = 1; k < steps; ++k) {
        const double t = k / static_cast<double>(steps);
        out.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
      }
    }
  }
  return out;
}

}  // namespace

Result<std::vector<char>> render_plot(const LinePlot& plot, PlotFormat format, int width, int height) {
  using namespace plot_detail;
  const std::string name = plot_name("line plot", plot.title);
  for (const Result<bool>& check :
       {check_size(name, width, height), check_text(name, "title", plot.title),
        check_text(name, "x axis label", plot.x.label), check_text(name, "y axis label", plot.y.label),
        check_series(name, plot.series)}) {
    if (!check) {
      return check.error();
    }
  }
  for (std::size_t i = 0; i < plot.lines.size(); ++i) {
    const HorizontalLine& line = plot.lines[i];
    const std::string which = "reference line " + std::to_string(i + 1);
    if (!std::isfinite(line.y)) {
      return make_error(name + ": " + which + " y is not finite");
    }
    if (line.colour && !is_finite(*line.colour)) {
      return make_error(name + ": " + which + " colour is not finite");
    }
    if (const auto ok = check_text(name, which + " label", line.label); !ok) {
      return ok.error();
    }
  }

  // Ranges: x from every drawable point; y from the drawable points inside a fixed x range, and the lines.
  std::vector<double> xs;
  std::vector<double> ys;
  for (const Series& s : plot.series) {
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (!plottable(s.x[k], plot.x.log) || !plottable(s.y[k], plot.y.log)) {
        continue;
      }
      xs.push_back(s.x[k]);
      if ((!plot.x.min || s.x[k] >= *plot.x.min) && (!plot.x.max || s.x[k] <= *plot.x.max)) {
        ys.push_back(s.y[k]);
      }
    }
  }
  for (const HorizontalLine& line : plot.lines) {
    if (plottable(line.y, plot.y.log)) {
      ys.push_back(line.y);
    }
  }
  const Result<Range> x_range = axis_range(name, "x", plot.x, xs, plot.x.log || plot.y.log);
  if (!x_range) {
    return x_range.error();
  }
  const Result<Range> y_range = axis_range(name, "y", plot.y, ys, plot.x.log || plot.y.log);
  if (!y_range) {
    return y_range.error();
  }

  const auto draw = [&](Canvas& canvas) {
    const Metrics& m = canvas.metrics();
    const double W = canvas.width();
    const double H = canvas.height();

    // Vertical layout.
    const double top = m.pad + title_block(m, plot.title) + 0.5 * m.tick;
    const double x_label_block = plot.x.label.empty() ? 0.0 : 0.965 * m.label + 0.6 * m.pad;
    const double bottom = m.pad + x_label_block + 1.25 * m.tick + m.tick_length + 0.4 * m.pad;
    const double plot_h = std::max(10.0, H - top - bottom);

    canvas.set_font(m.tick);
    const int y_count = std::clamp(static_cast<int>(plot_h / (2.8 * m.tick)), 2, 12);
    TickSet y_ticks = make_ticks(*y_range, plot.y.log, y_count);
    {
      // A reference line on an automatic end would hide in the frame (y = 1 over albedos up to 1): widen
      // that end by one more tick.
      Range r = *y_range;
      bool widen = false;
      for (const HorizontalLine& line : plot.lines) {
        const double tolerance = 1e-9 * std::abs(y_ticks.max - y_ticks.min);
        if (r.expand_hi && line.y >= y_ticks.max - tolerance) {
          r.hi = plot.y.log ? y_ticks.max * 1.01 : y_ticks.max + 0.01 * (y_ticks.max - y_ticks.min);
          widen = true;
        }
        if (r.expand_lo && line.y <= y_ticks.min + tolerance && plottable(line.y, plot.y.log)) {
          r.lo = plot.y.log ? y_ticks.min / 1.01 : y_ticks.min - 0.01 * (y_ticks.max - y_ticks.min);
          widen = true;
        }
      }
      if (widen) {
        y_ticks = make_ticks(r, plot.y.log, y_count);
      }
    }
    const double y_label_width = widest_label(canvas, y_ticks);

    // Horizontal layout.
    const double y_label_block = plot.y.label.empty() ? 0.0 : 0.965 * m.label + 0.6 * m.pad;
    const double left = m.pad + y_label_block + y_label_width + m.tick_length + 0.4 * m.pad;
    double right = m.pad + 1.5 * m.tick;
    double plot_w = std::max(10.0, W - left - right);

    TickSet x_ticks;
    for (int n = std::clamp(static_cast<int>(plot_w / (4.0 * m.tick)), 2, 12);; --n) {
      x_ticks = make_ticks(*x_range, plot.x.log, n);
      int labelled = 0;
      const double widest = widest_label(canvas, x_ticks, &labelled);
      if (labelled * (widest + 1.2 * m.tick) <= plot_w || n <= 2) {
        break;
      }
    }
    // The last x label is centred on the right edge: make room for its overhang.
    for (auto it = x_ticks.ticks.rbegin(); it != x_ticks.ticks.rend(); ++it) {
      if (!it->minor) {
        const double overhang = 0.5 * canvas.number_width(it->label) - (right - m.pad);
        if (overhang > 0.0 && it->value >= x_ticks.max - 1e-9 * std::abs(x_ticks.max - x_ticks.min)) {
          right += overhang;
          plot_w = std::max(10.0, W - left - right);
        }
        break;
      }
    }

    const Rect frame{left, top, left + plot_w, top + plot_h};
    const Scale sx{x_ticks.min, x_ticks.max, plot.x.log, frame.x0, frame.x1};
    const Scale sy{y_ticks.min, y_ticks.max, plot.y.log, frame.y1, frame.y0};

    // Grid: minor first, then major, so major lines win where they meet.
    for (const bool minor : {true, false}) {
      for (const Tick& t : x_ticks.ticks) {
        const double px = sx(t.value);
        if (t.minor == minor && px >= frame.x0 - 0.5 && px <= frame.x1 + 0.5) {
          const double x = canvas.snap(px, 1.0);
          canvas.line({x, frame.y0}, {x, frame.y1}, 1.0, minor ? minor_grid_grey : grid_grey);
        }
      }
      for (const Tick& t : y_ticks.ticks) {
        const double py = sy(t.value);
        if (t.minor == minor && py >= frame.y0 - 0.5 && py <= frame.y1 + 0.5) {
          const double y = canvas.snap(py, 1.0);
          canvas.line({frame.x0, y}, {frame.x1, y}, 1.0, minor ? minor_grid_grey : grid_grey);
        }
      }
    }

    // Data and reference lines, clipped to the frame.
    cairo_save(canvas.cr());
    cairo_rectangle(canvas.cr(), frame.x0, frame.y0, frame.width(), frame.height());
    cairo_clip(canvas.cr());
    std::vector<std::vector<Point>> drawn;
    for (const HorizontalLine& line : plot.lines) {
      const double py = sy(line.y);
      if (std::isfinite(py)) {
        const double y = canvas.snap(py, 1.2 * m.scale);
        canvas.line({frame.x0, y}, {frame.x1, y}, 1.2 * m.scale, line.colour.value_or(reference_grey), line.dashed);
        drawn.push_back({{frame.x0, y}, {frame.x1, y}});
      }
    }
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
      const Series& s = plot.series[i];
      std::vector<Point> points(s.x.size());
      for (std::size_t k = 0; k < s.x.size(); ++k) {
        points[k] = {sx(s.x[k]), sy(s.y[k])};
      }
      const double w = s.width * m.scale;
      canvas.polyline(points, frame.grown(2.0 * w + 2.0), w, series_colour(s, i), series_dashed(s, i));
      drawn.push_back(std::move(points));
    }
    cairo_restore(canvas.cr());

    // Frame, tick marks, tick labels.
    const Rect snapped{canvas.snap(frame.x0, 1.0), canvas.snap(frame.y0, 1.0), canvas.snap(frame.x1, 1.0),
                       canvas.snap(frame.y1, 1.0)};
    canvas.stroke_rect(snapped, 1.0, frame_grey);
    canvas.set_font(m.tick);
    for (const Tick& t : x_ticks.ticks) {
      const double px = sx(t.value);
      if (t.minor || px < frame.x0 - 0.5 || px > frame.x1 + 0.5) {
        continue;
      }
      const double x = canvas.snap(px, 1.0);
      canvas.line({x, snapped.y1}, {x, snapped.y1 + m.tick_length}, 1.0, frame_grey);
      canvas.set_colour(ink);
      canvas.number(t.label, px, frame.y1 + m.tick_length + 0.35 * m.pad, HAlign::centre, VAlign::top);
    }
    for (const Tick& t : y_ticks.ticks) {
      const double py = sy(t.value);
      if (t.minor || py < frame.y0 - 0.5 || py > frame.y1 + 0.5) {
        continue;
      }
      const double y = canvas.snap(py, 1.0);
      canvas.line({snapped.x0 - m.tick_length, y}, {snapped.x0, y}, 1.0, frame_grey);
      canvas.set_colour(ink);
      canvas.number(t.label, frame.x0 - m.tick_length - 0.35 * m.pad, py, HAlign::right, VAlign::centre);
    }

    // Axis labels and title.
    canvas.set_font(m.label);
    canvas.set_colour(ink);
    canvas.text(plot.x.label, 0.5 * (frame.x0 + frame.x1), H - m.pad, HAlign::centre, VAlign::bottom);
    canvas.text_rotated(plot.y.label, m.pad + 0.5 * 0.965 * m.label, 0.5 * (frame.y0 + frame.y1), -0.5 * pi);
    draw_title(canvas, plot.title);

    // Reference line labels: above the line at the right end (below it when the line is at the top), on a
    // white backing so that they read over the grid.
    canvas.set_font(m.tick);
    for (const HorizontalLine& line : plot.lines) {
      const double py = sy(line.y);
      if (line.label.empty() || !std::isfinite(py) || py < frame.y0 - 0.5 || py > frame.y1 + 0.5) {
        continue;
      }
      const double w = canvas.text_width(line.label);
      const double x = frame.x1 - 0.5 * m.pad;
      const bool below = py - 1.6 * m.tick < frame.y0;
      const double baseline = below ? py + 0.4 * m.tick + canvas.cap_height() : py - 0.4 * m.tick;
      canvas.fill_rect({x - w - 0.2 * m.tick, baseline - canvas.cap_height() - 0.2 * m.tick, x + 0.2 * m.tick,
                        baseline + 0.2 * m.tick},
                       white, 0.8);
      canvas.set_colour(line.colour.value_or(reference_grey));
      canvas.text(line.label, x, baseline, HAlign::right, VAlign::baseline);
      drawn.push_back({{x - w, baseline - canvas.cap_height()}, {x, baseline}});
    }

    // Legend: the inside corner that covers the fewest samples of the drawing; ties go to the first of
    // top right, top left, bottom right, bottom left.
    const std::vector<LegendEntry> entries = legend_entries(plot.series);
    if (plot.legend && !entries.empty()) {
      const LegendBox box = legend_size(canvas, entries);
      const double inset = 0.8 * m.pad;
      const std::vector<Point> corners{{frame.x1 - inset - box.width, frame.y0 + inset},
                                       {frame.x0 + inset, frame.y0 + inset},
                                       {frame.x1 - inset - box.width, frame.y1 - inset - box.height},
                                       {frame.x0 + inset, frame.y1 - inset - box.height}};
      const std::vector<Point> samples = coverage_samples(drawn, 4.0 * m.scale);
      std::size_t best = 0;
      std::size_t best_count = std::numeric_limits<std::size_t>::max();
      for (std::size_t c = 0; c < corners.size(); ++c) {
        const Rect r = Rect{corners[c].x, corners[c].y, corners[c].x + box.width, corners[c].y + box.height}.grown(3.0);
        const auto count = static_cast<std::size_t>(
            std::count_if(samples.begin(), samples.end(), [&](const Point& p) { return r.contains(p); }));
        if (count < best_count) {
          best = c;
          best_count = count;
        }
      }
      draw_legend(canvas, entries, corners[best].x, corners[best].y);
    }
  };

  std::string desc = "x axis: " + plot.x.label + "\ny axis: " + plot.y.label;
  for (const Series& s : plot.series) {
    if (!s.label.empty()) {
      desc += "\nseries: " + s.label;
    }
  }
  for (const HorizontalLine& line : plot.lines) {
    if (!line.label.empty()) {
      desc += "\nreference line: " + line.label;
    }
  }
  return render_with_cairo(format, width, height, draw, plot.title, desc);
}

}  // namespace shadelab
