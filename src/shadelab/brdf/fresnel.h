// shadelab Fresnel reflectance: exact unpolarized reflectance of a smooth interface, and Schlick's form.
// The formulas live once, in the shading dialect (src/shadelab/kernels/fresnel.sl, with their sources), so
// that shaders use the same text; this header gives them their C++ names.
//
// - F_dielectric(cos_i, eta): relative index eta = n_t / n_i; a negative cos_i means the light arrives from
//   the other side (the interface is seen with 1/eta); total internal reflection gives 1.
// - F_conductor(cos_i, n, k): complex relative index n + ik, k >= 0, seen from outside.
// - F_schlick(cos_i, f0) = f0 + (1 - f0)(1 - cos)^5; f0_from_ior(n) = ((n - 1)/(n + 1))^2 and
//   f0_from_ior(n, k) = ((n - 1)^2 + k^2)/((n + 1)^2 + k^2).
#pragma once

#include "shadelab/color/rgb.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

using kernel::F_conductor;
using kernel::F_dielectric;
using kernel::F_schlick;
using kernel::f0_from_ior;

inline Rgb F_conductor(double cos_i, const Rgb& n, const Rgb& k) { return kernel::F_conductor_rgb(cos_i, n, k); }
inline Rgb F_schlick(double cos_i, const Rgb& f0) { return kernel::F_schlick_rgb(cos_i, f0); }
inline double f0_from_ior(double n, double k) { return kernel::f0_from_ior_k(n, k); }

}  // namespace shadelab
