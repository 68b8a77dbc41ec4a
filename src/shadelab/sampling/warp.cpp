#include "shadelab/sampling/warp.h"

#include <algorithm>
#include <cmath>

#include "shadelab/core/constants.h"

namespace shadelab {

namespace {
// sin(theta) from cos(theta), clamped so rounding can never give the square root of a negative number.
double sin_from_cos(double c) { return std::sqrt(std::max(0.0, 1.0 - c * c)); }
}  // namespace

double azimuth(const Vec3& w) {
  const double phi = std::atan2(w.y, w.x);
  // atan2 is in [-pi, pi]; a negative phi smaller than half an ulp of 2 pi would round up to 2 pi itself, so
  // the result is capped at the largest double below 2 pi to keep it in [0, 2 pi).
  return phi < 0.0 ? std::min(phi + two_pi, std::nextafter(two_pi, 0.0)) : phi;
}

// Hemisphere: z = u0 is uniform in [0,1] because d(omega) = dz dphi.
Vec3 sample_uniform_hemisphere(Vec2 u) {
  const double z = u.x;
  return spherical_direction(sin_from_cos(z), z, two_pi * u.y);
}
double uniform_hemisphere_pdf(const Vec3& w) { return w.z >= 0.0 ? inv_two_pi : 0.0; }
Vec2 invert_uniform_hemisphere(const Vec3& w) { return {w.z, azimuth(w) * inv_two_pi}; }

// Cosine: cos^2(theta) = u0 (the z-marginal of cos/pi is 2z dz, whose CDF is z^2).
Vec3 sample_cosine_hemisphere(Vec2 u) {
  const double z = std::sqrt(u.x);
  return spherical_direction(std::sqrt(std::max(0.0, 1.0 - u.x)), z, two_pi * u.y);
}
double cosine_hemisphere_pdf(const Vec3& w) { return w.z > 0.0 ? w.z * inv_pi : 0.0; }
Vec2 invert_cosine_hemisphere(const Vec3& w) { return {w.z * w.z, azimuth(w) * inv_two_pi}; }

// Power cosine: the z-marginal (n+1) z^n dz has CDF z^(n+1), so z = u0^(1/(n+1)).
Vec3 sample_power_cosine(Vec2 u, double n) {
  const double z = std::pow(u.x, 1.0 / (n + 1.0));
  return spherical_direction(sin_from_cos(z), z, two_pi * u.y);
}
double power_cosine_pdf(const Vec3& w, double n) {
  return w.z > 0.0 ? (n + 1.0) * inv_two_pi * std::pow(w.z, n) : 0.0;
}
Vec2 invert_power_cosine(const Vec3& w, double n) {
  return {std::pow(std::max(w.z, 0.0), n + 1.0), azimuth(w) * inv_two_pi};
}

// Sphere: z uniform in [-1, 1].
Vec3 sample_uniform_sphere(Vec2 u) {
  const double z = 1.0 - 2.0 * u.x;
  return spherical_direction(sin_from_cos(z), z, two_pi * u.y);
}
double uniform_sphere_pdf(const Vec3&) { return inv_four_pi; }
Vec2 invert_uniform_sphere(const Vec3& w) { return {(1.0 - w.z) * 0.5, azimuth(w) * inv_two_pi}; }

// Cap: z uniform in [cos_max, 1].
Vec3 sample_spherical_cap(Vec2 u, double cos_max) {
  const double z = 1.0 - u.x * (1.0 - cos_max);
  return spherical_direction(sin_from_cos(z), z, two_pi * u.y);
}
double spherical_cap_pdf(const Vec3& w, double cos_max) {
  return w.z >= cos_max ? 1.0 / (two_pi * (1.0 - cos_max)) : 0.0;
}
Vec2 invert_spherical_cap(const Vec3& w, double cos_max) {
  return {(1.0 - w.z) / (1.0 - cos_max), azimuth(w) * inv_two_pi};
}

}  // namespace shadelab
