// shadelab punctual lights, radiometric: directional (irradiance E_perp, W/m^2), point and spot (intensity
// I, W/sr, inverse-square falloff). Build them from game or photometric units with light/units.h.
//
// Reflected radiance from a punctual light: L_o = f_r E_perp cos(theta_i) (the lecture's rendering
// equation with a delta light), where E_perp = I / r^2 for point and spot lights.
// Spot falloff: the smooth cone of glTF KHR_lights_punctual (its recommended implementation):
//   t = clamp((cos(angle) - cos_outer) / (cos_inner - cos_outer), 0, 1), falloff = t^2.
#pragma once

#include "shadelab/color/rgb.h"
#include "shadelab/core/vec.h"

namespace shadelab {

struct DirectionalLight {
  Vec3 to_light{0.0, 0.0, 1.0};  // unit direction from the scene toward the light
  Rgb irradiance;                // E_perp, W/m^2
  // Game mode only: add the light to the SH9 ambient (D3DX-style, envmap/diffuse/sh.h) instead of shading it per
  // pixel, as engines do for fill lights. The reference renders it exactly either way.
  bool game_sh = false;
};

struct PointLight {
  Vec3 position;
  Rgb intensity;  // W/sr
};

struct SpotLight {
  Vec3 position;
  Vec3 axis{0.0, 0.0, -1.0};  // unit direction the spot points to
  Rgb intensity;              // W/sr on the axis
  double cos_inner = 0.9;     // full intensity inside this cone
  double cos_outer = 0.8;     // zero outside this cone
};

// What a punctual light delivers at a point: the direction toward it, its distance, and E_perp there.
struct LightIncidence {
  Vec3 wi;
  double distance = 0.0;  // infinite for directional lights
  Rgb irradiance_perp;
};

LightIncidence incident(const DirectionalLight& light, const Vec3& p);
LightIncidence incident(const PointLight& light, const Vec3& p);
LightIncidence incident(const SpotLight& light, const Vec3& p);

double spot_falloff(double cos_angle, double cos_inner, double cos_outer);

}  // namespace shadelab
