#include "shadelab/light/punctual.h"

#include <algorithm>
#include <limits>

#include "shadelab/kernels/kernels.h"

namespace shadelab {

LightIncidence incident(const DirectionalLight& light, const Vec3&) {
  return {light.to_light, std::numeric_limits<double>::infinity(), light.irradiance};
}

LightIncidence incident(const PointLight& light, const Vec3& p) {
  const Vec3 d = light.position - p;
  const double r2 = dot(d, d);
  const double r = std::sqrt(r2);
  if (r == 0.0) return {{0.0, 0.0, 1.0}, 0.0, {}};  // at the light itself: no defined direction, no light
  return {d / r, r, kernel::point_light_irradiance(light.intensity, r2)};  // E_perp = I / r^2 (game_shading.sl)
}

double spot_falloff(double cos_angle, double cos_inner, double cos_outer) {
  // KHR_lights_punctual: scale = 1 / max(0.001, cos_inner - cos_outer), squared smooth ramp.
  const double scale = 1.0 / std::max(1e-3, cos_inner - cos_outer);
  const double t = std::clamp((cos_angle - cos_outer) * scale, 0.0, 1.0);
  return t * t;
}

LightIncidence incident(const SpotLight& light, const Vec3& p) {
  LightIncidence in = incident(PointLight{light.position, light.intensity}, p);
  if (in.distance == 0.0) return in;
  // The angle from the spot's axis to the shading point is that between the axis and -wi.
  in.irradiance_perp *= spot_falloff(-dot(in.wi, light.axis), light.cos_inner, light.cos_outer);
  return in;
}

}  // namespace shadelab
