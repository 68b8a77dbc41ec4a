#include "shadelab/light/sphere_light.h"

#include <algorithm>
#include <cmath>

#include "shadelab/core/constants.h"

namespace shadelab {

double sphere_irradiance_factor(double cos_theta, double sin_beta) {
  cos_theta = std::clamp(cos_theta, -1.0, 1.0);
  sin_beta = std::clamp(sin_beta, 0.0, 1.0);
  const double s2 = sin_beta * sin_beta;
  const double cos_beta = std::sqrt(1.0 - s2);
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  // theta <= pi/2 - beta  <=>  cos(theta) >= sin(beta): the whole cap is above the horizon.
  if (cos_theta >= sin_beta) return pi * s2 * cos_theta;  // E = pi L sin^2(beta) cos(theta)
  // theta >= pi/2 + beta  <=>  cos(theta) <= -sin(beta): the whole cap is below.
  if (cos_theta <= -sin_beta) return 0.0;
  // Straddling (Snyder 1996). Here sin(theta) >= cos(beta) > 0 unless beta = pi/2 (the sphere touches p).
  // beta = pi/2: the cap is the hemisphere about the centre direction, E / L = pi (1 + cos(theta)) / 2.
  if (cos_beta == 0.0) return pi * 0.5 * (1.0 + cos_theta);
  const double x = cos_beta / sin_beta;  // cot(beta)
  const double y = std::clamp(-x * cos_theta / sin_theta, -1.0, 1.0);
  const double s = sin_theta * std::sqrt(1.0 - y * y);
  return (cos_theta * std::acos(y) - x * s) * s2 + std::atan(s / x);
}

Rgb sphere_light_irradiance(const SphereLight& light, const Vec3& p, const Vec3& n) {
  const Vec3 d = light.center - p;
  const double dist = length(d);
  if (dist <= light.radius) return {};
  const double sin_beta = light.radius / dist;
  return light.radiance * sphere_irradiance_factor(dot(n, d / dist), sin_beta);
}

}  // namespace shadelab
