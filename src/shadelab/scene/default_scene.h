// shadelab's default scene: one sphere per BRDF model family (lambert, phong-modified,
// blinn-phong-modified, cook-torrance, minimalist-cook-torrance, ward-anisotropic, lafortune,
// wrapped-diffuse) in a row on a large ground quad of the zoo article's wet and dry asphalt: constant
// specular (Schlick F0 = 0.04), all the detail in the gloss map (Cook-Torrance with the normalized
// Blinn-Phong D driven by a procedural asphalt-gloss texture), under the built-in sky with a low sun in
// backlight (contre-jour, as the article's photo). 640 x 360, 64 samples per pixel.
//
// Contract: default_scene() parses default_scene_json() with parse_scene (so the built-in scene exercises
// the scene format), and that text is the content of scenes/default.json (a test checks both are the same
// JSON). It needs no files. A parse failure is a bug in this file: default_scene throws std::logic_error.
#pragma once

#include <string_view>

#include "shadelab/scene/scene.h"

namespace shadelab {

std::string_view default_scene_json();
Scene default_scene();

}  // namespace shadelab
