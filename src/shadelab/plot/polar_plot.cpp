// shadelab plots: the polar chart of an in-plane lobe (contract in plot.h).
//
// The upper half-disc, centre at the bottom middle: angle 0 (the normal) points up, +90 degrees right,
// -90 left, as BRDF Explorer draws in-plane lobes. Spokes every 15 degrees (30 when small) labelled every
// 30, semicircles at the radius ticks labelled along the right horizon, the legend below the horizon on
// the left.
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
constexpr double degree = pi / 180.0;

// Radius value -> fraction of the disc radius (NaN stays NaN).
struct RadiusScale {
  bool log = false;
  double max = 1.0;        // linear: the value at the rim
  double top_exp = 0.0;    // log: log10 of the value at the rim
  double decades = 4.0;    // log: decades between the centre and the rim

  double operator()(double v) const {
    if (std::isnan(v)) {
      return nan;
    }
    if (!log) {
      return std::clamp(v / max, 0.0, 1e12);
    }
    if (!(v > 0.0)) {
      return 0.0;  // log10(0) = -inf, clamped at the centre
    }
    return std::clamp((std::log10(v) - (top_exp - decades)) / decades, 0.0, 1e12);
  }
};

bool is_decade(double v) {
  const double e = std::log10(v);
  return std::abs(e - std::round(e)) < 1e-9;
}

// "-30°" style label of an angle in whole degrees.
std::string degrees_label(int d) { return std::to_string(d) + "\u00b0"; }

}  // namespace

Result<std::vector<char>> render_plot(const PolarPlot& plot, PlotFormat format, int width, int height) {
  using namespace plot_detail;
  const std::string name = plot_name("polar plot", plot.title);
  for (const Result<bool>& check : {check_size(name, width, height), check_text(name, "title", plot.title),
                                    check_text(name, "radius label", plot.radius_label),
                                    check_series(name, plot.series)}) {
    if (!check) {
      return check.error();
    }
  }
  double data_max = 0.0;
  double positive_max = 0.0;
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const Series& s = plot.series[i];
    for (std::size_t k = 0; k < s.y.size(); ++k) {
      if (s.y[k] < 0.0) {
        return make_error(name + ": " + series_name(s, i) + ": point " + std::to_string(k) + " has a negative radius (" +
                          number(s.y[k]) + ")");
      }
      if (std::isfinite(s.x[k]) && std::isfinite(s.y[k])) {
        data_max = std::max(data_max, s.y[k]);
        positive_max = std::max(positive_max, s.y[k]);
      }
    }
  }
  if (!std::isfinite(plot.log_floor_decades) || !(plot.log_floor_decades > 0.0) || plot.log_floor_decades > 30.0) {
    return make_error(name + ": log_floor_decades = " + number(plot.log_floor_decades) +
                      " is out of range (0, 30]");
  }
  if (plot.radius_max && (!std::isfinite(*plot.radius_max) || !(*plot.radius_max > 0.0))) {
    return make_error(name + ": radius_max = " + number(*plot.radius_max) + " is not a positive number");
  }
  for (std::size_t i = 0; i < plot.rays.size(); ++i) {
    const std::string which = "ray " + std::to_string(i + 1);
    if (!std::isfinite(plot.rays[i].angle)) {
      return make_error(name + ": " + which + " angle is not finite");
    }
    if (const auto ok = check_text(name, which + " label", plot.rays[i].label); !ok) {
      return ok.error();
    }
  }

  RadiusScale rs;
  rs.log = plot.log_radius;
  rs.decades = plot.log_floor_decades;
  if (plot.log_radius) {
    rs.top_exp = plot.radius_max ? std::log10(*plot.radius_max)
                                 : (positive_max > 0.0 ? std::ceil(std::log10(positive_max) - 1e-9) : 0.0);
  }

  const auto draw = [&](Canvas& canvas) {
    const Metrics& m = canvas.metrics();
    const double W = canvas.width();
    const double H = canvas.height();
    canvas.set_font(m.tick);
    const double cap = canvas.cap_height();
    const double gap = 0.5 * m.tick;
    const double side_label = canvas.number_width(degrees_label(-90));

    // Layout, top down: the title; the "0°" label; the half-disc; below the horizon the radius labels and
    // the radius axis label on the right, the legend on the left (or under everything when too wide). A
    // half-disc is twice as wide as high, so the height left over is shared above and below the drawing.
    const double top = m.pad + title_block(m, plot.title);
    const double radius_block = m.tick_length + 0.3 * m.pad + 1.25 * m.tick +
                                (plot.radius_label.empty() ? 0.0 : 0.5 * m.pad + 0.965 * m.label);
    const std::vector<LegendEntry> entries = legend_entries(plot.series);
    const bool with_legend = plot.legend && !entries.empty();
    const LegendBox box = with_legend ? legend_size(canvas, entries) : LegendBox{};
    canvas.set_font(m.tick);
    const double legend_right = 0.5 * W - 0.5 * canvas.number_width("0.0") - m.tick;  // clear of the centre label
    const bool legend_beside = with_legend && legend_right - box.width >= m.pad;
    const double under_block = !with_legend ? radius_block
                               : legend_beside ? std::max(radius_block, 0.6 * m.pad + box.height)
                                               : radius_block + 0.6 * m.pad + box.height;
    const double R = std::max(10.0, std::min(0.5 * W - m.pad - gap - side_label,
                                             H - top - m.pad - under_block - gap - cap));
    const double extra = std::max(0.0, H - top - m.pad - (gap + cap + R + under_block));
    const Point c{0.5 * W, top + 0.5 * extra + gap + cap + R};
    Point legend_at{};
    if (legend_beside) {
      // Left-aligned with the rim's end when there is room, else right-aligned next to the centre.
      legend_at = {std::min(c.x - R, legend_right - box.width), c.y + 0.6 * m.pad};
    } else if (with_legend) {
      legend_at = {std::max(m.pad, c.x - 0.5 * box.width), c.y + radius_block + 0.6 * m.pad};
    }

    const auto at = [&](double angle, double radius) {
      return Point{c.x + radius * std::sin(angle), c.y - radius * std::cos(angle)};
    };

    // Radius ticks.
    canvas.set_font(m.tick);
    TickSet r_ticks;
    if (plot.log_radius) {
      const double lo = std::pow(10.0, rs.top_exp - rs.decades);
      const double hi = std::pow(10.0, rs.top_exp);
      for (int n = std::clamp(static_cast<int>(R / (3.0 * m.tick)), 2, 12);; --n) {
        r_ticks = log_ticks(lo, hi, n);
        int labelled = 0;
        double widest = 0.0;
        for (const Tick& t : r_ticks.ticks) {
          labelled += t.minor ? 0 : 1;
          widest = t.minor ? widest : std::max(widest, canvas.number_width(t.label));
        }
        if (labelled * (widest + m.tick) <= R || n <= 2) {
          break;
        }
      }
    } else {
      const double max = plot.radius_max ? *plot.radius_max : (data_max > 0.0 ? data_max : 1.0);
      for (int n = std::clamp(static_cast<int>(R / (3.0 * m.tick)), 2, 12);; --n) {
        r_ticks = linear_ticks(0.0, max, n, false, !plot.radius_max);
        double widest = 0.0;
        for (const Tick& t : r_ticks.ticks) {
          widest = std::max(widest, canvas.number_width(t.label));
        }
        if (static_cast<double>(r_ticks.ticks.size()) * (widest + m.tick) <= R + widest || n <= 2) {
          break;
        }
      }
      rs.max = r_ticks.max;
    }

    // Radius circles: labelled ticks dark, unlabelled decades light (log: no 2..9 circles, too busy).
    for (const bool minor : {true, false}) {
      for (const Tick& t : r_ticks.ticks) {
        const double rho = rs(t.value) * R;
        if (t.minor != minor || !(rho > 0.5) || rho > R - 0.5 || (minor && !is_decade(t.value))) {
          continue;
        }
        canvas.set_colour(minor ? minor_grid_grey : grid_grey);
        cairo_set_line_width(canvas.cr(), 1.0);
        cairo_new_path(canvas.cr());
        cairo_arc(canvas.cr(), c.x, c.y, rho, pi, 2.0 * pi);
        cairo_stroke(canvas.cr());
      }
    }
    // Spokes: every 15 degrees when the disc is large enough, darker every 30.
    const int spoke_step = R >= 120.0 * m.scale ? 15 : 30;
    for (const bool minor : {true, false}) {
      for (int d = -90 + spoke_step; d < 90; d += spoke_step) {
        if ((d % 30 != 0) == minor) {
          canvas.line(c, at(d * degree, R), 1.0, minor ? minor_grid_grey : grid_grey);
        }
      }
    }

    // Series, clipped to the half-disc.
    cairo_save(canvas.cr());
    cairo_new_path(canvas.cr());
    cairo_arc(canvas.cr(), c.x, c.y, R, pi, 2.0 * pi);
    cairo_close_path(canvas.cr());
    cairo_clip(canvas.cr());
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
      const Series& s = plot.series[i];
      std::vector<Point> points(s.x.size());
      for (std::size_t k = 0; k < s.x.size(); ++k) {
        const double rho = rs(s.y[k]) * R;
        points[k] = std::isfinite(s.x[k]) && std::isfinite(rho) ? at(s.x[k], rho) : Point{nan, nan};
      }
      const double w = s.width * m.scale;
      canvas.polyline(points, Rect{c.x - R, c.y - R, c.x + R, c.y}.grown(2.0 * w + 2.0), w, series_colour(s, i),
                      series_dashed(s, i));
    }
    cairo_restore(canvas.cr());

    // Rim and horizon.
    canvas.set_colour(frame_grey);
    cairo_set_line_width(canvas.cr(), 1.0);
    cairo_new_path(canvas.cr());
    cairo_arc(canvas.cr(), c.x, c.y, R, pi, 2.0 * pi);
    cairo_stroke(canvas.cr());
    const double horizon_y = canvas.snap(c.y, 1.5 * m.scale);
    canvas.line({c.x - R - 0.5, horizon_y}, {c.x + R + 0.5, horizon_y}, 1.5 * m.scale, frame_grey);

    // Angle labels every 30 degrees, just outside the rim.
    canvas.set_font(m.tick);
    canvas.set_colour(ink);
    for (int d = -90; d <= 90; d += 30) {
      const std::string label = degrees_label(d);
      const double a = d * degree;
      const double w = canvas.number_width(label);
      Point p = at(a, R + gap + 0.5 * (std::abs(std::sin(a)) * w + std::abs(std::cos(a)) * cap));
      if (std::abs(d) == 90) {
        p.y -= 0.5 * cap + 0.25 * gap;  // sit on the horizon, clear of the radius labels below it
      }
      canvas.number(label, p.x, p.y, HAlign::centre, VAlign::centre);
    }

    // Radius labels along the right horizon.
    for (const Tick& t : r_ticks.ticks) {
      const double rho = rs(t.value) * R;
      if (t.minor || !std::isfinite(rho) || rho > R + 0.5) {
        continue;
      }
      canvas.line({c.x + rho, horizon_y}, {c.x + rho, horizon_y + m.tick_length}, 1.0, frame_grey);
      canvas.set_colour(ink);
      canvas.number(t.label, c.x + rho, horizon_y + m.tick_length + 0.3 * m.pad, HAlign::centre, VAlign::top);
    }
    if (!plot.radius_label.empty()) {
      canvas.set_font(m.label);
      const double w = canvas.text_width(plot.radius_label);
      const double x = std::clamp(c.x + 0.5 * R, m.pad + 0.5 * w, W - m.pad - 0.5 * w);
      canvas.set_colour(ink);
      canvas.text(plot.radius_label, x, c.y + radius_block, HAlign::centre, VAlign::bottom);
    }

    // Rays: from the centre to the rim, labelled just inside the rim on a white backing.
    canvas.set_font(m.tick);
    for (const PolarRay& ray : plot.rays) {
      canvas.line(c, at(ray.angle, R), 1.2 * m.scale, reference_grey, true);
      if (ray.label.empty()) {
        continue;
      }
      const double w = canvas.text_width(ray.label);
      const double inset = gap + 0.5 * (std::abs(std::sin(ray.angle)) * w + std::abs(std::cos(ray.angle)) * cap);
      const Point p = at(ray.angle, std::max(0.0, R - inset - 0.2 * m.tick));
      canvas.fill_rect({p.x - 0.5 * w - 0.2 * m.tick, p.y - 0.5 * cap - 0.25 * m.tick, p.x + 0.5 * w + 0.2 * m.tick,
                        p.y + 0.5 * cap + 0.25 * m.tick},
                       white, 0.85);
      canvas.set_colour(reference_grey);
      canvas.text(ray.label, p.x, p.y, HAlign::centre, VAlign::centre);
    }

    draw_title(canvas, plot.title);
    if (with_legend) {
      draw_legend(canvas, entries, legend_at.x, legend_at.y);
    }
  };

  std::string desc = "radius: " + plot.radius_label + (plot.log_radius ? " (log scale)" : "");
  for (const Series& s : plot.series) {
    if (!s.label.empty()) {
      desc += "\nseries: " + s.label;
    }
  }
  for (const PolarRay& ray : plot.rays) {
    if (!ray.label.empty()) {
      desc += "\nray: " + ray.label;
    }
  }
  return render_with_cairo(format, width, height, draw, plot.title, desc);
}

}  // namespace shadelab
