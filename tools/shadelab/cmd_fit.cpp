// shadelab fit MODEL DATA [--fix NAME=VALUE ...] [--free NAME ...] [--metric cosine-l2|cube-root|log] [--starts N]
//   [--theta-d-stride S] [--phi-d-stride S] [--phi-h N] [--json]
// Fits a model's free parameters to DATA (fit/fit.h): a MERL (.binary), RGL (.bsdf) or UTIA (.bin) file, or model:NAME[,PARAM=VALUE...] to
// fit one model to another. Prints the parameters, the residual in the metric, the directional-albedo difference
// (fit minus data, luminance) over theta and the wall time; --json prints them as an object.
#include <fmt/core.h>

#include <chrono>

#include "cli_common.h"
#include "shadelab/analysis/albedo.h"
#include "shadelab/brdf/measured.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/brdf/rgl.h"
#include "shadelab/brdf/utia.h"
#include "shadelab/fit/fit.h"

namespace shadelab::cli {

namespace fs = std::filesystem;

namespace {

struct FitCliOptions {
  std::string model;
  std::string data;
  std::vector<std::string> fix;
  std::vector<std::string> free;
  std::string metric = "cosine-l2";
  int starts = 4;
  int theta_d_stride = 3;
  int phi_d_stride = 6;
  int phi_h = 0;  // 0: 1 for isotropic data, 8 otherwise
  bool json = false;
};

bool is_grey_colour(const FitParamValue& p);

std::string numbers_text(const FitParamValue& p) {
  if (is_grey_colour(p)) return fmt::format("{:.6g}", p.numbers[0]);
  return fit_param_text(p, 6);
}

// A grey colour (three equal channels) as one number, as a user types it.
bool is_grey_colour(const FitParamValue& p) {
  return p.group_size == 0 && p.numbers.size() == 3 && p.numbers[0] == p.numbers[1] && p.numbers[0] == p.numbers[2];
}

nlohmann::json numbers_json(const FitParamValue& p) {
  if (p.numbers.size() == 1 || is_grey_colour(p)) return p.numbers[0];
  if (p.group_size > 0) {
    nlohmann::json groups = nlohmann::json::array();
    for (std::size_t g = 0; g < p.numbers.size(); g += static_cast<std::size_t>(p.group_size)) {
      groups.push_back(std::vector<double>(p.numbers.begin() + static_cast<std::ptrdiff_t>(g),
                                           p.numbers.begin() + static_cast<std::ptrdiff_t>(g) + p.group_size));
    }
    return groups;
  }
  return p.numbers;
}

void run_fit(const FitCliOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const FitMetric metric = unwrap(parse_fit_metric(o.metric));
  if (find_brdf_model(o.model) == nullptr) throw UsageError("fit: unknown model '" + o.model + "' (brdf list)");
  if (o.starts < 1 || o.starts > 64) throw UsageError("--starts: " + std::to_string(o.starts) + " is out of range [1, 64]");
  for (const auto& [name, v] : {std::pair{"--theta-d-stride", o.theta_d_stride}, std::pair{"--phi-d-stride", o.phi_d_stride}}) {
    if (v < 1 || v > 90) throw UsageError(std::string(name) + ": " + std::to_string(v) + " is out of range [1, 90]");
  }
  if (o.phi_h < 0 || o.phi_h > 64) throw UsageError("--phi-h: " + std::to_string(o.phi_h) + " is out of range [0, 64]");
  FitOptions fo;
  fo.metric = metric;
  fo.fixed = parse_assignments(o.fix);
  fo.free = o.free;
  fo.starts = o.starts;
  FitGridOptions grid;
  grid.theta_d_stride = o.theta_d_stride;
  grid.phi_d_stride = o.phi_d_stride;

  // The data, and a BRDF of it for the albedo comparison.
  BrdfPtr data_brdf;
  FitData data;
  std::string data_kind;
  if (o.data.rfind("model:", 0) == 0) {
    const auto spec = unwrap(parse_model_spec(o.data));
    auto b = make_brdf(spec.first, spec.second);
    if (!b) throw UsageError("DATA: " + b.error().message);
    data_brdf = std::move(*b);
    grid.n_phi_h = o.phi_h > 0 ? o.phi_h : (looks_isotropic(*data_brdf) ? 1 : 8);
    work_begins();
    data = fit_data_from_brdf(*data_brdf, grid);
    data_kind = "model";
  } else if (const fs::path path(o.data); path.extension() == ".bsdf" || path.extension() == ".bin") {
    // RGL tensor and UTIA files: their own evaluation (brdf/rgl.h, brdf/utia.h) on the grid.
    auto b = path.extension() == ".bsdf" ? read_rgl_brdf(path) : read_utia_brdf(path);
    if (!b) throw UsageError(b.error().message);
    data_brdf = std::move(*b);
    grid.n_phi_h = o.phi_h > 0 ? o.phi_h : (looks_isotropic(*data_brdf) ? 1 : 8);
    work_begins();
    data = fit_data_from_brdf(*data_brdf, grid);
    data_kind = path.extension() == ".bsdf" ? "rgl" : "utia";
  } else {
    require_extension("DATA", path, {".binary", ".bsdf", ".bin"},
                      "a MERL (.binary), RGL (.bsdf) or UTIA (.bin) file, or model:NAME[,PARAM=VALUE...]");
    auto table = std::make_shared<const MerlTable>(unwrap(read_merl(path)));
    work_begins();
    data = fit_data_from_merl(*table, grid);
    data_brdf = std::make_unique<MeasuredBrdf>(table);
    data_kind = "merl";
  }
  if (data.wi.empty()) throw UsageError("DATA '" + o.data + "': no measured configuration within the fit's grid");
  const FitResult r = unwrap(fit_model(o.model, data, fo));
  const double seconds_fit = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Directional albedo, fit minus data (Rec. 709 luminance), theta_o = 0, 10, ..., 80 degrees.
  auto fitted = make_brdf(o.model, r.assignments);
  if (!fitted) throw UsageError(fitted.error().message);
  // A tolerance for a table (a measured BRDF is trilinear between bins: the adaptive rule would refine every kink).
  AlbedoOptions ao;
  ao.quadrature.rel_tol = 1e-4;
  ao.quadrature.abs_tol = 1e-6;
  std::vector<std::pair<double, double>> albedo;
  for (int deg = 0; deg <= 80; deg += 10) {
    const double t = deg * 3.14159265358979323846 / 180.0;
    const double a = luminance(directional_albedo(**fitted, t, ao).albedo) - luminance(directional_albedo(*data_brdf, t, ao).albedo);
    albedo.emplace_back(deg, a);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (o.json) {
    nlohmann::json params = nlohmann::json::object();
    const ModelInfo* info = find_brdf_model(o.model);
    for (const auto& spec : info->params) {
      const auto it = std::find_if(r.params.begin(), r.params.end(), [&](const auto& p) { return p.name == spec.name; });
      if (it != r.params.end()) {
        params[spec.name] = numbers_json(*it);
        continue;
      }
      // A word (a choice): the fixed value, else the default.
      std::string word = spec.default_value;
      for (const auto& [k, v] : fo.fixed) {
        if (k == spec.name) word = v;
      }
      params[spec.name] = word;
    }
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& [t, d] : albedo) rows.push_back({t, d});
    print_json({{"model", o.model},
                {"data", o.data},
                {"data_kind", data_kind},
                {"params", params},
                {"fitted", r.fitted},
                {"metric", fit_metric_name(r.metric)},
                {"residual", r.residual},
                {"start_residuals", r.start_residuals},
                {"configurations", r.configurations},
                {"evaluations", r.evaluations},
                {"albedo_difference", rows},
                {"seconds", seconds},
                {"seconds_fit", seconds_fit}});
    return;
  }
  fmt::print("fit {} to {} ({} configurations, metric {})\n", o.model, o.data, r.configurations, fit_metric_name(r.metric));
  for (const auto& p : r.params) {
    const bool fixed = std::any_of(fo.fixed.begin(), fo.fixed.end(), [&](const auto& a) { return a.first == p.name; });
    fmt::print("  {:<12} {:<28} {}\n", p.name, numbers_text(p), p.fitted ? "fitted" : (fixed ? "fixed" : "default, not fitted"));
  }
  fmt::print("residual {:.6g} ({}; best of {} starts: ", r.residual, fit_metric_name(r.metric), r.start_residuals.size());
  for (std::size_t i = 0; i < r.start_residuals.size(); ++i) fmt::print("{}{:.3g}", i ? ", " : "", r.start_residuals[i]);
  fmt::print(")\n");
  fmt::print("directional albedo, fit - data (luminance):");
  for (const auto& [t, d] : albedo) fmt::print(" {:g}deg {:+.4f}", t, d);
  fmt::print("\n{} evaluations, {:.2f} s (fit {:.2f} s)\n", r.evaluations, seconds, seconds_fit);
}

void add_fit_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<FitCliOptions>();
  auto* sub = app.add_subcommand("fit", "fit a model's parameters to measured data or to another model");
  sub->add_option("model", o->model, "the model to fit (brdf list)")->required();
  sub->add_option("data", o->data, "a MERL (.binary), RGL (.bsdf) or UTIA (.bin) file, or model:NAME[,PARAM=VALUE...]")->required();
  sub->add_option("--fix", o->fix, "hold a parameter at a value, NAME=VALUE (repeatable)");
  sub->add_option("--free", o->free, "fit exactly these parameters (repeatable; default: the model's free set)");
  sub->add_option("--metric", o->metric, "cosine-l2 (Ngan et al. 2005), cube-root (Fores et al. 2012) or log (Low et al. 2012)")
      ->capture_default_str();
  sub->add_option("--starts", o->starts, "deterministic starts (the defaults, then Halton points)")->capture_default_str();
  sub->add_option("--theta-d-stride", o->theta_d_stride, "use every S-th theta_d bin of the MERL grid")->capture_default_str();
  sub->add_option("--phi-d-stride", o->phi_d_stride, "use every S-th phi_d bin of the MERL grid")->capture_default_str();
  sub->add_option("--phi-h", o->phi_h, "half-vector azimuths for model data (0: 1 if isotropic, else 8)")->capture_default_str();
  sub->add_flag("--json", o->json, "machine-readable output");
  sub->callback([o, &command] { command.run = [o] { run_fit(*o); }; });
}

}  // namespace

const CommandRegistration registration_fit(37, add_fit_command);

}  // namespace shadelab::cli
