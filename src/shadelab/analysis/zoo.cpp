#include "shadelab/analysis/zoo.h"

#include <array>
#include <cmath>

#include "shadelab/brdf/blinn_phong.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/phong.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/text.h"

namespace shadelab {

namespace {

constexpr std::array<std::string_view, 6> row_names = {"phong",           "phong-modified",
                                                       "blinn-phong",     "blinn-phong-modified",
                                                       "blinn-phong-ndf", "blinn-phong-heightfield"};

// The row's integrand over [0, pi/2] (Schüler 2011, the zoo's "RDF/INTEGRAND" and "NDF/INTEGRAND" columns).
double integrand(std::size_t row, double t, double n) {
  switch (row) {
    case 0: return std::pow(std::cos(t), n) * std::sin(t);                                // cos^n t sin t
    case 1: return std::pow(std::cos(t), n) * std::cos(t) * std::sin(t);                  // cos^n t cos t sin t
    case 2: return std::pow(std::cos(0.5 * t), n) * std::sin(t);                          // cos^n(t/2) sin t
    case 3: return std::pow(std::cos(0.5 * t), n) * std::cos(t) * std::sin(t);            // cos^n(t/2) cos t sin t
    case 4: return std::pow(std::cos(t), n) * std::sin(t);                                // cos^n a sin a
    default: return std::pow(std::cos(t), n) * std::cos(t) * std::sin(t);                 // cos^n a cos a sin a
  }
}

void fill_texts_and_closed_form(std::size_t row, double n, ZooRow& r) {
  using BP = BlinnPhong::Normalization;
  switch (row) {
    case 0:
      r.table = "RDF";
      r.function_text = "(R.L)^n";
      r.integrand_text = "cos^n(t) sin(t)";
      r.closed_form_text = "(n+1) / (2 pi)";
      r.literature = "(none listed)";
      r.closed_form = Phong::normalization_factor(n, Phong::Normalization::exact, false);
      break;
    case 1:
      r.table = "RDF";
      r.function_text = "(R.L)^n (N.L)";
      r.integrand_text = "cos^n(t) cos(t) sin(t)";
      r.closed_form_text = "(n+2) / (2 pi)";
      r.literature = "[3,5,8] Giesen; Lafortune & Willems; Lewis";
      r.closed_form = Phong::normalization_factor(n, Phong::Normalization::exact, true);
      break;
    case 2:
      r.table = "RDF";
      r.function_text = "(N.H)^n";
      r.integrand_text = "cos^n(t/2) sin(t)";
      r.closed_form_text = "(n+2) / (4 pi (2 - 2^(-n/2)))";
      r.lower_text = "(n+2) / (8 pi)";
      r.upper_text = "(n+4) / (8 pi)";
      r.literature = "[6] Gotanda";
      r.closed_form = BlinnPhong::normalization_factor(n, BP::exact, false);
      r.lower = BlinnPhong::normalization_factor(n, BP::lower, false);
      r.upper = BlinnPhong::normalization_factor(n, BP::upper, false);
      break;
    case 3:
      r.table = "RDF";
      r.function_text = "(N.H)^n (N.L)";
      r.integrand_text = "cos^n(t/2) cos(t) sin(t)";
      r.closed_form_text = "(n+2)(n+4) / (8 pi (2^(-n/2) + n))";
      r.lower_text = "(n+6) / (8 pi)";
      r.upper_text = "(n+8) / (8 pi)";
      r.literature = "[3,9] Giesen; Akenine-Möller, Haines & Hoffman";
      r.closed_form = BlinnPhong::normalization_factor(n, BP::exact, true);
      r.lower = BlinnPhong::normalization_factor(n, BP::lower, true);
      r.upper = BlinnPhong::normalization_factor(n, BP::upper, true);
      break;
    case 4:
      r.table = "NDF";
      r.function_text = "(N.H)^n";
      r.integrand_text = "cos^n(a) sin(a)";
      r.closed_form_text = "(n+1) / (2 pi)";
      r.literature = "[2,4,5] Schüler; Kelemen & Szirmay-Kalos; Lafortune & Willems";
      r.closed_form = D_blinn_phong_ndf(1.0, n);
      break;
    default:
      r.table = "NDF";
      r.function_text = "(N.H)^n (heightfield: projected area)";
      r.integrand_text = "cos^n(a) cos(a) sin(a)";
      r.closed_form_text = "(n+2) / (2 pi)";
      r.literature = "[10,11] Pharr & Humphreys; Hoffman";
      r.closed_form = D_blinn_phong(1.0, n);
      break;
  }
}

}  // namespace

std::span<const std::string_view> zoo_models() { return row_names; }

QuadratureOptions zoo_quadrature() {
  QuadratureOptions o;
  o.rel_tol = 1e-13;
  o.max_subdivisions = 4000;
  return o;
}

Result<ZooRow> zoo_row(std::string_view model, double n, const QuadratureOptions& options) {
  std::size_t row = row_names.size();
  for (std::size_t i = 0; i < row_names.size(); ++i) {
    if (row_names[i] == model) row = i;
  }
  if (row == row_names.size()) {
    std::string list;
    for (auto name : row_names) list += (list.empty() ? "" : ", ") + std::string(name);
    return make_error("zoo: unknown model '" + printable(model) + "' (rows: " + list + ")");
  }
  if (!std::isfinite(n) || n < 0.0) {
    return make_error("zoo: exponent n = " + std::to_string(n) + " must be finite and >= 0");
  }
  ZooRow r;
  r.model = std::string(model);
  r.n = n;
  fill_texts_and_closed_form(row, n, r);
  const QuadratureResult q = integrate([row, n](double t) { return integrand(row, t, n); }, 0.0, pi / 2, options);
  r.integral = q.value;
  r.integral_error = q.error;
  r.numeric = 1.0 / (two_pi * q.value);               // normalization = 1 / (2 pi I)
  r.numeric_error = r.numeric * q.error / q.value;     // first-order propagation of the error of I
  r.relative_error = std::abs(r.numeric - r.closed_form) / r.closed_form;
  r.evaluations = q.evaluations;
  r.converged = q.converged;
  return r;
}

Result<std::vector<ZooRow>> zoo_table(double n, const QuadratureOptions& options) {
  std::vector<ZooRow> rows;
  for (auto name : row_names) {
    auto r = zoo_row(name, n, options);
    if (!r) return r.error();
    rows.push_back(std::move(r).value());
  }
  return rows;
}

}  // namespace shadelab
