// shadelab hemisphere light: uniform sky radiance above the horizon plane, uniform ground radiance below.
// For a surface whose normal makes the angle theta with the up direction, the fraction of its cosine-
// weighted hemisphere that sees the sky is (1 + cos(theta)) / 2, so exactly
//   E = pi (L_sky (1 + cos(theta)) / 2 + L_ground (1 - cos(theta)) / 2)
// (the hemisphere lighting of Akenine-Möller, Haines, Hoffman, "Real-Time Rendering", 3rd ed., 8.6.1, which
// games evaluate without the pi in game units). Tested against numeric integration.
#pragma once

#include "shadelab/color/rgb.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/vec.h"

namespace shadelab {

struct HemisphereLight {
  Vec3 up{0.0, 1.0, 0.0};  // world +Y
  Rgb sky;                 // radiance, W m^-2 sr^-1
  Rgb ground;
};

constexpr Rgb hemisphere_irradiance(const Rgb& sky, const Rgb& ground, double cos_theta) {
  return (sky * (0.5 * (1.0 + cos_theta)) + ground * (0.5 * (1.0 - cos_theta))) * pi;
}

inline Rgb hemisphere_irradiance(const HemisphereLight& light, const Vec3& n) {
  return hemisphere_irradiance(light.sky, light.ground, dot(n, light.up));
}

}  // namespace shadelab
