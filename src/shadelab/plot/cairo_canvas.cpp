// shadelab plot internals: Cairo surfaces in memory, text, clipped polylines, the legend (see cairo_canvas.h).
#include "shadelab/plot/cairo_canvas.h"

#include <cairo-svg.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "shadelab/core/constants.h"
#include "shadelab/core/text.h"
#include "shadelab/image/srgb.h"

namespace shadelab::plot_detail {
namespace {

constexpr std::string_view font_family = "DejaVu Sans";
constexpr double superscript_size = 0.7;   // of the base font size
constexpr double superscript_rise = 0.42;  // of the base font size
constexpr std::string_view minus_sign = "\u2212";

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
struct FontOptionsDeleter {
  void operator()(cairo_font_options_t* o) const { cairo_font_options_destroy(o); }
};

// Cairo's write callback: appends to the std::vector<char> passed as closure.
cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
  auto* bytes = static_cast<std::vector<char>*>(closure);
  const auto* begin = reinterpret_cast<const char*>(data);
  bytes->insert(bytes->end(), begin, begin + length);
  return CAIRO_STATUS_SUCCESS;
}

// A number label "a^b" -> {"a", "b"}, no '^' -> {text, ""}; a minus sign starting either part becomes
// U+2212. Plain text is returned as it is.
std::pair<std::string, std::string> typeset(std::string_view text, bool number) {
  if (!number) {
    return {std::string(text), {}};
  }
  const auto fix_minus = [](std::string_view part) {
    std::string s(part);
    if (!s.empty() && s[0] == '-') {
      s.replace(0, 1, minus_sign);
    }
    return s;
  };
  const auto caret = text.find('^');
  if (caret == std::string_view::npos) {
    return {fix_minus(text), {}};
  }
  return {fix_minus(text.substr(0, caret)), fix_minus(text.substr(caret + 1))};
}

double advance(cairo_t* cr, const std::string& s) {
  if (s.empty()) {
    return 0.0;
  }
  cairo_text_extents_t extents;
  cairo_text_extents(cr, s.c_str(), &extents);
  return extents.x_advance;
}

// Liang-Barsky: clips the segment a-b to r; false when nothing is left.
bool clip_segment(Point& a, Point& b, const Rect& r) {
  double t0 = 0.0;
  double t1 = 1.0;
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const std::array<double, 4> p{-dx, dx, -dy, dy};
  const std::array<double, 4> q{a.x - r.x0, r.x1 - a.x, a.y - r.y0, r.y1 - a.y};
  for (std::size_t i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) {
        return false;
      }
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
    if (t0 > t1) {
      return false;
    }
  }
  const Point a0 = a;
  if (t0 > 0.0) {
    a = {a0.x + t0 * dx, a0.y + t0 * dy};
  }
  if (t1 < 1.0) {
    b = {a0.x + t1 * dx, a0.y + t1 * dy};
  }
  return true;
}

bool finite(const Point& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// Cairo names the root group "surface" + a process-wide counter, so a second plot in the same process
// would differ from the first. Renumber every id="surfaceN" and #surfaceN reference in order of first appearance, from 1.
std::string renumber_surfaces(const std::string& svg) {
  std::string out;
  out.reserve(svg.size());
  std::map<std::string, int> numbers;
  constexpr std::string_view word = "surface";
  std::size_t pos = 0;
  for (;;) {
    const std::size_t hit = svg.find(word, pos);
    if (hit == std::string::npos) {
      out.append(svg, pos, std::string::npos);
      break;
    }
    std::size_t end = hit + word.size();
    while (end < svg.size() && svg[end] >= '0' && svg[end] <= '9') {
      ++end;
    }
    const bool is_id = hit > 0 && (svg[hit - 1] == '"' || svg[hit - 1] == '#') && end > hit + word.size();
    out.append(svg, pos, hit - pos);
    if (is_id) {
      const std::string digits = svg.substr(hit + word.size(), end - hit - word.size());
      const auto [it, inserted] = numbers.emplace(digits, static_cast<int>(numbers.size()) + 1);
      out.append(word);
      out.append(std::to_string(it->second));
    } else {
      out.append(svg, hit, end - hit);
    }
    pos = end;
  }
  return out;
}

std::vector<char> finish_svg(const std::vector<char>& cairo_svg, const std::string& title, const std::string& desc) {
  std::string svg = renumber_surfaces(std::string(cairo_svg.begin(), cairo_svg.end()));
  const std::size_t root = svg.find("<svg");
  const std::size_t root_end = root == std::string::npos ? std::string::npos : svg.find('>', root);
  if (root_end != std::string::npos) {
    std::string meta;
    if (!title.empty()) {
      meta += "\n<title>" + xml_escape(title) + "</title>";
    }
    if (!desc.empty()) {
      meta += "\n<desc>" + xml_escape(desc) + "</desc>";
    }
    svg.insert(root_end + 1, meta);
  }
  return {svg.begin(), svg.end()};
}

}  // namespace

Metrics metrics_for(int width, int height) {
  // The geometric mean of the two ratios, so that 400 x 600 is not drawn with the text of 400 x 300; at most
  // 1.5 times the smaller ratio, so that a very wide, short image keeps room for its chart.
  const double rw = width / 800.0;
  const double rh = height / 600.0;
  const double s = std::clamp(std::min(std::sqrt(rw * rh), 1.5 * std::min(rw, rh)), 0.5, 4.0);
  Metrics m;
  m.scale = s;
  m.title *= s;
  m.label *= s;
  m.tick *= s;
  m.legend *= s;
  m.pad *= s;
  m.tick_length *= s;
  return m;
}

Canvas::Canvas(cairo_t* cr, int width, int height)
    : m_cr(cr), m_width(width), m_height(height), m_metrics(metrics_for(width, height)) {
  set_font(m_metrics.tick);
}

void Canvas::set_colour(const Rgb& linear, double alpha) {
  const auto encode = [](double v) { return std::clamp(linear_to_srgb(std::clamp(v, 0.0, 1.0)), 0.0, 1.0); };
  cairo_set_source_rgba(m_cr, encode(linear.r), encode(linear.g), encode(linear.b), alpha);
}

void Canvas::set_font(double size, bool bold) {
  const std::string family(font_family);
  cairo_select_font_face(m_cr, family.c_str(), CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(m_cr, size);
  m_font_size = size;
}

double Canvas::width_of(std::string_view text, bool number) const {
  const auto [base, sup] = typeset(text, number);
  double w = advance(m_cr, base);
  if (!sup.empty()) {
    cairo_set_font_size(m_cr, m_font_size * superscript_size);
    w += advance(m_cr, sup);
    cairo_set_font_size(m_cr, m_font_size);
  }
  return w;
}

void Canvas::draw(std::string_view text, bool number, double x, double y, HAlign h, VAlign v) {
  if (text.empty()) {
    return;
  }
  const double w = width_of(text, number);
  const double x0 = h == HAlign::left ? x : (h == HAlign::centre ? x - 0.5 * w : x - w);
  double baseline = y;
  switch (v) {
    case VAlign::top: baseline = y + cap_height(); break;
    case VAlign::centre: baseline = y + 0.5 * cap_height(); break;
    case VAlign::baseline: break;
    case VAlign::bottom: baseline = y - 0.236 * m_font_size; break;  // DejaVu Sans descent
  }
  const auto [base, sup] = typeset(text, number);
  cairo_move_to(m_cr, x0, baseline);
  cairo_show_text(m_cr, base.c_str());
  if (!sup.empty()) {
    const double base_width = advance(m_cr, base);
    cairo_set_font_size(m_cr, m_font_size * superscript_size);
    cairo_move_to(m_cr, x0 + base_width, baseline - superscript_rise * m_font_size);
    cairo_show_text(m_cr, sup.c_str());
    cairo_set_font_size(m_cr, m_font_size);
  }
}

void Canvas::text_rotated(std::string_view text, double x, double y, double angle) {
  cairo_save(m_cr);
  cairo_translate(m_cr, x, y);
  cairo_rotate(m_cr, angle);
  this->text(text, 0.0, 0.0, HAlign::centre, VAlign::centre);
  cairo_restore(m_cr);
}

double Canvas::snap(double coordinate, double line_width) const {
  // An odd pixel width is centred on a pixel centre, an even one on a pixel edge.
  const double w = std::max(1.0, std::round(line_width));
  const bool odd = static_cast<long long>(w) % 2 == 1;
  return odd ? std::floor(coordinate) + 0.5 : std::round(coordinate);
}

void Canvas::set_dash(bool dashed, double width) {
  if (dashed) {
    const std::array<double, 2> pattern{4.0 * width + 2.0, 2.5 * width + 2.0};
    cairo_set_dash(m_cr, pattern.data(), 2, 0.0);
  } else {
    cairo_set_dash(m_cr, nullptr, 0, 0.0);
  }
}

void Canvas::line(Point a, Point b, double width, const Rgb& colour, bool dashed) {
  set_colour(colour);
  cairo_set_line_width(m_cr, width);
  cairo_set_line_cap(m_cr, CAIRO_LINE_CAP_BUTT);
  set_dash(dashed, width);
  cairo_move_to(m_cr, a.x, a.y);
  cairo_line_to(m_cr, b.x, b.y);
  cairo_stroke(m_cr);
  set_dash(false, width);
}

void Canvas::polyline(const std::vector<Point>& points, const Rect& bounds, double width, const Rgb& colour,
                      bool dashed) {
  set_colour(colour);
  cairo_set_line_width(m_cr, width);
  cairo_set_line_join(m_cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(m_cr, dashed ? CAIRO_LINE_CAP_BUTT : CAIRO_LINE_CAP_ROUND);
  set_dash(dashed, width);

  std::vector<Point> dots;
  bool pen_down = false;
  Point pen{};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    if (!finite(p)) {
      pen_down = false;
      continue;
    }
    const bool has_prev = i > 0 && finite(points[i - 1]);
    const bool has_next = i + 1 < points.size() && finite(points[i + 1]);
    if (!has_prev) {
      if (!has_next && bounds.contains(p)) {
        dots.push_back(p);
      }
      pen_down = false;
      continue;
    }
    Point a = points[i - 1];
    Point b = p;
    if (!clip_segment(a, b, bounds)) {
      pen_down = false;
      continue;
    }
    if (!pen_down || a.x != pen.x || a.y != pen.y) {
      cairo_move_to(m_cr, a.x, a.y);
    }
    cairo_line_to(m_cr, b.x, b.y);
    pen = b;
    pen_down = true;
  }
  cairo_stroke(m_cr);
  set_dash(false, width);
  for (const Point& d : dots) {
    cairo_new_sub_path(m_cr);
    cairo_arc(m_cr, d.x, d.y, std::max(1.5, 1.25 * width), 0.0, 2.0 * pi);
  }
  cairo_fill(m_cr);
}

void Canvas::fill_rect(const Rect& r, const Rgb& colour, double alpha) {
  set_colour(colour, alpha);
  cairo_rectangle(m_cr, r.x0, r.y0, r.width(), r.height());
  cairo_fill(m_cr);
}

void Canvas::stroke_rect(const Rect& r, double width, const Rgb& colour) {
  set_colour(colour);
  cairo_set_line_width(m_cr, width);
  set_dash(false, width);
  cairo_rectangle(m_cr, r.x0, r.y0, r.width(), r.height());
  cairo_stroke(m_cr);
}

// ---- title ----

double title_block(const Metrics& m, const std::string& title) {
  return title.empty() ? 0.0 : 0.965 * m.title + 0.9 * m.pad;
}

void draw_title(Canvas& canvas, const std::string& title) {
  if (title.empty()) {
    return;
  }
  const auto& m = canvas.metrics();
  canvas.set_font(m.title, true);
  const double available = canvas.width() - 2.0 * m.pad;
  const double w = canvas.text_width(title);
  if (w > available) {
    canvas.set_font(std::max(0.6 * m.title, m.title * available / w), true);  // shrink a long title to fit
  }
  canvas.set_colour(ink);
  canvas.text(title, 0.5 * canvas.width(), m.pad, HAlign::centre, VAlign::top);
}

// ---- legend ----

namespace {
struct LegendLayout {
  double pad = 0.0;
  double row = 0.0;
  double sample = 0.0;
  double gap = 0.0;
};
LegendLayout legend_layout(const Canvas& canvas) {
  const Metrics& m = canvas.metrics();
  return {0.7 * m.legend, 1.5 * m.legend, 2.4 * m.legend, 0.6 * m.legend};
}
}  // namespace

LegendBox legend_size(Canvas& canvas, const std::vector<LegendEntry>& entries) {
  if (entries.empty()) {
    return {};
  }
  canvas.set_font(canvas.metrics().legend);
  const LegendLayout l = legend_layout(canvas);
  double text = 0.0;
  for (const LegendEntry& e : entries) {
    text = std::max(text, canvas.text_width(e.label));
  }
  return {2.0 * l.pad + l.sample + l.gap + text, 2.0 * l.pad + l.row * static_cast<double>(entries.size())};
}

void draw_legend(Canvas& canvas, const std::vector<LegendEntry>& entries, double x, double y) {
  if (entries.empty()) {
    return;
  }
  const LegendBox box = legend_size(canvas, entries);
  const LegendLayout l = legend_layout(canvas);
  const double s = canvas.metrics().scale;
  const Rect r{x, y, x + box.width, y + box.height};
  canvas.fill_rect(r, white, 0.9);
  canvas.stroke_rect({canvas.snap(r.x0, 1.0), canvas.snap(r.y0, 1.0), canvas.snap(r.x1, 1.0), canvas.snap(r.y1, 1.0)},
                     1.0, grid_grey);
  canvas.set_font(canvas.metrics().legend);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const LegendEntry& e = entries[i];
    const double cy = y + l.pad + l.row * (static_cast<double>(i) + 0.5);
    canvas.line({x + l.pad, cy}, {x + l.pad + l.sample, cy}, e.width * s, e.colour, e.dashed);
    canvas.set_colour(ink);
    canvas.text(e.label, x + l.pad + l.sample + l.gap, cy, HAlign::left, VAlign::centre);
  }
}

Rgb series_colour(const Series& series, std::size_t index) {
  return series.colour ? *series.colour : plot_palette(index);
}

bool series_dashed(const Series& series, std::size_t index) {
  const bool palette_repeat = !series.colour && (index / plot_palette_size) % 2 == 1;
  return series.dashed || palette_repeat;
}

std::vector<LegendEntry> legend_entries(const std::vector<Series>& series) {
  std::vector<LegendEntry> entries;
  for (std::size_t i = 0; i < series.size(); ++i) {
    if (!series[i].label.empty()) {
      entries.push_back({series[i].label, series_colour(series[i], i), series[i].width, series_dashed(series[i], i)});
    }
  }
  return entries;
}

// ---- surfaces ----

Result<std::vector<char>> render_with_cairo(PlotFormat format, int width, int height,
                                            const std::function<void(Canvas&)>& draw, const std::string& svg_title,
                                            const std::string& svg_desc) {
  std::vector<char> bytes;
  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
      format == PlotFormat::png
          ? cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height)
          : cairo_svg_surface_create_for_stream(append_bytes, &bytes, static_cast<double>(width),
                                                static_cast<double>(height)));
  if (const cairo_status_t st = cairo_surface_status(surface.get()); st != CAIRO_STATUS_SUCCESS) {
    return make_error(std::string("plot: cannot create the Cairo surface: ") + cairo_status_to_string(st));
  }
  if (format == PlotFormat::svg) {
#if CAIRO_VERSION >= CAIRO_VERSION_ENCODE(1, 15, 10)
    // <svg width="800px" height="600px">: one user unit is one pixel (Cairo 1.16 defaults to points).
    cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PX);
#endif
  }
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  {
    std::unique_ptr<cairo_t, ContextDeleter> cr(cairo_create(surface.get()));
    // Fixed font options, so that the output does not depend on the desktop's font settings. Unhinted
    // metrics: text advances are the same on the SVG and the PNG surface.
    std::unique_ptr<cairo_font_options_t, FontOptionsDeleter> options(cairo_font_options_create());
    cairo_font_options_set_antialias(options.get(), CAIRO_ANTIALIAS_GRAY);
    cairo_font_options_set_hint_style(options.get(), CAIRO_HINT_STYLE_NONE);
    cairo_font_options_set_hint_metrics(options.get(), CAIRO_HINT_METRICS_OFF);
    cairo_set_font_options(cr.get(), options.get());

    cairo_set_source_rgb(cr.get(), 1.0, 1.0, 1.0);
    cairo_paint(cr.get());
    Canvas canvas(cr.get(), width, height);
    draw(canvas);
    status = cairo_status(cr.get());
  }
  if (status == CAIRO_STATUS_SUCCESS) {
    if (format == PlotFormat::png) {
      cairo_surface_flush(surface.get());
      status = cairo_surface_write_to_png_stream(surface.get(), append_bytes, &bytes);
    } else {
      cairo_surface_finish(surface.get());  // the SVG is written to `bytes` here
      status = cairo_surface_status(surface.get());
    }
  }
  if (status != CAIRO_STATUS_SUCCESS) {
    return make_error(std::string("plot: Cairo failed: ") + cairo_status_to_string(status));
  }
  if (format == PlotFormat::svg) {
    return finish_svg(bytes, svg_title, svg_desc);
  }
  return bytes;
}

}  // namespace shadelab::plot_detail
