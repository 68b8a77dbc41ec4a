#include "shadelab/analysis/plot_data.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "shadelab/analysis/zoo.h"
#include "shadelab/brdf/fresnel.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/core/constants.h"

namespace shadelab {

namespace {

// The shortest text that reads back as v, for messages.
std::string text_of(double v) {
  std::string out;
  for (int digits = 1; digits <= 17; ++digits) {
    std::ostringstream t;
    t.precision(digits);
    t << v;
    out = t.str();
    if (std::strtod(out.c_str(), nullptr) == v) break;
  }
  return out;
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

bool declares(const std::string& model, const std::string& param) {
  const ModelInfo* info = find_brdf_model(model);
  if (info == nullptr) return false;
  return std::any_of(info->params.begin(), info->params.end(), [&](const ParamSpec& p) { return p.name == param; });
}

}  // namespace

Result<std::vector<PlotModel>> assign_model_params(const std::vector<std::string>& models,
                                                   const std::vector<std::string>& params) {
  if (models.empty()) return make_error("no model given");
  std::vector<PlotModel> out;
  for (const auto& m : models) {
    if (find_brdf_model(m) == nullptr) return make_brdf(m).error();
    out.push_back({m, {}, m});
  }
  for (const auto& text : params) {
    const auto eq = text.find('=');
    const auto colon = text.find(':');
    const bool qualified = colon != std::string::npos && (eq == std::string::npos || colon < eq);
    const std::string qualifier = qualified ? text.substr(0, colon) : std::string();
    auto assignment = split_assignment(qualified ? std::string_view(text).substr(colon + 1) : std::string_view(text));
    if (!assignment) return make_error("'" + text + "': " + assignment.error().message);
    std::vector<std::size_t> targets;
    if (qualified) {
      const bool number = !qualifier.empty() &&
                          std::all_of(qualifier.begin(), qualifier.end(), [](char c) { return c >= '0' && c <= '9'; });
      if (number) {
        const std::size_t k = qualifier.size() > 6 ? 0 : static_cast<std::size_t>(std::stoul(qualifier));
        if (k < 1 || k > models.size()) {
          return make_error("'" + text + "': model number " + qualifier + " is out of range [1, " +
                            std::to_string(models.size()) + "]");
        }
        targets.push_back(k - 1);
      } else {
        for (std::size_t i = 0; i < models.size(); ++i) {
          if (models[i] == qualifier) targets.push_back(i);
        }
        if (targets.empty()) {
          return make_error("'" + text + "': '" + qualifier + "' is not one of the models given (" +
                            join_names(models) + ")");
        }
      }
    } else if (models.size() == 1) {
      targets.push_back(0);  // make_brdf names an unknown parameter of the one model
    } else {
      for (std::size_t i = 0; i < models.size(); ++i) {
        if (declares(models[i], assignment->first)) targets.push_back(i);
      }
      if (targets.empty()) {
        return make_error("'" + text + "': none of the models given (" + join_names(models) + ") has a parameter '" +
                          assignment->first + "'");
      }
    }
    for (std::size_t t : targets) {
      // A later assignment of the same parameter replaces the earlier one, in its place.
      auto& list = out[t].params;
      const auto same =
          std::find_if(list.begin(), list.end(), [&](const auto& p) { return p.first == assignment->first; });
      if (same != list.end()) {
        same->second = assignment->second;
      } else {
        list.push_back(*assignment);
      }
    }
  }
  for (auto& m : out) {
    std::string list;
    for (const auto& [name, value] : m.params) list += (list.empty() ? "" : ", ") + name + "=" + value;
    if (!list.empty()) m.label = m.model + " (" + list + ")";
  }
  return out;
}

double channel_value(const Rgb& c, PlotChannel channel) {
  switch (channel) {
    case PlotChannel::luminance:
      return luminance(c);
    case PlotChannel::max:
      return c.max_component();
    case PlotChannel::r:
      return c.r;
    case PlotChannel::g:
      return c.g;
    case PlotChannel::b:
      return c.b;
  }
  return luminance(c);
}

std::string_view channel_name(PlotChannel channel) {
  switch (channel) {
    case PlotChannel::luminance:
      return "luminance";
    case PlotChannel::max:
      return "max";
    case PlotChannel::r:
      return "r";
    case PlotChannel::g:
      return "g";
    case PlotChannel::b:
      return "b";
  }
  return "luminance";
}

Result<PlotChannel> parse_plot_channel(std::string_view text) {
  for (PlotChannel c : {PlotChannel::luminance, PlotChannel::max, PlotChannel::r, PlotChannel::g, PlotChannel::b}) {
    if (channel_name(c) == text) return c;
  }
  return make_error("channel '" + std::string(text) + "' is not one of luminance | max | r | g | b");
}

Vec3 in_plane_direction(double angle_deg) {
  const double a = deg_to_rad(angle_deg);
  return {std::sin(a), 0.0, std::cos(a)};
}

std::vector<double> linear_spaced(double first, double last, int n) {
  std::vector<double> out;
  if (n < 2) return {first};
  out.reserve(static_cast<std::size_t>(n));
  // first + (last - first) i / (n - 1) in one rounding per value, so the last value is exactly `last`.
  for (int i = 0; i < n; ++i) out.push_back(first + (last - first) * (static_cast<double>(i) / (n - 1)));
  out.back() = last;
  return out;
}

std::vector<double> log_spaced(double first, double last, int n) {
  std::vector<double> out = linear_spaced(std::log10(first), std::log10(last), n);
  for (double& v : out) v = std::pow(10.0, v);
  out.front() = first;
  out.back() = last;
  return out;
}

Result<LobeCurve> lobe_curve(const Brdf& f, const LobeOptions& options) {
  if (!std::isfinite(options.theta_in_deg) || options.theta_in_deg < 0.0 || options.theta_in_deg >= 90.0) {
    return make_error("lobe: theta_in = " + text_of(options.theta_in_deg) + " is out of range [0, 90) degrees");
  }
  if (options.samples < 3 || options.samples > 100001) {
    return make_error("lobe: samples = " + std::to_string(options.samples) + " is out of range [3, 100001]");
  }
  LobeCurve c;
  c.options = options;
  c.fixed_direction = in_plane_direction(-options.theta_in_deg);
  c.mirror_deg = options.theta_in_deg;
  c.angle_deg = linear_spaced(-90.0, 90.0, options.samples);
  c.value.reserve(c.angle_deg.size());
  c.luminance.reserve(c.angle_deg.size());
  for (double a : c.angle_deg) {
    Rgb v;
    // At +-90 degrees the swept direction lies on the horizon, where every BRDF is 0 by contract; sin(pi/2)
    // and cos(pi/2) in floating point would leave it 6e-17 above it instead.
    if (std::abs(a) < 90.0) {
      const Vec3 swept = in_plane_direction(a);
      v = options.fixed == LobeFixed::light ? f.eval(c.fixed_direction, swept) : f.eval(swept, c.fixed_direction);
      if (options.times_cos) v = v * swept.z;
    }
    c.value.push_back(v);
    c.luminance.push_back(luminance(v));
  }
  return c;
}

AlbedoOptions albedo_curve_options() {
  AlbedoOptions o;
  o.quadrature.rel_tol = 1e-8;
  return o;
}

std::vector<double> default_albedo_angles() { return linear_spaced(0.0, 89.0, 90); }

Result<AlbedoCurve> albedo_curve(const Brdf& f, const std::vector<double>& theta_deg, const AlbedoOptions& options) {
  if (theta_deg.empty()) return make_error("albedo: no angles");
  for (double t : theta_deg) {
    if (!std::isfinite(t) || t < 0.0 || t >= 90.0) {
      return make_error("albedo: theta = " + text_of(t) + " is out of range [0, 90) degrees");
    }
  }
  AlbedoCurve c;
  c.theta_deg = theta_deg;
  for (double t : theta_deg) {
    const AlbedoResult r = directional_albedo(f, deg_to_rad(t), options);
    c.albedo.push_back(r.albedo);
    c.luminance.push_back(luminance(r.albedo));
    c.converged = c.converged && r.converged;
  }
  return c;
}

// Minimalist Cook-Torrance, ks F V with ks = F0 and F V = 1/(4 (L.H)^3) (Schüler, ShaderX7 2.5; zoo article).
double fv_minimalist(double lh, double f0) { return f0 * 0.25 / (lh * lh * lh); }

// Schlick's F times Kelemen and Szirmay-Kalos' V = 1/(4 (L.H)^2) (brdf/fresnel.h, brdf/microfacet.h).
double fv_schlick_kelemen(double lh, double f0) { return F_schlick(lh, f0) * V_kelemen(lh); }

std::vector<double> default_fv_f0() { return {0.02, 0.05, 0.8}; }

Result<FvCurve> fv_curve(double f0, double max_angle_deg, int samples) {
  if (!std::isfinite(f0) || f0 < 0.0 || f0 > 1.0) {
    return make_error("fv: F0 = " + text_of(f0) + " is out of range [0, 1]");
  }
  if (!std::isfinite(max_angle_deg) || max_angle_deg <= 0.0 || max_angle_deg >= 90.0) {
    return make_error("fv: the largest angle " + text_of(max_angle_deg) + " is out of range (0, 90) degrees");
  }
  if (samples < 2 || samples > 100001) {
    return make_error("fv: samples = " + std::to_string(samples) + " is out of range [2, 100001]");
  }
  FvCurve c;
  c.f0 = f0;
  c.angle_deg = linear_spaced(0.0, max_angle_deg, samples);
  for (double a : c.angle_deg) {
    const double lh = std::cos(deg_to_rad(a));
    c.minimalist.push_back(fv_minimalist(lh, f0));
    c.schlick_kelemen.push_back(fv_schlick_kelemen(lh, f0));
  }
  return c;
}

Result<std::vector<ZooCurve>> zoo_curves(const std::vector<double>& n, const std::vector<std::string>& models) {
  if (n.empty()) return make_error("zoo: no exponents");
  std::vector<std::string> rows = models;
  if (rows.empty()) {
    for (auto name : zoo_models()) rows.emplace_back(name);
  }
  // Only the closed forms are used: a loose, short quadrature keeps zoo_row cheap.
  QuadratureOptions cheap;
  cheap.rel_tol = 1e-3;
  cheap.max_subdivisions = 8;
  std::vector<ZooCurve> out;
  for (const auto& model : rows) {
    ZooCurve c;
    c.model = model;
    for (double e : n) {
      auto row = zoo_row(model, e, cheap);
      if (!row) return row.error();
      if (c.n.empty()) {
        c.table = row->table;
        c.closed_form_text = row->closed_form_text;
        c.lower_text = row->lower_text;
        c.upper_text = row->upper_text;
        if (row->lower) c.lower.emplace();
        if (row->upper) c.upper.emplace();
      }
      c.n.push_back(e);
      c.closed_form.push_back(row->closed_form);
      if (c.lower) c.lower->push_back(row->lower.value_or(0.0));
      if (c.upper) c.upper->push_back(row->upper.value_or(0.0));
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace shadelab
