#include "shadelab/analysis/check.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "shadelab/core/constants.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {

namespace {

constexpr double no_threshold = std::numeric_limits<double>::quiet_NaN();

std::string num(double v, int precision = 6) {
  std::ostringstream os;
  os << std::setprecision(precision) << v;
  return os.str();
}

std::string rgb(const Rgb& c, int precision = 10) {
  return "(" + num(c.r, precision) + ", " + num(c.g, precision) + ", " + num(c.b, precision) + ")";
}

Vec3 view(double theta_deg) {
  const double t = deg_to_rad(theta_deg);
  return {std::sin(t), 0.0, std::cos(t)};
}

// The albedo at normal incidence, to well below the 1e-9 of the normalization check.
AlbedoResult normal_albedo(const Brdf& f) {
  AlbedoOptions o;
  o.quadrature.rel_tol = 1e-11;
  return directional_albedo(f, 0.0, o);
}

CheckItem report_normal_albedo(const Brdf& f, const std::string& why) {
  const AlbedoResult a = normal_albedo(f);
  return {"normalization", true, a.albedo.max_component(), no_threshold,
          "albedo at normal incidence " + rgb(a.albedo) + " (" + why + ")"};
}

bool has_param(const ModelInfo& info, std::string_view name) {
  return std::any_of(info.params.begin(), info.params.end(), [&](const ParamSpec& p) { return p.name == name; });
}

CheckItem normalization_item(const ModelInfo& info, const ParamAssignments& params, const Brdf& f,
                             const CheckOptions& options) {
  if (!has_param(info, "normalization") || !has_param(info, "ks")) {
    return report_normal_albedo(f, "the model has no normalization parameter; reported only");
  }
  auto values = parse_params(info.name, info.params, params);
  if (!values) return {"normalization", false, 0.0, no_threshold, values.error().message};
  if (values->choice("normalization") != "exact") {
    return report_normal_albedo(f, "normalization=" + values->choice("normalization") + "; reported only");
  }
  const Rgb ks = values->color("ks");
  ParamAssignments specular_only = params;
  if (has_param(info, "kd")) specular_only.emplace_back("kd", "0");
  auto variant = make_brdf(info.name, specular_only);
  if (!variant) return {"normalization", false, 0.0, options.normalization_tolerance, variant.error().message};
  const AlbedoResult a = normal_albedo(**variant);
  // Relative to the largest channel of ks, so that a zero channel must give a (near) zero albedo.
  const double scale = ks.max_component();
  double err = 0.0;
  for (int c = 0; c < 3; ++c) err = std::max(err, std::abs(a.albedo[c] - ks[c]));
  if (scale > 0.0) err /= scale;
  return {"normalization", err <= options.normalization_tolerance, err, options.normalization_tolerance,
          "kd=0 variant: albedo at normal incidence " + rgb(a.albedo, 13) + " vs ks " + rgb(ks, 13) +
              (a.converged ? "" : " (quadrature did not converge)")};
}

std::string assignments_text(const ParamAssignments& params) {
  std::string text;
  for (const auto& [name, value] : params) text += (text.empty() ? "" : " ") + name + "=" + value;
  return text;
}


// Directional albedo over the furnace angles; the figure is the largest |1 - albedo| (any channel).
CheckItem furnace_item(const Brdf& f, bool compensated, const std::string& what, const CheckOptions& options) {
  AlbedoOptions o;
  o.quadrature.rel_tol = 1e-6;  // ample for the furnace bound of 1e-3
  double worst = 0.0;
  double worst_theta = 0.0;
  Rgb worst_albedo;
  std::string list;
  for (double t : options.furnace_angles_deg) {
    const Rgb a = directional_albedo(f, deg_to_rad(t), o).albedo;
    double e = 0.0;
    for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(1.0 - a[c]));
    if (!(e <= worst)) {
      worst = std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
      worst_theta = t;
      worst_albedo = a;
    }
    list += (list.empty() ? "" : ", ") + num(t) + ": " + num(a.max_component(), 7);
  }
  const std::string detail = "white furnace, " + what + ": max |1 - albedo| " + num(worst, 4) + " at theta_o = " +
                             num(worst_theta) + " deg " + rgb(worst_albedo, 7) + "; albedo at " + list;
  if (compensated) {
    return {"furnace", worst <= options.furnace_tolerance, worst, options.furnace_tolerance,
            detail + " (energy compensation on: must be within " + num(options.furnace_tolerance) + ")"};
  }
  return {"furnace", true, worst, no_threshold, detail + " (no compensation: the energy loss, reported only)"};
}

// The variance of the weight's largest channel at wo over count samples.
double weight_variance(const Brdf& f, const Vec3& wo, std::uint64_t count) {
  Pcg32 rng(0x5eed, 0x766172ULL);
  double sum[3] = {0.0, 0.0, 0.0};
  double sum2[3] = {0.0, 0.0, 0.0};
  for (std::uint64_t i = 0; i < count; ++i) {
    const Vec2 u{rng.next_double(), rng.next_double()};
    const double u_lobe = rng.next_double();
    const Rgb w = f.sample(wo, u, u_lobe).weight;
    for (int c = 0; c < 3; ++c) {
      sum[c] += w[c];
      sum2[c] += w[c] * w[c];
    }
  }
  const double n = static_cast<double>(std::max<std::uint64_t>(count, 2));
  double v = 0.0;
  for (int c = 0; c < 3; ++c) v = std::max(v, (sum2[c] - sum[c] * sum[c] / n) / (n - 1.0));
  return v;
}

std::string param_of(const ModelInfo& info, const ParamAssignments& params, std::string_view name) {
  std::string value;
  for (const auto& p : info.params) {
    if (p.name == name) value = p.default_value;
  }
  for (const auto& [k, v] : params) {
    if (k == name) value = v;
  }
  return value;
}

}  // namespace

bool CheckReport::passed() const {
  return std::all_of(items.begin(), items.end(), [](const CheckItem& i) { return i.passed; });
}

const CheckItem* CheckReport::find(std::string_view name) const {
  for (const auto& i : items) {
    if (i.name == name) return &i;
  }
  return nullptr;
}

namespace {

// A tabulated model (Brdf::is_tabulated, a measured table): its density jumps at every cell of its sampler and its
// eval has kinks at every bin centre, so the chi-square's per-cell quadrature runs at 3e-3 (a hundredth of the
// counts' own noise at 1e6 samples in 800 cells) and the energy scan refines its maximum to 0.5 degrees; the
// albedo's own floor is tabulated_rel_tol (albedo.h), the pdf integral a midpoint sum (chi_square.h). Reciprocity
// to 1e-9: the lookup's angles are computed from (wi, wo) and (wo, wi) by different roundings, which on a sharp
// peak's steep interpolation is 1.8e-12 relative (a ggx table of roughness 0.4, f = 2132).
CheckOptions for_model(const Brdf& f, CheckOptions o) {
  if (!f.is_tabulated()) return o;
  o.reciprocity_tolerance = std::max(o.reciprocity_tolerance, 1e-9);
  o.chi_square.cell_rel_tol = std::max(o.chi_square.cell_rel_tol, 3e-3);
  o.energy.theta_tol_deg = std::max(o.energy.theta_tol_deg, 0.5);
  return o;
}

}  // namespace

CheckReport check_brdf(const Brdf& f, const CheckOptions& given) {
  const CheckOptions options = for_model(f, given);
  CheckReport report;
  report.items.push_back(report_normal_albedo(f, "no model information; reported only"));

  // Energy.
  const AlbedoMax m = max_albedo(f, options.energy);
  // A stochastic model's albedo is a sampled mean: the limit widens by 4 of its standard errors there.
  const double energy_limit =
      1.0 + (f.is_stochastic()
                 ? std::max(options.energy_tolerance,
                            4.0 * directional_albedo(f, deg_to_rad(m.theta_deg), options.energy.albedo).error.max_component())
                 : options.energy_tolerance);
  report.items.push_back({"energy", m.value <= energy_limit, m.value, energy_limit,
                          "max albedo " + num(m.value, 10) + " at theta_o = " + num(m.theta_deg, 6) + " deg, " +
                              rgb(m.albedo, 8) + (m.value <= energy_limit ? "" : ": exceeds 1, not energy conserving") +
                              (m.converged ? "" : " (some albedo integrals did not converge)")});

  // Reciprocity.
  const ReciprocityResult rec = reciprocity_error(f);
  const std::string worst = " (worst pair of " + std::to_string(rec.pairs) + ": f(a,b) " + rgb(rec.f_ab, 8) +
                            ", f(b,a) " + rgb(rec.f_ba, 8) + ")";
  if (f.is_stochastic()) {
    report.items.push_back({"reciprocity", std::isfinite(rec.max_relative_error), rec.max_relative_error, no_threshold,
                            "reciprocal in expectation only (eval is a Monte Carlo estimate): measured max relative "
                            "|f(a,b) - f(b,a)| = " + num(rec.max_relative_error, 3) +
                                " includes the estimates' noise; reported only" + worst});
  } else if (f.is_reciprocal()) {
    report.items.push_back({"reciprocity", rec.max_relative_error <= options.reciprocity_tolerance,
                            rec.max_relative_error, options.reciprocity_tolerance,
                            "max relative |f(a,b) - f(b,a)| = " + num(rec.max_relative_error, 3) + worst});
  } else {
    const bool measurable = rec.max_relative_error > options.non_reciprocal_minimum;
    report.items.push_back({"reciprocity", measurable, rec.max_relative_error, options.non_reciprocal_minimum,
                            std::string(measurable ? "non-reciprocal by design (is_reciprocal() is false), "
                                                   : "claims to be non-reciprocal but ") +
                                "measured max relative |f(a,b) - f(b,a)| = " + num(rec.max_relative_error, 3) +
                                (measurable ? " > " : " <= ") + num(options.non_reciprocal_minimum, 3)});
  }

  // pdf integral, sample consistency and the independent mean of the weights over the check angles.
  double worst_integral = 0.0;
  double worst_integral_theta = 0.0;
  double worst_integral_value = 1.0;
  double integral_limit = options.pdf_integral_tolerance;
  double worst_sample = 0.0;
  double worst_z = 0.0;
  double worst_z_theta = 0.0;
  WeightMean worst_mean;
  std::uint64_t below = 0;
  std::uint64_t bad_below = 0;
  std::uint64_t non_finite = 0;
  std::uint64_t zero_pdf = 0;
  std::uint64_t samples = 0;
  std::string variances;
  double worst_variance = 0.0;
  for (double t : options.angles_deg) {
    const QuadratureResult p = pdf_integral(f, view(t));
    const double e = std::abs(p.value - 1.0);
    // A statistical part (pdf_smooth_below_horizon() false) widens the tolerance to 4 standard errors.
    const double limit = std::max(options.pdf_integral_tolerance, 4.0 * p.error);
    if (!(e / limit <= worst_integral / integral_limit)) {
      worst_integral = std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
      worst_integral_theta = t;
      worst_integral_value = p.value;
      integral_limit = limit;
    }
    const SampleConsistency s = sample_consistency(f, view(t), options.consistency_samples);
    worst_sample = std::max({worst_sample, s.max_pdf_error, s.max_weight_error});
    below += s.below_horizon;
    bad_below += s.nonzero_weight_below_horizon;
    non_finite += s.non_finite;
    zero_pdf += s.zero_pdf;
    samples += s.samples;
    const WeightMean wm = weight_mean(f, view(t), options.consistency_samples);
    // A stochastic model's albedo comes from its own sampler (albedo.h): no independent check to make.
    if (!f.is_stochastic() && !(wm.max_z <= worst_z)) {
      worst_z = std::isnan(wm.max_z) ? std::numeric_limits<double>::infinity() : wm.max_z;
      worst_z_theta = t;
      worst_mean = wm;
    }
    const double var = wm.standard_error.max_component() * wm.standard_error.max_component() *
                       static_cast<double>(wm.samples);
    worst_variance = std::max(worst_variance, var);
    variances += (variances.empty() ? "" : ", ") + num(t) + " deg: " + num(var, 4);
  }
  report.items.push_back({"pdf integral", worst_integral <= integral_limit, worst_integral, integral_limit,
                          "max |integral of pdf over the sphere - 1| over the check angles; worst " +
                              num(worst_integral_value, 12) + " at theta_o = " + num(worst_integral_theta) + " deg" +
                              (f.pdf_smooth_below_horizon() ? ""
                                                            : " (mass below the horizon from the sampler's share of " +
                                                                  std::to_string(pdf_integral_lower_samples_for(f)) +
                                                                  " samples: tolerance 4 standard errors)")});
  // The mean weight must equal the albedo computed by quadrature, without sample(): an independent check of
  // the sampler's pdf and weights; the per-sample consistency must hold too.
  const bool samples_ok = worst_sample <= options.weight_tolerance && bad_below == 0 && non_finite == 0 &&
                          worst_z <= options.weight_mean_z;
  report.items.push_back({"sample weights", samples_ok, worst_z, options.weight_mean_z,
                          (f.is_stochastic() ? std::string("mean weight vs albedo: not independent for a stochastic model "
                                                           "(its albedo is its sampler's mean), skipped; ")
                                             : "mean weight vs directional albedo by quadrature: max |z| " + num(worst_z, 4) +
                                                   " at theta_o = " + num(worst_z_theta) + " deg (mean " +
                                                   rgb(worst_mean.mean, 8) + ", albedo " + rgb(worst_mean.albedo, 8) +
                                                   ", standard error " + rgb(worst_mean.standard_error, 3) + "); ") +
                              "max relative error of sample().pdf vs pdf() and " +
                              "of weight vs f cos / pdf " + num(worst_sample, 3) + " over " + std::to_string(samples) +
                              " samples; " + std::to_string(below) + " below the horizon (" +
                              std::to_string(bad_below) + " with non-zero weight), " + std::to_string(zero_pdf) +
                              " with pdf 0, " + std::to_string(non_finite) + " non-finite"});
  // Chi-square, Sidak-corrected over the angles.
  const double level = sidak_significance(options.alpha, static_cast<int>(options.angles_deg.size()));
  for (double t : options.angles_deg) {
    const ChiSquareResult c = chi_square_test(f, view(t), options.chi_square);
    std::string detail = "statistic " + num(c.statistic) + ", dof " + std::to_string(c.degrees_of_freedom) + ", " +
                         std::to_string(c.samples) + " samples, " + std::to_string(c.pooled_cells) +
                         " cells pooled, level " + num(level, 4) + " (alpha " + num(options.alpha) + " Sidak-corrected for " +
                         std::to_string(options.angles_deg.size()) + " angles)";
    if (c.invalid_samples > 0) detail += ", " + std::to_string(c.invalid_samples) + " non-finite samples";
    if (c.unexpected_samples > 0) detail += ", " + std::to_string(c.unexpected_samples) + " samples where the pdf is 0";
    report.items.push_back({"chi-square theta=" + num(t), c.p_value >= level, c.p_value, level, detail});
  }
  report.items.push_back(furnace_item(f, false, "the model as given (no model information)", options));
  report.items.push_back({"variance", true, worst_variance, no_threshold,
                          "variance of the weight f cos / pdf (largest channel), " + std::to_string(options.consistency_samples) +
                              " samples at theta_o " + variances + "; reported only"});
  return report;
}

Result<CheckReport> check_brdf(std::string_view model, const ParamAssignments& params, const CheckOptions& options) {
  auto f = make_brdf(model, params);
  if (!f) return f.error();
  const ModelInfo* info = find_brdf_model(model);
  CheckReport report = check_brdf(**f, options);
  report.model = std::string(model);
  report.params = assignments_text(params);
  report.items.front() = normalization_item(*info, params, **f, options);
  // The white furnace: the model's F = 1, no-diffuse variant where it has one (f = none, kd = 0, ks = 1;
  // filament: metallic = 1, base_color = 1, so that f0 = 1).
  ParamAssignments white = params;
  std::string what = "the model as given (it has no F = 1 setting)";
  const auto choice_has = [&](std::string_view name, std::string_view word) {
    for (const auto& p : info->params) {
      if (p.name == name) return std::find(p.choices.begin(), p.choices.end(), word) != p.choices.end();
    }
    return false;
  };
  if (choice_has("f", "none")) {
    white.emplace_back("f", "none");
    if (has_param(*info, "kd")) white.emplace_back("kd", "0");
    if (has_param(*info, "ks")) white.emplace_back("ks", "1");
    what = "variant f=none" + std::string(has_param(*info, "kd") ? " kd=0" : "") + (has_param(*info, "ks") ? " ks=1" : "");
  } else if (has_param(*info, "metallic") && has_param(*info, "base_color")) {
    white.emplace_back("metallic", "1");
    white.emplace_back("base_color", "1");
    what = "variant metallic=1 base_color=1 (f0 = 1)";
  }
  const bool compensated = param_of(*info, params, "ms") == "kulla-conty" || param_of(*info, params, "energy_compensation") == "on";
  if (auto w = make_brdf(model, white)) {
    report.items[report.items.size() - 2] = furnace_item(**w, compensated, what, options);
  }
  // The variance of every sampler the model offers, at the check angles.
  const ParamSpec* sampling = nullptr;
  for (const auto& p : info->params) {
    if (p.name == "sampling") sampling = &p;
  }
  if (sampling != nullptr) {
    CheckItem& v = report.items.back();
    const std::string configured = param_of(*info, params, "sampling");
    std::string others;
    for (const auto& choice : sampling->choices) {
      ParamAssignments variant = params;
      variant.emplace_back("sampling", choice);
      auto g = make_brdf(model, variant);
      if (!g) continue;
      std::string list;
      for (double t : options.angles_deg) {
        list += (list.empty() ? "" : ", ") + num(weight_variance(**g, view(t), options.consistency_samples), 4);
      }
      others += "; " + choice + (choice == configured ? " (configured)" : "") + ": " + list;
    }
    v.detail += "; per sampler, at theta_o " + [&] {
      std::string a;
      for (double t : options.angles_deg) a += (a.empty() ? "" : "/") + num(t);
      return a;
    }() + " deg" + others;
  }
  return report;
}

}  // namespace shadelab
