// shadelab plot lobe | albedo | fv | zoo: BRDF charts as SVG or PNG (plot module, Cairo), with the data behind
// them as CSV (--csv FILE) and JSON (--json, on stdout). The data comes from analysis/plot_data.h; this file
// only turns it into charts and files. docs/plots.md ("Gallery") shows each chart and says what it draws.
#include <fmt/core.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli_common.h"
#include "shadelab/analysis/plot_data.h"
#include "shadelab/core/constants.h"
#include "shadelab/image/image_io.h"
#include "shadelab/plot/plot.h"

namespace shadelab::cli {

namespace {

// Options every chart has.
struct ChartOptions {
  std::string out;
  std::string size = "800x600";
  std::string csv;
  std::string title;
  bool json = false;
};

struct ChartSize {
  int width = 800;
  int height = 600;
};

// "WIDTHxHEIGHT" (digits, x, digits) within the plot module's limits.
ChartSize parse_size(const std::string& text) {
  const auto x = text.find_first_of("xX");
  const auto digits = [](const std::string& s) {
    return !s.empty() && s.size() <= 6 && s.find_first_not_of("0123456789") == std::string::npos;
  };
  if (x == std::string::npos || !digits(text.substr(0, x)) || !digits(text.substr(x + 1))) {
    throw UsageError("--size: expected WIDTHxHEIGHT in pixels, e.g. 800x600, got '" + text + "'");
  }
  const ChartSize s{std::stoi(text.substr(0, x)), std::stoi(text.substr(x + 1))};
  if (s.width < plot_min_size || s.width > plot_max_size || s.height < plot_min_size || s.height > plot_max_size) {
    throw UsageError(
        fmt::format("--size: {} x {} is outside [{}, {}] pixels", s.width, s.height, plot_min_size, plot_max_size));
  }
  return s;
}

// Checked before any work: the size, and that the output's extension is one the plot module writes.
ChartSize check_chart_options(const ChartOptions& o) {
  const ChartSize size = parse_size(o.size);
  auto format = plot_format_from_path(o.out);
  if (!format) throw UsageError("--out: " + format.error().message);
  if (!o.csv.empty() && std::filesystem::is_directory(o.csv)) {
    throw UsageError("--csv: '" + o.csv + "' is a directory");
  }
  std::vector<NamedPath> outputs{{"--out", o.out}};
  if (!o.csv.empty()) outputs.push_back({"--csv", o.csv});
  check_outputs({}, outputs);  // writable, and not one file twice
  return size;
}

// A CSV field: quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

// Shortest round-trip text of a number (fmt's default for double).
std::string num(double v) { return fmt::format("{}", v); }

// The chart and its --csv data are one output set (issue 40, finding 7): both replaced together or neither.
template <typename Plot>
void write_chart(const Plot& plot, const ChartOptions& o, const ChartSize& size, const std::string& csv) {
  const PlotFormat format = unwrap(plot_format_from_path(o.out));
  std::vector<std::pair<std::filesystem::path, std::vector<char>>> files;
  files.emplace_back(o.out, unwrap(render_plot(plot, format, size.width, size.height)));
  if (!o.csv.empty()) files.emplace_back(o.csv, std::vector<char>(csv.begin(), csv.end()));
  unwrap(write_files_atomically(files));
}

nlohmann::json params_json(const ParamAssignments& params) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, value] : params) j[name] = value;
  return j;
}

std::string params_text(const ParamAssignments& params) {
  std::string out;
  for (const auto& [name, value] : params) out += (out.empty() ? "" : ";") + name + "=" + value;
  return out;
}

struct BuiltModel {
  PlotModel spec;
  BrdfPtr brdf;
};

std::vector<BuiltModel> build_models(const std::vector<std::string>& models, const std::vector<std::string>& params) {
  std::vector<BuiltModel> out;
  for (auto& m : unwrap(assign_model_params(models, params))) {
    BrdfPtr f = unwrap(make_brdf(m.model, m.params));
    out.push_back({std::move(m), std::move(f)});
  }
  return out;
}

PlotChannel parse_channel(const std::string& text) {
  auto c = parse_plot_channel(text);
  if (!c) throw UsageError("--channel: " + c.error().message);
  return *c;
}

// "0.02" -> "0.02", 45 -> "45": numbers in titles and legends.
std::string short_num(double v) { return fmt::format("{:g}", v); }

// ---- lobe ----

struct LobeCliOptions {
  ChartOptions chart;
  std::vector<std::string> models;
  std::vector<std::string> params;
  double theta_in = 45.0;
  bool log = false;
  bool cos = false;
  double decades = 4.0;
  std::string fixed = "light";
  std::string channel = "luminance";
  int samples = 721;
};

void run_lobe(const LobeCliOptions& o) {
  const ChartSize size = check_chart_options(o.chart);
  if (!std::isfinite(o.theta_in) || o.theta_in < 0.0 || o.theta_in >= 90.0) {
    throw UsageError(fmt::format("--theta-in: {} is out of range [0, 90) degrees", o.theta_in));
  }
  if (o.samples < 3 || o.samples > 100001) {
    throw UsageError(fmt::format("--samples: {} is out of range [3, 100001]", o.samples));
  }
  if (!std::isfinite(o.decades) || o.decades <= 0.0 || o.decades > 30.0) {
    throw UsageError(fmt::format("--decades: {} is out of range (0, 30]", o.decades));
  }
  LobeOptions lo;
  lo.theta_in_deg = o.theta_in;
  lo.times_cos = o.cos;
  lo.samples = o.samples;
  if (o.fixed != "light" && o.fixed != "viewer") {
    throw UsageError("--fixed: '" + o.fixed + "' is not one of light | viewer");
  }
  lo.fixed = o.fixed == "light" ? LobeFixed::light : LobeFixed::viewer;
  const PlotChannel channel = parse_channel(o.channel);
  const auto models = build_models(o.models, o.params);
  work_begins();

  const bool light_fixed = lo.fixed == LobeFixed::light;
  const std::string fixed_name = light_fixed ? "light" : "viewer";
  const std::string swept = light_fixed ? "θo" : "θi";
  const std::string quantity = o.cos ? "f_r cos " + swept : "f_r";
  const Vec3 fixed_direction = in_plane_direction(-o.theta_in);

  PolarPlot plot;
  plot.title = o.chart.title.empty() ? fmt::format("In-plane lobe, {} at {}° ({}{})", fixed_name, short_num(o.theta_in),
                                                   quantity, o.log ? ", log" : "")
                                     : o.chart.title;
  plot.log_radius = o.log;
  plot.log_floor_decades = o.decades;
  plot.radius_label = fmt::format("{} (1/sr, {})", quantity, channel_name(channel));
  if (o.theta_in == 0.0) {
    plot.rays.push_back({0.0, fixed_name + " = mirror"});
  } else {
    plot.rays.push_back({deg_to_rad(-o.theta_in), fixed_name});
    plot.rays.push_back({deg_to_rad(o.theta_in), "mirror"});
  }

  nlohmann::json series = nlohmann::json::array();
  std::string csv = "model,params,label,angle_deg,r,g,b,luminance,plotted\n";
  for (const auto& m : models) {
    const LobeCurve c = unwrap(lobe_curve(*m.brdf, lo));
    Series s;
    s.label = m.spec.label;
    nlohmann::json rgb = nlohmann::json::array();
    std::vector<double> plotted;
    for (std::size_t i = 0; i < c.angle_deg.size(); ++i) {
      const double v = channel_value(c.value[i], channel);
      s.x.push_back(deg_to_rad(c.angle_deg[i]));
      s.y.push_back(std::max(0.0, v));
      plotted.push_back(v);
      rgb.push_back(to_json(c.value[i]));
      csv += fmt::format("{},{},{},{},{},{},{},{},{}\n", m.spec.model, csv_field(params_text(m.spec.params)),
                         csv_field(m.spec.label), num(c.angle_deg[i]), num(c.value[i].r), num(c.value[i].g),
                         num(c.value[i].b), num(c.luminance[i]), num(v));
    }
    plot.series.push_back(std::move(s));
    series.push_back({{"model", m.spec.model},
                      {"params", params_json(m.spec.params)},
                      {"label", m.spec.label},
                      {"angle_deg", c.angle_deg},
                      {"rgb", rgb},
                      {"luminance", c.luminance},
                      {"plotted", plotted}});
  }
  write_chart(plot, o.chart, size, csv);
  if (o.chart.json) {
    print_json({{"plot", "lobe"},
                {"out", o.chart.out},
                {"width", size.width},
                {"height", size.height},
                {"theta_in_deg", o.theta_in},
                {"fixed", fixed_name},
                {"fixed_direction", {fixed_direction.x, fixed_direction.y, fixed_direction.z}},
                {"mirror_deg", o.theta_in},
                {"quantity", o.cos ? "f_cos" : "f"},
                {"unit", "1/sr"},
                {"channel", channel_name(channel)},
                {"log", o.log},
                {"series", series}});
  }
}

// ---- albedo ----

struct AlbedoCliOptions {
  ChartOptions chart;
  std::vector<std::string> models;
  std::vector<std::string> params;
  std::vector<double> theta;
  std::string channel = "max";
};

void run_albedo_plot(const AlbedoCliOptions& o) {
  const ChartSize size = check_chart_options(o.chart);
  for (double t : o.theta) {
    if (!std::isfinite(t) || t < 0.0 || t >= 90.0) {
      throw UsageError(fmt::format("--theta: {} is out of range [0, 90) degrees", t));
    }
  }
  const PlotChannel channel = parse_channel(o.channel);
  const auto models = build_models(o.models, o.params);
  const std::vector<double> thetas = o.theta.empty() ? default_albedo_angles() : o.theta;
  work_begins();

  LinePlot plot;
  plot.title = o.chart.title.empty() ? "Directional albedo" : o.chart.title;
  plot.x.label = "view angle θo from the normal (degrees)";
  plot.x.min = 0.0;
  plot.x.max = 90.0;
  plot.y.label = fmt::format("directional albedo ({})",
                             channel == PlotChannel::max ? "largest RGB channel" : std::string(channel_name(channel)));
  plot.y.min = 0.0;
  plot.lines.push_back({1.0, "energy conservation", std::nullopt, true});

  nlohmann::json series = nlohmann::json::array();
  std::string csv = "model,params,label,theta_deg,r,g,b,luminance,plotted,converged\n";
  for (const auto& m : models) {
    const AlbedoCurve c = unwrap(albedo_curve(*m.brdf, thetas));
    Series s;
    s.label = m.spec.label;
    s.x = c.theta_deg;
    nlohmann::json rgb = nlohmann::json::array();
    for (std::size_t i = 0; i < c.theta_deg.size(); ++i) {
      const double v = channel_value(c.albedo[i], channel);
      s.y.push_back(v);
      rgb.push_back(to_json(c.albedo[i]));
      csv += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", m.spec.model, csv_field(params_text(m.spec.params)),
                         csv_field(m.spec.label), num(c.theta_deg[i]), num(c.albedo[i].r), num(c.albedo[i].g),
                         num(c.albedo[i].b), num(c.luminance[i]), num(v), c.converged ? "true" : "false");
    }
    series.push_back({{"model", m.spec.model},
                      {"params", params_json(m.spec.params)},
                      {"label", m.spec.label},
                      {"theta_deg", c.theta_deg},
                      {"rgb", rgb},
                      {"luminance", c.luminance},
                      {"plotted", s.y},
                      {"converged", c.converged}});
    plot.series.push_back(std::move(s));
  }
  write_chart(plot, o.chart, size, csv);
  if (o.chart.json) {
    print_json({{"plot", "albedo"},
                {"out", o.chart.out},
                {"width", size.width},
                {"height", size.height},
                {"channel", channel_name(channel)},
                {"rel_tol", albedo_curve_options().quadrature.rel_tol},
                {"series", series}});
  }
}

// ---- fv ----

struct FvCliOptions {
  ChartOptions chart;
  std::vector<double> f0;
  double max_angle = 85.0;
  int samples = 171;
  bool linear = false;
};

void run_fv(const FvCliOptions& o) {
  const ChartSize size = check_chart_options(o.chart);
  for (double f : o.f0) {
    if (!std::isfinite(f) || f < 0.0 || f > 1.0) throw UsageError(fmt::format("--f0: {} is out of range [0, 1]", f));
    if (f == 0.0 && !o.linear) throw UsageError("--f0: 0 cannot be drawn on a log axis (add --linear)");
  }
  if (!std::isfinite(o.max_angle) || o.max_angle <= 0.0 || o.max_angle >= 90.0) {
    throw UsageError(fmt::format("--max-angle: {} is out of range (0, 90) degrees", o.max_angle));
  }
  if (o.samples < 2 || o.samples > 100001) {
    throw UsageError(fmt::format("--samples: {} is out of range [2, 100001]", o.samples));
  }
  const std::vector<double> f0s = o.f0.empty() ? default_fv_f0() : o.f0;
  work_begins();

  LinePlot plot;
  plot.title = o.chart.title.empty() ? "Minimalist F V against Schlick F × Kelemen V" : o.chart.title;
  plot.x.label = "angle between L and H, θd (degrees)";
  plot.x.min = 0.0;
  plot.x.max = o.max_angle;
  plot.y.label = "specular factor ks F V (dimensionless)";
  plot.y.log = !o.linear;

  nlohmann::json curves = nlohmann::json::array();
  std::string csv = "f0,angle_deg,l_dot_h,minimalist,schlick_kelemen\n";
  for (std::size_t k = 0; k < f0s.size(); ++k) {
    const FvCurve c = unwrap(fv_curve(f0s[k], o.max_angle, o.samples));
    const Rgb colour = plot_palette(k);
    plot.series.push_back({fmt::format("minimalist F0 / (4 (L·H)³), F0 = {}", short_num(c.f0)), c.angle_deg,
                           c.minimalist, colour, 2.0, false});
    plot.series.push_back({fmt::format("Schlick F / (4 (L·H)²), F0 = {}", short_num(c.f0)), c.angle_deg,
                           c.schlick_kelemen, colour, 2.0, true});
    std::vector<double> lh;
    for (std::size_t i = 0; i < c.angle_deg.size(); ++i) {
      lh.push_back(std::cos(deg_to_rad(c.angle_deg[i])));
      csv += fmt::format("{},{},{},{},{}\n", num(c.f0), num(c.angle_deg[i]), num(lh.back()), num(c.minimalist[i]),
                         num(c.schlick_kelemen[i]));
    }
    curves.push_back({{"f0", c.f0},
                      {"angle_deg", c.angle_deg},
                      {"l_dot_h", lh},
                      {"minimalist", c.minimalist},
                      {"schlick_kelemen", c.schlick_kelemen}});
  }
  write_chart(plot, o.chart, size, csv);
  if (o.chart.json) {
    print_json({{"plot", "fv"},
                {"out", o.chart.out},
                {"width", size.width},
                {"height", size.height},
                {"minimalist", "F0 / (4 (L.H)^3)"},
                {"schlick_kelemen", "F_schlick(L.H, F0) / (4 (L.H)^2)"},
                {"log", !o.linear},
                {"curves", curves}});
  }
}

// ---- zoo ----

struct ZooCliOptions {
  ChartOptions chart;
  std::vector<std::string> rows;
  double n_min = 0.1;
  double n_max = 10000.0;
  int samples = 161;
  bool linear = false;
  bool relative = false;
};

// Ascii formula text from zoo.h with pi written as π.
std::string pretty(std::string text) {
  for (std::size_t p = text.find("pi"); p != std::string::npos; p = text.find("pi", p)) text.replace(p, 2, "π");
  return text;
}

void run_zoo_plot(const ZooCliOptions& o) {
  const ChartSize size = check_chart_options(o.chart);
  const bool log_ok = o.linear || o.n_min > 0.0;
  if (!std::isfinite(o.n_min) || o.n_min < 0.0 || !log_ok) {
    throw UsageError(
        fmt::format("--n-min: {} must be finite and {}", o.n_min, o.linear ? ">= 0" : "> 0 on a log axis"));
  }
  if (!std::isfinite(o.n_max) || o.n_max <= o.n_min || o.n_max > 1e6) {
    throw UsageError(fmt::format("--n-max: {} must be finite, above --n-min ({}) and at most 1e6", o.n_max, o.n_min));
  }
  if (o.samples < 2 || o.samples > 100001) {
    throw UsageError(fmt::format("--samples: {} is out of range [2, 100001]", o.samples));
  }
  const std::vector<double> n =
      o.linear ? linear_spaced(o.n_min, o.n_max, o.samples) : log_spaced(o.n_min, o.n_max, o.samples);
  work_begins();
  auto curves = zoo_curves(n, o.rows);
  if (!curves) throw UsageError("--row: " + curves.error().message);

  LinePlot plot;
  plot.title = o.chart.title.empty() ? "The Blinn-Phong normalization zoo" : o.chart.title;
  plot.x.label = "specular exponent n";
  plot.x.log = !o.linear;
  plot.x.min = o.n_min;
  plot.x.max = o.n_max;
  plot.y.label = o.relative ? "bound / closed form" : "normalization factor (1/sr)";
  plot.y.log = !o.linear && !o.relative;
  if (o.relative && o.chart.title.empty()) plot.title = "Zoo bounds relative to the closed form";

  nlohmann::json rows = nlohmann::json::array();
  std::string csv = "model,table,n,closed_form,lower,upper\n";
  for (std::size_t k = 0; k < curves->size(); ++k) {
    const ZooCurve& c = (*curves)[k];
    const Rgb colour = plot_palette(k);
    if (o.relative) {
      // Each bound divided by the row's closed form: how far the bounds are from exact, against n.
      if (c.lower && c.upper) {
        std::vector<double> lo;
        std::vector<double> up;
        for (std::size_t i = 0; i < c.n.size(); ++i) {
          lo.push_back((*c.lower)[i] / c.closed_form[i]);
          up.push_back((*c.upper)[i] / c.closed_form[i]);
        }
        plot.series.push_back({fmt::format("{} lower: {}", c.model, pretty(c.lower_text)), c.n, lo, colour, 2.0, true});
        plot.series.push_back(
            {fmt::format("{} upper: {}", c.model, pretty(c.upper_text)), c.n, up, colour, 2.0, false});
      }
    } else {
      // Two pairs of rows share a closed form (phong and blinn-phong-ndf, phong-modified and
      // blinn-phong-heightfield): RDF rows are drawn wide and NDF rows narrow on top, so both stay visible.
      const double width = c.table == "RDF" ? 4.0 : 1.5;
      plot.series.push_back(
          {fmt::format("{}: {}", c.model, pretty(c.closed_form_text)), c.n, c.closed_form, colour, width, false});
    }
    if (!o.relative && c.lower && c.upper) {
      plot.series.push_back({fmt::format("{} bounds: {} .. {}", c.model, pretty(c.lower_text), pretty(c.upper_text)),
                             c.n, *c.lower, colour, 1.0, true});
      plot.series.push_back({"", c.n, *c.upper, colour, 1.0, true});
    }
    for (std::size_t i = 0; i < c.n.size(); ++i) {
      csv += fmt::format("{},{},{},{},{},{}\n", c.model, c.table, num(c.n[i]), num(c.closed_form[i]),
                         c.lower ? num((*c.lower)[i]) : "", c.upper ? num((*c.upper)[i]) : "");
    }
    nlohmann::json j = {{"model", c.model},
                        {"table", c.table},
                        {"closed_form_text", c.closed_form_text},
                        {"n", c.n},
                        {"closed_form", c.closed_form}};
    j["lower"] = c.lower ? nlohmann::json(*c.lower) : nlohmann::json(nullptr);
    j["upper"] = c.upper ? nlohmann::json(*c.upper) : nlohmann::json(nullptr);
    j["lower_text"] = c.lower_text;
    j["upper_text"] = c.upper_text;
    rows.push_back(std::move(j));
  }
  if (o.relative) {
    if (plot.series.empty())
      throw UsageError("--relative: none of the rows drawn has bounds (blinn-phong, blinn-phong-modified)");
    plot.lines.push_back({1.0, "closed form", std::nullopt, true});
  }
  write_chart(plot, o.chart, size, csv);
  if (o.chart.json) {
    print_json({{"plot", "zoo"},
                {"relative", o.relative},
                {"out", o.chart.out},
                {"width", size.width},
                {"height", size.height},
                {"log", !o.linear},
                {"rows", rows}});
  }
}

// ---- registration ----

void add_chart_options(CLI::App* sub, ChartOptions& o, const std::string& default_out) {
  o.out = default_out;
  sub->add_option("--out", o.out, "chart file, .svg or .png")->capture_default_str();
  sub->add_option("--size", o.size, "chart size WIDTHxHEIGHT in pixels, each in [64, 8192]")->capture_default_str();
  sub->add_option("--csv", o.csv, "also write the data behind the chart as CSV");
  sub->add_option("--title", o.title, "chart title (default: one that says what is drawn)");
  sub->add_flag("--json", o.json, "print the data behind the chart as JSON");
}

void add_model_args(CLI::App* sub, std::vector<std::string>& models, std::vector<std::string>& params) {
  sub->add_option("MODEL", models, "one or more models (see brdf list), drawn in one chart")->required();
  sub->add_option("-p,--param", params,
                  "NAME=VALUE for every model that has NAME; MODEL:NAME=VALUE for the models of that name; "
                  "K:NAME=VALUE for the K-th model (1-based); repeatable")
      ->allow_extra_args(false);  // one value per --param, so MODELs may follow it
}

void add_plot_command(CLI::App& app, Command& command) {
  auto* plot = app.add_subcommand("plot", "charts of BRDFs as SVG or PNG: lobe, albedo, fv, zoo");
  plot->require_subcommand(1);

  auto lobe = std::make_shared<LobeCliOptions>();
  auto* l = plot->add_subcommand("lobe", "polar chart of the in-plane lobe, several models overlaid");
  add_model_args(l, lobe->models, lobe->params);
  l->add_option("--theta-in", lobe->theta_in, "angle of the fixed direction from the normal, degrees in [0, 90)")
      ->capture_default_str();
  l->add_flag("--log", lobe->log, "log radius (--decades decades below the top decade)");
  l->add_option("--decades", lobe->decades, "decades shown with --log, in (0, 30]")->capture_default_str();
  l->add_flag("--cos", lobe->cos, "multiply by the cosine of the swept direction");
  l->add_option("--fixed", lobe->fixed, "which direction is fixed at --theta-in: light (sweep the viewer) or viewer")
      ->capture_default_str();
  l->add_option("--channel", lobe->channel, "what is drawn: luminance, max, r, g or b")->capture_default_str();
  l->add_option("--samples", lobe->samples, "angles over [-90, 90] degrees")->capture_default_str();
  add_chart_options(l, lobe->chart, "lobe.svg");
  l->callback([lobe, &command] { command.run = [lobe] { run_lobe(*lobe); }; });

  auto albedo = std::make_shared<AlbedoCliOptions>();
  auto* a = plot->add_subcommand("albedo", "directional albedo against the angle, with the energy-conservation line");
  add_model_args(a, albedo->models, albedo->params);
  a->add_option("--theta", albedo->theta, "view angle in degrees, [0, 90); repeatable (default 0, 1, ..., 89)")
      ->allow_extra_args(false);
  a->add_option("--channel", albedo->channel, "what is drawn: max, luminance, r, g or b")->capture_default_str();
  add_chart_options(a, albedo->chart, "albedo.svg");
  a->callback([albedo, &command] { command.run = [albedo] { run_albedo_plot(*albedo); }; });

  auto fv = std::make_shared<FvCliOptions>();
  auto* f = plot->add_subcommand("fv", "the zoo article's figure: minimalist F V against Schlick F with Kelemen V");
  f->add_option("--f0", fv->f0, "specular reflectances F0 in [0, 1] (default 0.02 0.05 0.8)");
  f->add_option("--max-angle", fv->max_angle, "largest angle between L and H, degrees in (0, 90)")
      ->capture_default_str();
  f->add_option("--samples", fv->samples, "angles from 0 to --max-angle")->capture_default_str();
  f->add_flag("--linear", fv->linear, "linear y axis instead of log");
  add_chart_options(f, fv->chart, "fv.svg");
  f->callback([fv, &command] { command.run = [fv] { run_fv(*fv); }; });

  auto zoo = std::make_shared<ZooCliOptions>();
  auto* z = plot->add_subcommand("zoo", "each normalization factor of the zoo against the exponent, with its bounds");
  z->add_option("--row", zoo->rows, "zoo rows to draw (default all six; see shadelab zoo)");
  z->add_option("--n-min", zoo->n_min, "smallest exponent")->capture_default_str();
  z->add_option("--n-max", zoo->n_max, "largest exponent")->capture_default_str();
  z->add_option("--samples", zoo->samples, "exponents from --n-min to --n-max")->capture_default_str();
  z->add_flag("--linear", zoo->linear, "linear axes instead of log-log");
  z->add_flag("--relative", zoo->relative, "draw each bound divided by its closed form (rows with bounds only)");
  add_chart_options(z, zoo->chart, "zoo.svg");
  z->callback([zoo, &command] { command.run = [zoo] { run_zoo_plot(*zoo); }; });
}

}  // namespace

const CommandRegistration registration_plot(70, add_plot_command);

}  // namespace shadelab::cli
