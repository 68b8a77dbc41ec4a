// shadelab Fresnel reflectance: exact unpolarized reflectance of a smooth interface, and Schlick's form.
//
// Exact: F = (|r_s|^2 + |r_p|^2) / 2 with r_s = (n1 cos_i - n2 cos_t)/(n1 cos_i + n2 cos_t) and
// r_p = (n2 cos_i - n1 cos_t)/(n2 cos_i + n1 cos_t) (Born & Wolf, Principles of Optics, 1.5.2; the
// lecture's slide "Fresnel Equations"); for a conductor n2 is complex, n + ik, and cos_t is complex.
// Schlick: F = F0 + (1 - F0)(1 - cos)^5 (Schlick, "An Inexpensive BRDF Model for Physically-based
// Rendering", Eurographics 1994, eq. 24), F0 = ((n - 1)/(n + 1))^2 at normal incidence.
#pragma once

#include "shadelab/color/rgb.h"

namespace shadelab {

// Dielectric with relative index eta = n_transmitted / n_incident (real, > 0). cos_i is the cosine of the
// angle between the incident direction and the normal on the incident side; a negative cos_i means the light
// arrives from the other side, and the interface is seen with 1/eta. Total internal reflection gives 1.
double F_dielectric(double cos_i, double eta);

// Conductor (or absorbing dielectric) with complex relative index n + ik, k >= 0, seen from outside.
double F_conductor(double cos_i, double n, double k);
Rgb F_conductor(double cos_i, const Rgb& n, const Rgb& k);

// Schlick's approximation from the reflectance at normal incidence.
constexpr double F_schlick(double cos_i, double f0) {
  const double m = 1.0 - cos_i;
  const double m2 = m * m;
  return f0 + (1.0 - f0) * (m2 * m2 * m);
}
constexpr Rgb F_schlick(double cos_i, const Rgb& f0) {
  return {F_schlick(cos_i, f0.r), F_schlick(cos_i, f0.g), F_schlick(cos_i, f0.b)};
}

// Reflectance at normal incidence of a dielectric of relative index n: ((n - 1)/(n + 1))^2.
constexpr double f0_from_ior(double n) {
  const double r = (n - 1.0) / (n + 1.0);
  return r * r;
}
// Reflectance at normal incidence of a conductor: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
constexpr double f0_from_ior(double n, double k) {
  return ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
}

}  // namespace shadelab
