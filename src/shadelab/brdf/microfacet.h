// shadelab microfacet terms, named after their equations. cos_h is N.H (H the unit half vector).
// Normal distributions D are normalized over projected area, integral of D(h) cos(theta_h) d(omega_h) = 1,
// except D_blinn_phong_ndf, which is the zoo's NDF row (integral of D d(omega_h) = 1).
#pragma once

#include <algorithm>
#include <cmath>

#include "shadelab/core/constants.h"
#include "shadelab/core/vec.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

// The terms shaders also need live once, in the shading dialect (src/shadelab/kernels/microfacet.sl, each with
// its source): D_beckmann, D_blinn_phong, D_blinn_phong_ndf, G_cook_torrance, V_kelemen, lambda_beckmann,
// G_smith_beckmann. Sampling and conversions, which only the C++ needs, follow here.
using kernel::D_beckmann;
using kernel::D_blinn_phong;
using kernel::D_blinn_phong_ndf;
using kernel::G_cook_torrance;
using kernel::G_smith_beckmann;
using kernel::lambda_beckmann;
using kernel::V_kelemen;

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

// Half vector of a reflection pair, on the side of the normal (kernels/common.sl).
inline Vec3 half_vector(const Vec3& wi, const Vec3& wo) { return kernel::half_vector(wi, wo); }

// Density of wi = reflect(wo, h) when h has density p_h per unit solid angle: p_h / (4 |wo.h|)
// (the Jacobian of the reflection map, Walter et al. 2007 eq. 14).
inline double reflect_jacobian_pdf(double pdf_h, const Vec3& wo, const Vec3& h) {
  const double oh = std::abs(dot(wo, h));
  return oh > 0.0 ? pdf_h / (4.0 * oh) : 0.0;
}

}  // namespace shadelab
