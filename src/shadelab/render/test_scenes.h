// Scenes built in code for the renderer's tests.
#pragma once

#include "shadelab/scene/scene.h"

namespace shadelab::testing {

inline int add_material(Scene& s, const std::string& model, ParamAssignments params, Rgb emission = {}) {
  Material m;
  m.name = model + std::to_string(s.materials.size());
  m.model = model;
  m.params = std::move(params);
  m.emission = emission;
  s.materials.push_back(std::move(m));
  return static_cast<int>(s.materials.size()) - 1;
}

// The white-furnace scene: a unit sphere of one material at the origin under a uniform environment of
// radiance L. It cannot see itself, so every pixel on it is L times the directional albedo at its N.V.
inline Scene furnace_sphere(const std::string& model, ParamAssignments params, int max_depth = 1, double radiance = 0.5) {
  Scene s;
  s.environment.kind = Environment::Kind::uniform;
  s.environment.uniform = Rgb::gray(radiance);
  s.spheres.push_back({{0, 0, 0}, 1.0, add_material(s, model, std::move(params))});
  s.settings.max_depth = max_depth;
  return s;
}

// A horizontal square of side 2 * half at height y, facing +Y.
inline QuadShape floor_quad(double half, double y, int material) {
  return {{-half, y, half}, {2.0 * half, 0.0, 0.0}, {0.0, 0.0, -2.0 * half}, material};
}

}  // namespace shadelab::testing
