// Test helpers for the DFG and split-sum lobe tests: GGX's D and Smith's Lambda written here from their
// papers, not taken from the kernels, so that the tests integrate an independent BRDF.
#pragma once

#include <cmath>
#include <numbers>

namespace shadelab::test_formulas {

// GGX D(h) = alpha^2 / (pi cos^4(theta_h) (alpha^2 + tan^2(theta_h))^2) (Walter et al. 2007 eq. 33).
inline double ggx_d(double cos_h, double alpha) {
  if (cos_h <= 0.0) return 0.0;
  const double c2 = cos_h * cos_h;
  const double tan2 = (1.0 - c2) / c2;
  const double s = alpha * alpha + tan2;
  return alpha * alpha / (std::numbers::pi * c2 * c2 * s * s);
}

// Smith's Lambda for GGX: (-1 + sqrt(1 + alpha^2 tan^2(theta))) / 2 (Walter et al. 2007 eq. 34 as Heitz 2014
// eq. 86 writes it).
inline double ggx_lambda(double cos_t, double alpha) {
  const double c2 = cos_t * cos_t;
  return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * (1.0 - c2) / c2));
}

}  // namespace shadelab::test_formulas
