// shadelab microfacet terms, named after their equations. cos_h is N.H (H the unit half vector).
// Normal distributions D are normalized over projected area, integral of D(h) cos(theta_h) d(omega_h) = 1,
// except D_blinn_phong_ndf, which is the zoo's NDF row (integral of D d(omega_h) = 1).
#pragma once

#include <algorithm>
#include <cmath>

#include "shadelab/core/constants.h"
#include "shadelab/core/vec.h"

namespace shadelab {

// Beckmann: exp(-tan^2(a)/m^2) / (pi m^2 cos^4(a)) (Cook & Torrance 1981 eq. 5 with the 1/pi of
// Walter et al. 2007 eq. 25). m is the RMS slope.
inline double D_beckmann(double cos_h, double m) {
  if (cos_h <= 0.0) return 0.0;
  const double c2 = cos_h * cos_h;
  const double tan2 = (1.0 - c2) / c2;
  return std::exp(-tan2 / (m * m)) / (pi * m * m * c2 * c2);
}

// Blinn-Phong, heightfield normalization: (n + 2)/(2 pi) cos^n (the zoo's "Blinn-Phong (heightfield)" row).
inline double D_blinn_phong(double cos_h, double n) {
  return cos_h > 0.0 ? (n + 2.0) * inv_two_pi * std::pow(cos_h, n) : 0.0;
}

// Blinn-Phong, NDF normalization: (n + 1)/(2 pi) cos^n (the zoo's "Blinn-Phong (NDF)" row).
inline double D_blinn_phong_ndf(double cos_h, double n) {
  return cos_h > 0.0 ? (n + 1.0) * inv_two_pi * std::pow(cos_h, n) : 0.0;
}

// Cook-Torrance masking-shadowing: min(1, 2 NH NV / VH, 2 NH NL / VH) (Cook & Torrance 1981 eq. 6;
// the lecture's slide, where VH = LH).
inline double G_cook_torrance(double nh, double nv, double nl, double vh) {
  return std::min(1.0, std::min(2.0 * nh * nv / vh, 2.0 * nh * nl / vh));
}

// Kelemen & Szirmay-Kalos 2001: G / (4 NL NV) ~= 1 / (4 (L.H)^2), a visibility term V.
inline double V_kelemen(double lh) { return 0.25 / (lh * lh); }

// Smith's Lambda for the Beckmann distribution: (erf(a) - 1)/2 + exp(-a^2)/(2 a sqrt(pi)),
// a = 1/(m tan(theta)) (Walter et al. 2007 eq. 27 and Heitz 2014 eq. 80 style).
inline double lambda_beckmann(double cos_theta_, double m) {
  if (cos_theta_ >= 1.0) return 0.0;
  const double tan_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta_ * cos_theta_)) / cos_theta_;
  const double a = 1.0 / (m * tan_theta);
  return 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(pi));
}

// Height-correlated Smith masking-shadowing for Beckmann: 1 / (1 + Lambda(wi) + Lambda(wo)) (Heitz 2014,
// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 99).
inline double G_smith_beckmann(double cos_i, double cos_o, double m) {
  return 1.0 / (1.0 + lambda_beckmann(cos_i, m) + lambda_beckmann(cos_o, m));
}

// Exponent <-> Beckmann roughness: n = 2/m^2 - 2 (Walter et al. 2007, section 5.2), so that the
// Blinn-Phong and Beckmann distributions nearly coincide.
inline double beckmann_m_from_exponent(double n) { return std::sqrt(2.0 / (n + 2.0)); }
inline double exponent_from_beckmann_m(double m) { return 2.0 / (m * m) - 2.0; }

// Sampling H with density D(h) cos(theta_h) for Beckmann: tan^2(theta) = -m^2 ln(1 - u) (Walter et al. 2007
// eq. 28).
inline Vec3 sample_beckmann_h(Vec2 u, double m) {
  const double tan2 = -m * m * std::log1p(-u.x);
  const double c = 1.0 / std::sqrt(1.0 + tan2);
  return spherical_direction(std::sqrt(std::max(0.0, 1.0 - c * c)), c, two_pi * u.y);
}

// Half vector of a reflection pair, on the side of the normal.
inline Vec3 half_vector(const Vec3& wi, const Vec3& wo) {
  Vec3 h = wi + wo;
  const double len = length(h);
  if (len == 0.0) return {0.0, 0.0, 1.0};  // wi == -wo: measure zero; any unit vector keeps eval finite
  h = h / len;
  return h.z < 0.0 ? -h : h;
}

// Density of wi = reflect(wo, h) when h has density p_h per unit solid angle: p_h / (4 |wo.h|)
// (the Jacobian of the reflection map, Walter et al. 2007 eq. 14).
inline double reflect_jacobian_pdf(double pdf_h, const Vec3& wo, const Vec3& h) {
  const double oh = std::abs(dot(wo, h));
  return oh > 0.0 ? pdf_h / (4.0 * oh) : 0.0;
}

}  // namespace shadelab
