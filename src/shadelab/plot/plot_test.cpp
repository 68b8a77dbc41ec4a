// Tests of the plot module: PNG and SVG files of the requested size, well-formed SVG carrying the chart's
// text, deterministic bytes, NaN gaps and clipping as documented, and an Error for every kind of bad input.
#include "shadelab/plot/plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace shadelab {
namespace {

namespace fs = std::filesystem;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

std::string text_of(const std::vector<char>& bytes) { return {bytes.begin(), bytes.end()}; }

std::uint32_t big_endian_u32(const std::vector<char>& b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    v = (v << 8) | static_cast<unsigned char>(b.at(at + i));
  }
  return v;
}

// PNG: the 8-byte signature, then the IHDR chunk (length 13, "IHDR", width, height, ...).
void expect_png_of_size(const std::vector<char>& bytes, int width, int height) {
  ASSERT_GE(bytes.size(), 33u);
  const std::string signature("\x89PNG\r\n\x1a\n", 8);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 8), signature);
  EXPECT_EQ(big_endian_u32(bytes, 8), 13u);
  EXPECT_EQ(std::string(bytes.begin() + 12, bytes.begin() + 16), "IHDR");
  EXPECT_EQ(big_endian_u32(bytes, 16), static_cast<std::uint32_t>(width));
  EXPECT_EQ(big_endian_u32(bytes, 20), static_cast<std::uint32_t>(height));
}

// A minimal XML well-formedness check: declarations, comments and CDATA are skipped; every start tag is
// closed by the matching end tag in order (or is empty, <x/>); quoted attribute values may hold '>';
// every '&' starts a known entity or a character reference; one root element and no text outside it.
// Returns "" when well-formed, else what is wrong; `root` receives the root's start tag.
std::string xml_problem(const std::string& xml, std::string* root) {
  std::vector<std::string> open;
  bool seen_root = false;
  std::size_t i = 0;
  const auto starts = [&](std::string_view s) { return xml.compare(i, s.size(), s) == 0; };
  const auto skip_past = [&](std::string_view end) {
    const std::size_t at = xml.find(end, i);
    if (at == std::string::npos) {
      return false;
    }
    i = at + end.size();
    return true;
  };
  const auto is_name_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == ':' || c == '-' || c == '_' || c == '.';
  };
  while (i < xml.size()) {
    const char c = xml[i];
    if (c == '<') {
      if (starts("<?")) {
        if (!skip_past("?>")) return "unterminated <?";
        continue;
      }
      if (starts("<!--")) {
        if (!skip_past("-->")) return "unterminated comment";
        continue;
      }
      if (starts("<![CDATA[")) {
        if (!skip_past("]]>")) return "unterminated CDATA";
        continue;
      }
      if (starts("<!")) {
        if (!skip_past(">")) return "unterminated <!";
        continue;
      }
      const bool closing = starts("</");
      std::size_t j = i + (closing ? 2 : 1);
      const std::size_t name_start = j;
      while (j < xml.size() && is_name_char(xml[j])) ++j;
      const std::string name = xml.substr(name_start, j - name_start);
      if (name.empty()) return "tag without a name at " + std::to_string(i);
      char quote = 0;
      while (j < xml.size() && (quote != 0 || xml[j] != '>')) {
        if (quote == 0 && (xml[j] == '"' || xml[j] == '\'')) {
          quote = xml[j];
        } else if (quote != 0 && xml[j] == quote) {
          quote = 0;
        } else if (xml[j] == '<') {
          return "'<' inside tag <" + name + ">";
        }
        ++j;
      }
      if (j >= xml.size()) return "unterminated tag <" + name + ">";
      const bool empty = !closing && xml[j - 1] == '/';
      if (closing) {
        if (open.empty() || open.back() != name) return "</" + name + "> does not close the open element";
        open.pop_back();
      } else {
        if (open.empty()) {
          if (seen_root) return "a second root element <" + name + ">";
          seen_root = true;
          if (root != nullptr) *root = xml.substr(i, j + 1 - i);
        }
        if (!empty) open.push_back(name);
      }
      i = j + 1;
      continue;
    }
    if (c == '&') {
      const std::size_t semi = xml.find(';', i);
      if (semi == std::string::npos) return "'&' without ';'";
      const std::string entity = xml.substr(i + 1, semi - i - 1);
      const bool named = entity == "amp" || entity == "lt" || entity == "gt" || entity == "quot" || entity == "apos";
      const bool numeric = entity.size() > 1 && entity[0] == '#';
      if (!named && !numeric) return "unknown entity &" + entity + ";";
      i = semi + 1;
      continue;
    }
    if (open.empty() && std::isspace(static_cast<unsigned char>(c)) == 0) {
      return std::string("text outside the root element: '") + c + "'";
    }
    ++i;
  }
  if (!open.empty()) return "<" + open.back() + "> is never closed";
  if (!seen_root) return "no root element";
  return "";
}

// The number in attribute `name`="123px" of a start tag (the unit, if any, must be px).
double attribute_number(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) {
    return nan;
  }
  const std::size_t begin = at + key.size();
  const std::size_t end = tag.find('"', begin);
  std::string value = tag.substr(begin, end - begin);
  if (value.size() > 2 && value.compare(value.size() - 2, 2, "px") == 0) {
    value.resize(value.size() - 2);
  }
  std::size_t used = 0;
  const double v = std::stod(value, &used);
  return used == value.size() ? v : nan;
}

void expect_svg_of_size(const std::vector<char>& bytes, int width, int height) {
  const std::string svg = text_of(bytes);
  std::string root;
  EXPECT_EQ(xml_problem(svg, &root), "");
  ASSERT_EQ(root.rfind("<svg", 0), 0u) << root;
  EXPECT_EQ(attribute_number(root, "width"), width);
  EXPECT_EQ(attribute_number(root, "height"), height);
  // One user unit per pixel.
  EXPECT_NE(root.find("viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) + "\""), std::string::npos)
      << root;
}

// The "d" of the first <path> drawn with stroke colour `rgb` (as Cairo writes it, e.g. "100%,0%,0%").
std::string path_with_stroke(const std::string& svg, const std::string& rgb) {
  const std::size_t style = svg.find("stroke:rgb(" + rgb + ")");
  if (style == std::string::npos) {
    return "";
  }
  const std::size_t tag = svg.rfind("<path", style);
  const std::size_t d = svg.find(" d=\"", tag);
  const std::size_t end = svg.find('"', d + 4);
  return svg.substr(d + 4, end - d - 4);
}

std::size_t count_moves(const std::string& d) {
  std::size_t n = 0;
  for (const char c : d) {
    n += c == 'M' ? 1 : 0;
  }
  return n;
}

Series red_series(std::vector<double> x, std::vector<double> y) {
  Series s;
  s.label = "red";
  s.x = std::move(x);
  s.y = std::move(y);
  s.colour = Rgb{1.0, 0.0, 0.0};
  return s;
}

LinePlot albedo_plot() {
  LinePlot plot;
  plot.title = "Directional albedo";
  plot.x.label = "incidence angle (degrees)";
  plot.y.label = "albedo";
  for (const double n : {1.0, 10.0, 100.0}) {
    Series s;
    s.label = "phong n = " + std::to_string(static_cast<int>(n));
    for (int i = 0; i <= 90; i += 2) {
      s.x.push_back(i);
      s.y.push_back(std::pow(std::cos(i * 3.141592653589793 / 180.0), 1.0 / n));
    }
    plot.series.push_back(s);
  }
  plot.lines.push_back({1.0, "energy conservation", {}, true});
  return plot;
}

PolarPlot lobe_plot() {
  PolarPlot plot;
  plot.title = "Lobe at 40 degrees";
  plot.radius_label = "f_r cos (1/sr)";
  Series s;
  s.label = "blinn-phong";
  for (int i = -90; i <= 90; ++i) {
    const double t = i * 3.141592653589793 / 180.0;
    s.x.push_back(t);
    s.y.push_back(std::pow(std::max(0.0, std::cos(t - 0.7)), 32.0) * std::cos(t) + 0.01);
  }
  plot.series.push_back(s);
  plot.rays = {{-0.7, "incident"}, {0.7, "mirror"}};
  return plot;
}

std::string error_of(const Result<std::vector<char>>& r) { return r ? std::string("(no error)") : r.error().message; }

// ---- files of the requested kind and size ----

TEST(Plot, PngHasTheSignatureAndTheRequestedSize) {
  for (const auto& [w, h] : {std::pair{800, 600}, std::pair{123, 457}, std::pair{64, 64}, std::pair{1500, 300}}) {
    SCOPED_TRACE(std::to_string(w) + " x " + std::to_string(h));
    const auto line = render_plot(albedo_plot(), PlotFormat::png, w, h);
    ASSERT_TRUE(line) << error_of(line);
    expect_png_of_size(*line, w, h);
    const auto polar = render_plot(lobe_plot(), PlotFormat::png, w, h);
    ASSERT_TRUE(polar) << error_of(polar);
    expect_png_of_size(*polar, w, h);
  }
}

TEST(Plot, SvgIsWellFormedXmlOfTheRequestedSize) {
  for (const auto& [w, h] : {std::pair{800, 600}, std::pair{321, 1234}, std::pair{8192, 64}}) {
    SCOPED_TRACE(std::to_string(w) + " x " + std::to_string(h));
    const auto line = render_plot(albedo_plot(), PlotFormat::svg, w, h);
    ASSERT_TRUE(line) << error_of(line);
    expect_svg_of_size(*line, w, h);
    const auto polar = render_plot(lobe_plot(), PlotFormat::svg, w, h);
    ASSERT_TRUE(polar) << error_of(polar);
    expect_svg_of_size(*polar, w, h);
  }
}

TEST(Plot, TheXmlCheckerRejectsWhatIsNotWellFormed) {
  EXPECT_EQ(xml_problem("<a><b/><c x=\"1>2\">t &amp; u</c></a>", nullptr), "");
  EXPECT_NE(xml_problem("<a><b></c></a>", nullptr), "");  // an end tag of another name
  EXPECT_NE(xml_problem("<a><b></a>", nullptr), "");
  EXPECT_NE(xml_problem("<a>", nullptr), "");
  EXPECT_NE(xml_problem("<a>x & y</a>", nullptr), "");
  EXPECT_NE(xml_problem("<a/><b/>", nullptr), "");
}

TEST(Plot, SvgCarriesTheTitleAxisLabelsAndLegendLabelsAsText) {
  LinePlot plot = albedo_plot();
  plot.title = "Albedo <phong> & \"friends\"";  // escaped, and the file stays well-formed
  const auto bytes = render_plot(plot, PlotFormat::svg);
  ASSERT_TRUE(bytes) << error_of(bytes);
  const std::string svg = text_of(*bytes);
  EXPECT_EQ(xml_problem(svg, nullptr), "");
  EXPECT_NE(svg.find("<title>Albedo &lt;phong&gt; &amp; &quot;friends&quot;</title>"), std::string::npos);
  EXPECT_NE(svg.find("incidence angle (degrees)"), std::string::npos);
  EXPECT_NE(svg.find("albedo"), std::string::npos);
  EXPECT_NE(svg.find("phong n = 1\n"), std::string::npos);
  EXPECT_NE(svg.find("phong n = 100"), std::string::npos);
  EXPECT_NE(svg.find("energy conservation"), std::string::npos);

  const auto polar = render_plot(lobe_plot(), PlotFormat::svg);
  ASSERT_TRUE(polar) << error_of(polar);
  const std::string psvg = text_of(*polar);
  for (const char* text : {"<title>Lobe at 40 degrees</title>", "f_r cos (1/sr)", "blinn-phong", "incident", "mirror"}) {
    EXPECT_NE(psvg.find(text), std::string::npos) << text;
  }
}

// ---- deterministic ----

TEST(Plot, SameInputGivesTheSameBytes) {
  for (const PlotFormat format : {PlotFormat::svg, PlotFormat::png}) {
    const auto a = render_plot(albedo_plot(), format);
    const auto b = render_plot(albedo_plot(), format);
    const auto c = render_plot(lobe_plot(), format);
    const auto d = render_plot(lobe_plot(), format);
    ASSERT_TRUE(a && b && c && d);
    EXPECT_EQ(*a, *b);  // in SVG this needs Cairo's process-wide surface ids renumbered
    EXPECT_EQ(*c, *d);
    EXPECT_NE(*a, *c);
  }
}

TEST(Plot, SvgHasNoTimestampOrProcessCounter) {
  const auto bytes = render_plot(albedo_plot(), PlotFormat::svg);
  ASSERT_TRUE(bytes);
  const std::string svg = text_of(*bytes);
  EXPECT_NE(svg.find("id=\"surface1\""), std::string::npos);
  EXPECT_EQ(svg.find("surface2"), std::string::npos);
  EXPECT_EQ(svg.find("CreationDate"), std::string::npos);
  EXPECT_EQ(svg.find("<metadata"), std::string::npos);
}

TEST(Plot, ThreadsRenderTheSameBytesAsOneThread) {
  const auto expected = render_plot(albedo_plot(), PlotFormat::png);
  ASSERT_TRUE(expected);
  std::vector<std::vector<char>> results(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < results.size(); ++t) {
    threads.emplace_back([&results, t] {
      const auto r = render_plot(albedo_plot(), PlotFormat::png);
      if (r) {
        results[t] = *r;
      }
    });
  }
  for (auto& thread : threads) {
    thread.join();
  }
  for (const auto& r : results) {
    EXPECT_EQ(r, *expected);
  }
}

// ---- data rules: NaN gaps, log axes, clipping ----

TEST(Plot, NanBreaksTheLineIntoSegments) {
  LinePlot plot;
  plot.series.push_back(red_series({0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4, 5}));
  const auto whole = render_plot(plot, PlotFormat::svg);
  ASSERT_TRUE(whole) << error_of(whole);
  EXPECT_EQ(count_moves(path_with_stroke(text_of(*whole), "100%,0%,0%")), 1u);

  plot.series[0].y[2] = nan;
  const auto broken = render_plot(plot, PlotFormat::svg);
  ASSERT_TRUE(broken) << error_of(broken);
  EXPECT_EQ(count_moves(path_with_stroke(text_of(*broken), "100%,0%,0%")), 2u);

  plot.series[0].x[4] = nan;  // a NaN x is a gap too: 0-1 is a line, 3 and 5 are single points, drawn as dots
  const auto dots = render_plot(plot, PlotFormat::svg);
  ASSERT_TRUE(dots) << error_of(dots);
  const std::string svg = text_of(*dots);
  EXPECT_EQ(count_moves(path_with_stroke(svg, "100%,0%,0%")), 1u);
  EXPECT_NE(svg.find("fill:rgb(100%,0%,0%)"), std::string::npos);
}

TEST(Plot, NonPositiveValuesOnALogAxisAreSkippedAndBreakTheLine) {
  LinePlot plot;
  plot.y.log = true;
  plot.series.push_back(red_series({0, 1, 2, 3, 4, 5}, {1, 10, 0, -5, 100, 1000}));
  const auto bytes = render_plot(plot, PlotFormat::svg);
  ASSERT_TRUE(bytes) << error_of(bytes);
  EXPECT_EQ(count_moves(path_with_stroke(text_of(*bytes), "100%,0%,0%")), 2u);  // 1-10 and 100-1000
}

TEST(Plot, FarAwayPointsAreClippedBeforeCairoSeesThem) {
  LinePlot plot;
  plot.x.min = 0.0;
  plot.x.max = 1.0;
  plot.y.min = 0.0;
  plot.y.max = 1.0;
  plot.series.push_back(red_series({0.0, 0.5, 1.0}, {0.5, 1e300, 0.5}));
  const auto bytes = render_plot(plot, PlotFormat::svg);
  ASSERT_TRUE(bytes) << error_of(bytes);
  const std::string d = path_with_stroke(text_of(*bytes), "100%,0%,0%");
  ASSERT_FALSE(d.empty());
  std::size_t numbers = 0;
  for (std::size_t i = 0; i < d.size();) {
    if (std::isdigit(static_cast<unsigned char>(d[i])) != 0 || d[i] == '-') {
      std::size_t used = 0;
      const double v = std::stod(d.substr(i), &used);
      EXPECT_GT(v, -50.0);  // Cairo's 24.8 fixed point would wrap coordinates beyond 2^23
      EXPECT_LT(v, 850.0);
      ++numbers;
      i += used;
    } else {
      ++i;
    }
  }
  EXPECT_GE(numbers, 8u);  // two segments, each a move and a line
}

TEST(Plot, AxisRangesFromTheCallerAreKept) {
  LinePlot plot;
  plot.x.min = -0.5;
  plot.x.max = 2.5;
  plot.series.push_back(red_series({0, 1, 2}, {3, 1, 2}));
  EXPECT_TRUE(render_plot(plot, PlotFormat::png));
  plot.series[0].y = {nan, nan, nan};  // nothing to draw: fine while both y ends are given
  plot.y.min = 0.0;
  plot.y.max = 1.0;
  EXPECT_TRUE(render_plot(plot, PlotFormat::png));
}

TEST(Plot, SinglePointsAndConstantSeriesRender) {
  LinePlot plot;
  plot.series.push_back(red_series({1.0}, {2.0}));
  EXPECT_TRUE(render_plot(plot, PlotFormat::png));
  plot.series[0] = red_series({0, 1, 2}, {0, 0, 0});
  EXPECT_TRUE(render_plot(plot, PlotFormat::svg));
  plot.y.log = true;
  plot.series[0] = red_series({0, 1, 2}, {5, 5, 5});
  EXPECT_TRUE(render_plot(plot, PlotFormat::svg));
}

TEST(Plot, PolarLogRadiusPutsZeroAtTheCentre) {
  PolarPlot plot = lobe_plot();
  plot.log_radius = true;
  plot.series[0].y[0] = 0.0;  // at -90 degrees
  plot.series[0].colour = Rgb{1.0, 0.0, 0.0};
  const auto svg = render_plot(plot, PlotFormat::svg, 800, 600);
  ASSERT_TRUE(svg) << error_of(svg);
  const std::string d = path_with_stroke(text_of(*svg), "100%,0%,0%");
  EXPECT_EQ(d.rfind("M 400 ", 0), 0u) << d.substr(0, 40);  // the centre is at x = width / 2
  EXPECT_TRUE(render_plot(plot, PlotFormat::png));
  plot.log_floor_decades = 2.5;
  plot.radius_max = 0.3;
  EXPECT_TRUE(render_plot(plot, PlotFormat::svg));
}

TEST(Plot, PaletteHasEightDistinctColoursThenRepeats) {
  std::set<std::tuple<double, double, double>> colours;
  for (std::size_t i = 0; i < plot_palette_size; ++i) {
    const Rgb c = plot_palette(i);
    colours.insert({c.r, c.g, c.b});
    EXPECT_GE(c.min_component(), 0.0);
    EXPECT_LE(c.max_component(), 1.0);
  }
  EXPECT_EQ(colours.size(), plot_palette_size);
  EXPECT_EQ(plot_palette(9).r, plot_palette(1).r);
  EXPECT_NEAR(plot_palette(0).b, std::pow((178.0 / 255.0 + 0.055) / 1.055, 2.4), 1e-12);  // linear, from sRGB
}

// ---- files ----

TEST(Plot, FormatComesFromTheExtension) {
  EXPECT_EQ(*plot_format_from_path("a/b.svg"), PlotFormat::svg);
  EXPECT_EQ(*plot_format_from_path("b.PNG"), PlotFormat::png);
  const auto jpg = plot_format_from_path("out/plot.jpg");
  ASSERT_FALSE(jpg);
  EXPECT_NE(jpg.error().message.find("'out/plot.jpg'"), std::string::npos) << jpg.error().message;
  EXPECT_NE(jpg.error().message.find("unknown extension '.jpg'"), std::string::npos) << jpg.error().message;
  EXPECT_FALSE(plot_format_from_path("plot"));
}

TEST(Plot, WritePlotWritesTheRenderedBytes) {
  const fs::path dir = fs::path(testing::TempDir()) / "shadelab_plot_test";
  fs::create_directories(dir);
  const auto read = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  const fs::path svg = dir / "albedo.svg";
  ASSERT_TRUE(write_plot(albedo_plot(), svg, 640, 480));
  EXPECT_EQ(read(svg), *render_plot(albedo_plot(), PlotFormat::svg, 640, 480));
  const fs::path png = dir / "lobe.PNG";
  ASSERT_TRUE(write_plot(lobe_plot(), png));
  expect_png_of_size(read(png), 800, 600);

  const fs::path jpg = dir / "lobe.jpg";
  const auto bad = write_plot(lobe_plot(), jpg);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("unknown extension"), std::string::npos);
  EXPECT_FALSE(fs::exists(jpg));
  const auto missing_dir = write_plot(lobe_plot(), dir / "no" / "such" / "dir.png");
  EXPECT_FALSE(missing_dir);
  fs::remove_all(dir);
}

// ---- errors ----

struct ErrorCase {
  const char* name;
  LinePlot plot;
  const char* expected;  // a part of the message
};

TEST(Plot, BadLinePlotInputGivesAnErrorNamingTheProblem) {
  std::vector<ErrorCase> cases;
  const LinePlot good = albedo_plot();
  {
    LinePlot p = good;
    p.series.clear();
    cases.push_back({"no series", p, "line plot 'Directional albedo': no series to draw"});
  }
  {
    LinePlot p = good;
    p.series[1].x.clear();
    p.series[1].y.clear();
    cases.push_back({"empty series", p, "series 2 'phong n = 10' has no points"});
  }
  {
    LinePlot p = good;
    p.series[0].y.pop_back();
    cases.push_back({"size mismatch", p, "has 46 x values but 45 y values"});
  }
  {
    LinePlot p = good;
    p.series[2].y[3] = inf;
    cases.push_back({"inf y", p, "series 3 'phong n = 100': point 3 is infinite (y)"});
  }
  {
    LinePlot p = good;
    p.series[0].x[0] = -inf;
    cases.push_back({"inf x", p, "point 0 is infinite (x)"});
  }
  {
    LinePlot p = good;
    p.series[0].width = 0.0;
    cases.push_back({"width", p, "line width"});
  }
  {
    LinePlot p = good;
    p.series[0].colour = Rgb{nan, 0.0, 0.0};
    cases.push_back({"colour", p, "colour is not finite"});
  }
  {
    LinePlot p = good;
    p.x.min = 5.0;
    p.x.max = 5.0;
    cases.push_back({"min = max", p, "x axis: min 5 is not below max 5"});
  }
  {
    LinePlot p = good;
    p.y.max = nan;
    cases.push_back({"nan max", p, "y axis max is not finite"});
  }
  {
    LinePlot p = good;
    p.x.log = true;
    p.x.min = 0.0;
    cases.push_back({"log min", p, "x axis min = 0 is not > 0 on a log axis"});
  }
  {
    LinePlot p = good;
    for (Series& s : p.series) {
      s.y.assign(s.y.size(), nan);
    }
    p.lines.clear();
    cases.push_back({"all nan", p, "x axis: no data point can be drawn (each has a NaN coordinate)"});
  }
  {
    LinePlot p = good;
    p.y.log = true;
    for (Series& s : p.series) {
      s.y.assign(s.y.size(), -1.0);
    }
    p.lines.clear();
    cases.push_back({"all negative on log", p, "(each has a NaN coordinate, or one <= 0 on a log axis)"});
  }
  {
    LinePlot p = good;
    p.lines[0].y = inf;
    cases.push_back({"line inf", p, "reference line 1 y is not finite"});
  }
  {
    LinePlot p = good;
    p.title = "bad \xC3\x28 utf-8";
    cases.push_back({"utf-8 title", p, "title is not valid UTF-8"});
  }
  {
    LinePlot p = good;
    p.x.label = "\xED\xA0\x80";  // a UTF-16 surrogate encoded in UTF-8
    cases.push_back({"utf-8 label", p, "x axis label is not valid UTF-8"});
  }
  {
    LinePlot p = good;
    p.series[0].label = "\xF0\x9F";  // truncated sequence
    cases.push_back({"utf-8 series", p, "the label of series 1 is not valid UTF-8"});
  }
  for (const ErrorCase& c : cases) {
    SCOPED_TRACE(c.name);
    const auto r = render_plot(c.plot, PlotFormat::png);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find(c.expected), std::string::npos) << r.error().message;
    EXPECT_EQ(r.error().message.find('\n'), std::string::npos);
  }
}

TEST(Plot, SizeOutOfRangeIsAnError) {
  for (const auto& [w, h] : {std::pair{63, 600}, std::pair{800, 8193}, std::pair{0, 0}, std::pair{-5, 100}}) {
    const auto line = render_plot(albedo_plot(), PlotFormat::png, w, h);
    ASSERT_FALSE(line);
    EXPECT_NE(line.error().message.find("is out of range [64, 8192] pixels"), std::string::npos)
        << line.error().message;
    EXPECT_FALSE(render_plot(lobe_plot(), PlotFormat::svg, w, h));
  }
  EXPECT_TRUE(render_plot(albedo_plot(), PlotFormat::svg, 64, 8192));
}

TEST(Plot, BadPolarPlotInputGivesAnErrorNamingTheProblem) {
  const auto expect_error = [](const PolarPlot& p, const std::string& expected) {
    const auto r = render_plot(p, PlotFormat::svg);
    ASSERT_FALSE(r) << expected;
    EXPECT_NE(r.error().message.find(expected), std::string::npos) << r.error().message;
  };
  PolarPlot p = lobe_plot();
  p.series[0].y[10] = -0.5;
  expect_error(p, "polar plot 'Lobe at 40 degrees': series 1 'blinn-phong': point 10 has a negative radius");
  p = lobe_plot();
  p.series[0].x[5] = inf;
  expect_error(p, "point 5 is infinite (x)");
  p = lobe_plot();
  p.log_floor_decades = 0.0;
  expect_error(p, "log_floor_decades");
  p.log_floor_decades = 31.0;
  expect_error(p, "log_floor_decades");
  p = lobe_plot();
  p.radius_max = -1.0;
  expect_error(p, "radius_max");
  p = lobe_plot();
  p.rays[1].angle = nan;
  expect_error(p, "ray 2 angle is not finite");
  p = lobe_plot();
  p.series.clear();
  expect_error(p, "no series to draw");
  p = lobe_plot();
  p.title.clear();
  p.series[0].x.pop_back();
  expect_error(p, "polar plot: series 1 'blinn-phong' has 180 x values but 181 y values");
  p = lobe_plot();
  p.radius_label = "\xFF";
  expect_error(p, "radius label is not valid UTF-8");
}

TEST(Plot, PolarNanIsAGapAndAnglesBeyondNinetyDegreesAreClipped) {
  PolarPlot p = lobe_plot();
  p.series[0].y[100] = nan;
  p.series[0].x.push_back(3.0);  // below the horizon: clipped away, not an error
  p.series[0].y.push_back(0.5);
  EXPECT_TRUE(render_plot(p, PlotFormat::png));
}

}  // namespace
}  // namespace shadelab
