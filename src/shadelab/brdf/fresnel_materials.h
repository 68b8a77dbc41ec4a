// shadelab Fresnel materials: named complex indices of refraction n + ik from published measurements, sampled
// at three wavelengths that stand for the R, G and B channels, for use with brdf/fresnel.h.
//
// Every material uses the same wavelengths: R = 650 nm, G = 550 nm, B = 450 nm. Where a publication tabulates
// other wavelengths, the value is linearly interpolated in wavelength between the two bracketing table rows
// (the rows are named next to each material in fresnel_materials.cpp). Dielectrics are given by their
// dispersion formula or table evaluated at those wavelengths, with k = 0 (their absorption is below 1e-7).
//
// Sampling a spectrum at three wavelengths is a rendering convention, not colorimetry: it is the usual
// "RGB IOR" approximation, good enough to give metals their tint, not a spectral upsampling.
#pragma once

#include <span>
#include <string_view>

#include "shadelab/color/rgb.h"

namespace shadelab {

struct FresnelMaterial {
  std::string_view name;         // lower-case identifier, e.g. "gold"
  bool conductor = false;        // false for dielectrics (k = 0)
  Rgb n;                         // real part of the IOR at the wavelengths in `wavelengths` (R, G, B)
  Rgb k;                         // extinction coefficient (0 for dielectrics)
  std::string_view wavelengths;  // the wavelengths of the R, G, B entries
  std::string_view source;       // the publication the numbers come from
};

// The wavelengths of every entry of fresnel_materials(), in R, G, B order.
inline constexpr std::string_view fresnel_material_wavelengths = "650, 550, 450 nm";

// All materials, in a fixed order (dielectrics first, then conductors).
std::span<const FresnelMaterial> fresnel_materials();

// The material with this name (ASCII case-insensitive), or nullptr if there is none.
const FresnelMaterial* find_fresnel_material(std::string_view name);

// Exact unpolarized reflectance per channel at incidence cosine cos_i, from air (n = 1) onto the material:
// F_dielectric(cos_i, n) for dielectrics, F_conductor(cos_i, n, k) for conductors (brdf/fresnel.h).
Rgb fresnel_reflectance(const FresnelMaterial& m, double cos_i);

// Reflectance at normal incidence: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2) per channel (Born & Wolf,
// Principles of Optics, ch. 14, at normal incidence).
Rgb fresnel_f0(const FresnelMaterial& m);

}  // namespace shadelab
