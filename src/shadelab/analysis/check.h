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
// - sample weights: an independent check of the sampler: the mean of consistency_samples weights must equal
//   the directional albedo computed by quadrature (without sample()), |z| <= weight_mean_z = 5 in every
//   channel at every check angle (weight_mean, chi_square.h; figure: the largest |z|); and, as before, the
//   relative differences between sample().pdf and pdf() and between sample().weight and f cos / pdf must be
//   <= 1e-6, with no non-finite values and weight 0 below the horizon.
// - pdf integral: the tolerance is max(1e-6, 4 standard errors) when the mass below the horizon is sampled
//   (pdf_smooth_below_horizon() false, chi_square.h).
// - chi-square theta=X, one per check angle (default 0, 30, 60, 80 degrees): p-value of the sampler against
//   the pdf >= the Sidak-corrected level 1 - (1 - alpha)^(1/k), alpha = 0.01, k = number of angles.
// - furnace: the directional albedo at furnace_angles_deg (0..89 degrees) of the model's white-furnace
//   variant (F = 1, no diffuse: f=none kd=0 ks=1 where the model has an f = none choice; filament:
//   metallic=1 base_color=1), else of the model as given; figure: max |1 - albedo|. With energy compensation
//   (ms=kulla-conty, energy_compensation=on) it must be <= furnace_tolerance = 1e-3; otherwise it is the
//   energy loss, reported (threshold NaN).
// - variance: the largest variance of the weight f cos / pdf over the check angles (consistency_samples
//   samples each), reported; the detail lists it per angle and, for a model with a `sampling` parameter, for
//   every sampler it offers.
// A tabulated model (Brdf::is_tabulated: measured) is checked with looser numerics where its table's kinks and
// jumps make the defaults endless: chi-square cells at 3e-3, the energy maximum to 0.5 degrees, reciprocity to
// 1e-9, the albedo to tabulated_rel_tol, the pdf integral by a midpoint sum (check.cpp, for_model); about 80 s for
// a measured ggx table (the grazing albedos most of it).
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
  double weight_mean_z = 5.0;
  std::vector<double> furnace_angles_deg = {0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0};
  double furnace_tolerance = 1e-3;
};

// Builds the model with make_brdf (errors name the model and parameter) and runs every check.
Result<CheckReport> check_brdf(std::string_view model, const ParamAssignments& params = {},
                               const CheckOptions& options = {});

// The checks that need only the Brdf; the normalization item then reports the albedo at normal incidence.
CheckReport check_brdf(const Brdf& f, const CheckOptions& options = {});

}  // namespace shadelab
