#include "shadelab/scene/default_scene.h"

#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "shadelab/scene/scene_json.h"

namespace shadelab {

namespace {

// The content of scenes/default.json.
constexpr std::string_view default_json = R"json({
  "$schema": "scene.schema.json",
  "description": "shadelab's default scene: one sphere per BRDF model family on wet and dry asphalt, contre-jour under a low sun (the zoo article's photo). Materials are named after their models.",
  "units": "radiometric",
  "camera": {
    "position": [0, 1.8, 10],
    "look_at": [0, 0.4, 0],
    "up": [0, 1, 0],
    "fov": 35,
    "width": 640,
    "height": 360
  },
  "render": { "spp": 64, "max_depth": 8, "seed": 1, "threads": 0, "rr_depth": 3 },
  "textures": {
    "asphalt_kd": { "procedural": "asphalt-diffuse", "size": 1024, "seed": 7, "albedo": 0.08 },
    "asphalt_gloss": { "procedural": "asphalt-gloss", "size": 1024, "seed": 7, "wet_fraction": 0.3 }
  },
  "materials": {
    "asphalt": {
      "model": "cook-torrance",
      "params": { "kd": 0.08, "ks": 1, "d": "blinn-phong", "g": "kelemen", "f": "schlick", "f0": 0.04, "n": 4 },
      "textures": { "kd": "asphalt_kd", "gloss": "asphalt_gloss" },
      "gloss_range": [2, 8192],
      "uv_scale": 200
    },
    "lambert": { "model": "lambert", "params": { "kd": [0.75, 0.75, 0.72] } },
    "phong-modified": { "model": "phong-modified", "params": { "kd": [0.6, 0.1, 0.08], "ks": 0.2, "n": 200 } },
    "blinn-phong-modified": {
      "model": "blinn-phong-modified",
      "params": { "kd": [0.1, 0.35, 0.12], "ks": 0.2, "n": 300 }
    },
    "cook-torrance": {
      "model": "cook-torrance",
      "params": { "kd": 0, "ks": 1, "d": "beckmann", "g": "smith", "f": "schlick", "f0": [1.0, 0.78, 0.34], "m": 0.15 }
    },
    "minimalist-cook-torrance": {
      "model": "minimalist-cook-torrance",
      "params": { "kd": [0.05, 0.15, 0.5], "ks": 0.04, "n": 800 }
    },
    "ward-anisotropic": {
      "model": "ward-anisotropic",
      "params": { "kd": 0.05, "ks": 0.6, "alpha_x": 0.3, "alpha_y": 0.05 }
    },
    "lafortune": { "model": "lafortune", "params": { "kd": [0.4, 0.25, 0.1], "ks": 1, "lobes": [[-1, -1, 1, 20]] } },
    "wrapped-diffuse": { "model": "wrapped-diffuse", "params": { "kd": [0.7, 0.5, 0.3], "w": 0.5 } }
  },
  "shapes": [
    { "type": "quad", "corner": [-1000, 0, 1000], "u": [2000, 0, 0], "v": [0, 0, -2000], "material": "asphalt" },
    { "type": "sphere", "center": [-4.2, 0.5, 0], "radius": 0.5, "material": "lambert" },
    { "type": "sphere", "center": [-3.0, 0.5, 0], "radius": 0.5, "material": "phong-modified" },
    { "type": "sphere", "center": [-1.8, 0.5, 0], "radius": 0.5, "material": "blinn-phong-modified" },
    { "type": "sphere", "center": [-0.6, 0.5, 0], "radius": 0.5, "material": "cook-torrance" },
    { "type": "sphere", "center": [0.6, 0.5, 0], "radius": 0.5, "material": "minimalist-cook-torrance" },
    { "type": "sphere", "center": [1.8, 0.5, 0], "radius": 0.5, "material": "ward-anisotropic" },
    { "type": "sphere", "center": [3.0, 0.5, 0], "radius": 0.5, "material": "lafortune" },
    { "type": "sphere", "center": [4.2, 0.5, 0], "radius": 0.5, "material": "wrapped-diffuse" }
  ],
  "environment": {
    "sky": {
      "sun_direction": [0.15, 0.22, -0.96],
      "sun_angular_radius": 0.27,
      "sun_irradiance": [5.0, 4.2, 3.2],
      "zenith": [0.10, 0.18, 0.40],
      "horizon": [0.60, 0.58, 0.55],
      "ground": [0.05, 0.045, 0.04]
    }
  }
}
)json";

}  // namespace

std::string_view default_scene_json() { return default_json; }

Scene default_scene() {
  const auto document = nlohmann::json::parse(default_json);
  auto scene = parse_scene(document, ".", "(built-in default)");
  if (!scene) throw std::logic_error("default scene: " + scene.error().message);
  return std::move(scene).value();
}

}  // namespace shadelab
