#include "shadelab/fit/shininess.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace shadelab {

namespace {

const char* mapping_source(const std::string& name) {
  if (name == "walter") return "Walter et al. 2007, eq. 29: alpha = sqrt(2/(n+2))";
  if (name == "cod") return "Lazarov 2013 (Call of Duty: Black Ops II): n = 8192^g, roughness = 1 - g, alpha = roughness^2";
  if (name == "godot") return "Godot (PR #17840): roughness = 1 - sqrt(1 - log2(n)/9), alpha = roughness^2";
  return "Babylon.js glTF exporter: roughness = 0.1 + 0.9 (1 - (min(n,1024)/1300)^(1/3))^3, alpha = roughness^2";
}

}  // namespace

std::vector<std::pair<std::string, std::optional<double>>> published_shininess_mappings(double n) {
  std::vector<std::pair<std::string, std::optional<double>>> out;
  // Walter et al. 2007, eq. 29: alpha_b = sqrt(2 / (n + 2)).
  out.emplace_back("walter", std::sqrt(2.0 / (n + 2.0)));
  // Lazarov 2013: n = 8192^g, so g = ln n / ln 8192; roughness = 1 - g.
  const double g = std::clamp(std::log(std::max(n, 1.0)) / std::log(8192.0), 0.0, 1.0);
  out.emplace_back("cod", (1.0 - g) * (1.0 - g));
  // Godot's Collada import: roughness = 1 - sqrt(1 - log2(n)/9), NaN beyond n = 512.
  const double s = 1.0 - std::log2(n) / 9.0;
  if (s >= 0.0 && n > 0.0) {
    const double r = 1.0 - std::sqrt(s);
    out.emplace_back("godot", r * r);
  } else {
    out.emplace_back("godot", std::nullopt);
  }
  // Babylon.js: the cubic Bezier with ordinates 1, 0.1, 0.1, 0.1 at t = (n/1300)^(1/3), n clamped to [0, 1024].
  const double t = std::cbrt(std::clamp(n, 0.0, 1024.0) / 1300.0);
  const double r = (1 - t) * (1 - t) * (1 - t) * 1.0 + 3 * (1 - t) * (1 - t) * t * 0.1 + 3 * (1 - t) * t * t * 0.1 + t * t * t * 0.1;
  out.emplace_back("babylon", r * r);
  return out;
}

Result<ShininessConversion> convert_shininess(const std::string& from, const std::string& to, double n, FitMetric metric,
                                              const FitGridOptions& grid) {
  if (from != "phong" && from != "blinn-phong" && from != "blinn-phong-modified" && from != "blinn-phong-microfacet") {
    return Error{"--from: '" + from + "' is not one of phong, blinn-phong, blinn-phong-modified, blinn-phong-microfacet"};
  }
  if (to != "ggx" && to != "beckmann") return Error{"--to: '" + to + "' is not one of ggx, beckmann"};
  if (!(n >= 1.0 && n <= 1e6)) return Error{"--n: " + std::to_string(n) + " is out of range [1, 1e6]"};
  char nbuf[32];
  std::snprintf(nbuf, sizeof nbuf, "%.17g", n);
  auto source = from == "blinn-phong-microfacet"
                    ? make_brdf("cook-torrance", {{"kd", "0"}, {"ks", "1"}, {"n", nbuf}, {"d", "blinn-phong"}, {"g", "smith"},
                                                  {"f", "none"}, {"form", "microfacet"}})
                    : make_brdf(from, {{"kd", "0"}, {"ks", "1"}, {"n", nbuf}});
  if (!source) return source.error();
  const FitData data = fit_data_from_brdf(**source, grid);

  const std::string model = to == "ggx" ? "ggx" : "cook-torrance";
  const std::string alpha_name = to == "ggx" ? "alpha" : "m";
  FitOptions o;
  o.metric = metric;
  o.free = {alpha_name};
  o.fixed = {{"kd", "0"}, {"ks", "1"}, {"f", "none"}};
  if (to == "beckmann") {
    o.fixed.insert(o.fixed.end(), {{"d", "beckmann"}, {"g", "smith"}, {"form", "microfacet"}});
  }
  o.starts = 3;
  const auto fit = fit_model(model, data, o);
  if (!fit) return fit.error();
  ShininessConversion c;
  c.from = from;
  c.to = to;
  c.n = n;
  c.metric = metric;
  c.residual = fit->residual;
  auto black = make_brdf("lambert", {{"kd", "0"}});
  if (!black) return black.error();
  const double scale = fit_residual(**black, data, metric);
  c.relative_residual = scale > 0.0 ? c.residual / scale : 0.0;
  const ModelInfo* info = find_brdf_model(model);
  double lo = 0.0, hi = 1.0;
  for (const auto& s : info->params) {
    if (s.name == alpha_name) {
      lo = s.min;
      hi = s.max;
    }
  }
  for (const auto& p : fit->params) {
    if (p.name == alpha_name) c.alpha = p.numbers[0];
  }
  const double box_lo = 0.002;  // the fitter's box for alpha and m (fit/fit.cpp)
  c.at_bound = c.alpha <= box_lo * (1 + 1e-6) || c.alpha >= 1.0 * (1 - 1e-6);
  for (const auto& [name, alpha] : published_shininess_mappings(n)) {
    ShininessMapping m;
    m.name = name;
    m.source = mapping_source(name);
    m.alpha = alpha;
    if (alpha) {
      const double a = std::clamp(*alpha, lo, std::min(hi, 1.0));
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.17g", a);
      ParamAssignments as = o.fixed;
      as.emplace_back(alpha_name, buf);
      auto b = make_brdf(model, as);
      if (!b) return b.error();
      m.residual = fit_residual(**b, data, metric);
      m.excess = c.residual > 0.0 ? m.residual / c.residual - 1.0 : 0.0;
      m.relative_residual = scale > 0.0 ? m.residual / scale : 0.0;
    }
    c.mappings.push_back(std::move(m));
  }
  return c;
}

}  // namespace shadelab
