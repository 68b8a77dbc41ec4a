// shadelab microfacet terms, named after their equations. cos_h is N.H (H the unit half vector).
// Normal distributions D are normalized over projected area, integral of D(h) cos(theta_h) d(omega_h) = 1,
// except D_blinn_phong_ndf, which is the zoo's NDF row (integral of D d(omega_h) = 1).
#pragma once

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/gloss.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/vec.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

// The terms shaders also need live once, in the shading dialect (src/shadelab/kernels/microfacet.sl, each with
// its source): D_beckmann, D_blinn_phong, D_blinn_phong_ndf, G_cook_torrance, V_kelemen, lambda_beckmann,
// G_smith_beckmann, and for GGX D_ggx, D_ggx_aniso, lambda_ggx, G1_ggx, G2_ggx_correlated, G2_ggx_separable,
// V_smith_ggx_correlated. Sampling and conversions, which only the C++ needs, follow here.
using kernel::D_beckmann;
using kernel::D_blinn_phong;
using kernel::D_blinn_phong_ndf;
using kernel::G_cook_torrance;
using kernel::G_smith_beckmann;
using kernel::lambda_beckmann;
using kernel::V_kelemen;
using kernel::D_ggx;
using kernel::D_ggx_aniso;
using kernel::G1_ggx;
using kernel::G2_ggx_correlated;
using kernel::G2_ggx_separable;
using kernel::lambda_ggx;
using kernel::V_smith_ggx_correlated;

// Exponent <-> Beckmann roughness: n = 2/m^2 - 2 (Walter et al. 2007, section 5.2), so that the
// Blinn-Phong and Beckmann distributions nearly coincide.
inline double beckmann_m_from_exponent(double n) { return std::sqrt(2.0 / (n + 2.0)); }
inline double exponent_from_beckmann_m(double m) { return 2.0 / (m * m) - 2.0; }

// Perceptual roughness r and GGX alpha: alpha = r^2 (Burley 2012, "Physically-Based Shading at Disney",
// section 5.4; Karis 2013): the library's one conversion (kernels/microfacet.sl alpha_from_roughness).
inline double alpha_from_perceptual_roughness(double r) { return kernel::alpha_from_roughness(r); }
inline double perceptual_roughness_from_alpha(double alpha) { return kernel::roughness_from_alpha(alpha); }

// The Phong exponent whose (R.L)^n lobe matches a GGX lobe of roughness alpha: GGX's alpha is a roughness
// like Beckmann's m (both the RMS slope's scale; Walter et al. 2007 section 5.2), m -> Blinn-Phong n =
// 2/m^2 - 2, and a Blinn-Phong (N.H)^n lobe is a Phong one of n/4 (brdf/gloss.h).
inline double phong_exponent_from_ggx_alpha(double alpha) {
  return phong_exponent_from_blinn_phong(exponent_from_beckmann_m(alpha));
}

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

// ---- GGX samplers (microfacet.cpp). Each draws a half vector h (h.z > 0) from u in [0, 1)^2; the model
// reflects wo about it. *_pdf(wi, wo) is the density of wi = reflect(wo, h) per unit solid angle over the
// whole sphere (0 where the sampler never produces wi). wo.z > 0 throughout.

// Plain NDF sampling, density D(h) cos(theta_h): the slopes stretched by (1/ax, 1/ay) have the density
// 1 / (pi (1 + r^2)^2), so r^2 = u/(1 - u) and phi = 2 pi u (Walter et al. 2007 eqs. 35-36, anisotropic as
// in Heitz 2014 section 5.3). pdf(wi) = D(h) cos(theta_h) / (4 |wo.h|), h the half vector of wi and wo.
Vec3 sample_ggx_ndf(Vec2 u, double ax, double ay);
double ggx_ndf_pdf(const Vec3& wi, const Vec3& wo, double ax, double ay);

// Visible normals, density D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z (Heitz 2014 eq. 38), by Heitz's
// projected-disk construction (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4),
// listing 1: stretch wo, sample the projected half disks, reproject, unstretch).
Vec3 sample_ggx_vndf_heitz(const Vec3& wo, Vec2 u, double ax, double ay);
// The same density by sampling a spherical cap in the stretched configuration (Dupuy & Benyoub 2023,
// "Sampling Visible GGX Normals with Spherical Caps", HPG, listing 3): z uniform in [-wo_s.z, 1].
Vec3 sample_ggx_vndf_caps(const Vec3& wo, Vec2 u, double ax, double ay);
// pdf of both: G1(wo) D(h) / (4 wo.z) = D(h) / (2 (wo.z + |(ax wo.x, ay wo.y, wo.z)|)) where h = normalize(wi +
// wo) has h.z > 0 and wo.h > 0; 0 elsewhere.
double ggx_vndf_pdf(const Vec3& wi, const Vec3& wo, double ax, double ay);

// Bounded VNDF (Eto & Tokuyoshi 2023, "Bounded VNDF Sampling for Smith-GGX Reflections", SIGGRAPH Asia
// Technical Communications, eqs. 5-6 and listing 1): the spherical cap is cut to z >= -b, b = k wo_s.z,
// k = (1 - a^2) s^2 / (s^2 + a^2 wo.z^2), s = 1 + |wo.xy|, a = min(1, min(ax, ay)); the cut-off part only
// holds half vectors that reflect wo below the horizon. pdf = D(h) / (2 (k wo.z + |(ax wo.x, ay wo.y,
// wo.z)|)) where the cap point of h is kept, 0 elsewhere.
Vec3 sample_ggx_vndf_bounded(const Vec3& wo, Vec2 u, double ax, double ay);
double ggx_vndf_bounded_pdf(const Vec3& wi, const Vec3& wo, double ax, double ay);
// Eto & Tokuyoshi's k (eq. 5 with eq. 6's a), in [0, 1].
double ggx_vndf_bounded_k(const Vec3& wo, double ax, double ay);

}  // namespace shadelab
