// shadelab normalization zoo: the table of Schüler, "The Blinn-Phong Normalization Zoo" (2011), recomputed.
//
// Contract:
// - Six rows, in the article's order (zoo_models()): the RDF rows phong, phong-modified, blinn-phong,
//   blinn-phong-modified (viewer on the normal, t = angle between N and L) and the NDF rows blinn-phong-ndf,
//   blinn-phong-heightfield (a = angle between N and H). Each row's normalization is 1 / (2 pi I(n)) with
//   I(n) the integral of the row's integrand over [0, pi/2] (the 2 pi is the azimuth).
// - zoo_row(model, n) returns the texts of the row (function, integrand, closed form, bounds, literature),
//   the closed form's value taken from the model code (Phong::normalization_factor,
//   BlinnPhong::normalization_factor for exact/lower/upper, D_blinn_phong_ndf(1, n), D_blinn_phong(1, n)),
//   so that the table tests the models, and the numeric normalization from the adaptive Gauss-Kronrod
//   quadrature (quadrature.h) with its propagated error estimate and its relative difference to the closed
//   form. Bounds exist for blinn-phong and blinn-phong-modified only.
// - n must be finite and >= 0; an unknown model or a bad n gives an Error naming it. No printing.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "shadelab/numeric/quadrature.h"
#include "shadelab/core/error.h"

namespace shadelab {

struct ZooRow {
  std::string model;             // registry-style name: "blinn-phong-modified"
  std::string table;             // "RDF" or "NDF"
  std::string function_text;     // "(N.H)^n (N.L)"
  std::string integrand_text;    // "cos^n(t/2) cos(t) sin(t)"
  std::string closed_form_text;  // "(n+2)(n+4) / (8 pi (2^(-n/2) + n))"
  std::string lower_text;        // "(n+6) / (8 pi)", empty without a bound
  std::string upper_text;
  std::string literature;        // "[3,9] Giesen; Akenine-Möller, Haines & Hoffman"

  double n = 0.0;
  double closed_form = 0.0;       // from the model code
  std::optional<double> lower;    // from the model code, where the zoo gives bounds
  std::optional<double> upper;
  double integral = 0.0;          // I(n) by quadrature
  double integral_error = 0.0;    // its error estimate
  double numeric = 0.0;           // 1 / (2 pi I(n))
  double numeric_error = 0.0;     // numeric * integral_error / integral
  double relative_error = 0.0;    // |numeric - closed_form| / closed_form
  std::int64_t evaluations = 0;
  bool converged = false;
};

// The six row names in table order.
std::span<const std::string_view> zoo_models();

// The default quadrature options of the zoo: rel_tol 1e-13, up to 4000 subdivisions.
QuadratureOptions zoo_quadrature();

// rel_tol applies to I(n); the default 1e-13 leaves the numeric column accurate to about 1e-13.
Result<ZooRow> zoo_row(std::string_view model, double n, const QuadratureOptions& options = zoo_quadrature());
Result<std::vector<ZooRow>> zoo_table(double n, const QuadratureOptions& options = zoo_quadrature());

}  // namespace shadelab
