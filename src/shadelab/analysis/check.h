// shadelab BRDF check: the report behind `shadelab brdf check MODEL`.
//
// Contract: check_brdf runs a fixed list of checks on one model with one parameter set and returns one item
// per check, {name, passed, figure, threshold, detail}; it never prints. The items, in order:
// - normalization: for a model with a `normalization` parameter set to exact (and a `ks` parameter), the
//   variant with kd = 0 (built through make_brdf) must have directional albedo at normal incidence equal to
//   ks, per channel, to 1e-9 relative (figure: max |albedo - ks| / max ks). Otherwise the albedo at normal
//   incidence of the model as given is reported (largest channel) and the item passes; threshold is NaN.
// - energy: the maximum over theta_o in [0, 89] degrees of the largest channel of the albedo (max_albedo)
//   must be <= 1 + 1e-6. A model may fail this by design (the report says so; nothing is hidden).
// - reciprocity: max relative |f(a,b) - f(b,a)| over the reciprocity grid (albedo.h) <= 1e-12; for a model
//   whose is_reciprocal() is false, the item passes when the measured error is > 1e-6 (non-reciprocal by
//   design, and measurably so).
// - pdf integral: max over the check angles of |integral of pdf over the sphere - 1| <= 1e-6.
// - sample weights: max over the check angles of the relative differences between sample().pdf and pdf(),
//   and between sample().weight and f cos / pdf, <= 1e-6; no non-finite values; weight 0 below the horizon.
// - chi-square theta=X, one per check angle (default 0, 30, 60, 80 degrees): p-value of the sampler against
//   the pdf >= the Sidak-corrected level 1 - (1 - alpha)^(1/k), alpha = 0.01, k = number of angles.
// All randomness uses fixed seeds. About one to a few seconds per model in a Release build.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "shadelab/analysis/albedo.h"
#include "shadelab/analysis/chi_square.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/error.h"

namespace shadelab {

struct CheckItem {
  std::string name;
  bool passed = false;
  double figure = 0.0;     // the measured number
  double threshold = 0.0;  // what it is compared with (NaN for an item that only reports)
  std::string detail;      // one line for a reader
};

struct CheckReport {
  std::string model;   // empty when checking a bare Brdf
  std::string params;  // "kd=0 n=10" as given
  std::vector<CheckItem> items;
  bool passed() const;
  const CheckItem* find(std::string_view name) const;
};

struct CheckOptions {
  std::vector<double> angles_deg = {0.0, 30.0, 60.0, 80.0};
  double alpha = 0.01;  // family-wise significance of the chi-square tests
  ChiSquareOptions chi_square;
  std::uint64_t consistency_samples = 100'000;
  AlbedoScanOptions energy;
  double normalization_tolerance = 1e-9;
  double energy_tolerance = 1e-6;
  double reciprocity_tolerance = 1e-12;
  double non_reciprocal_minimum = 1e-6;
  double weight_tolerance = 1e-6;
  double pdf_integral_tolerance = 1e-6;
};

// Builds the model with make_brdf (errors name the model and parameter) and runs every check.
Result<CheckReport> check_brdf(std::string_view model, const ParamAssignments& params = {},
                               const CheckOptions& options = {});

// The checks that need only the Brdf; the normalization item then reports the albedo at normal incidence.
CheckReport check_brdf(const Brdf& f, const CheckOptions& options = {});

}  // namespace shadelab
