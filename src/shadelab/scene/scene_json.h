// shadelab scene files: the JSON scene format (docs/scene-format.md, scenes/scene.schema.json) read into a
// Scene (scene.h).
//
// Contract:
// - load_scene reads the file and parses it; parse_scene does the same for a document already parsed, with
//   relative file names (meshes, textures, environment maps) resolved against base_dir.
// - The result is a valid Scene (scene.h's contract): every value checked, every light converted from the
//   scene's "units" (game, radiometric or photometric) to radiometry with light/units.h, every material's
//   BRDF built once from its validated parameters, every referenced file read.
// - Every error is ONE line: the file (`source`), the RFC 6901 JSON pointer of the offending field, and
//   what is wrong, e.g.
//     scene.json: /shapes/3/radius: expected a number > 0, got -2
//     scene.json: /materials/ground/params/n: brdf phong: parameter 'n' = -1 is out of range [0, 1e+06]
//   Malformed JSON names the line and column instead of a pointer. Unknown keys, duplicate keys (load_scene
//   only: a parsed document has already lost them), wrong types, non-finite or out-of-range numbers, zero
//   vectors, unknown model, material or texture names and missing files are all errors: a typo never
//   passes silently. Values beyond the scene limits (scene/limits.h: coordinates, lengths, light values,
//   triangles, JSON depth, file sizes) are errors too. Nothing throws, nothing prints.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "shadelab/core/error.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

Result<Scene> load_scene(const std::filesystem::path& path);

Result<Scene> parse_scene(const nlohmann::json& document, const std::filesystem::path& base_dir,
                          const std::string& source);

// The keys a scene document may have at its top level, in the order the documentation lists them.
std::span<const std::string_view> scene_top_level_keys();

}  // namespace shadelab
