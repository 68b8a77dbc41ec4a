// End-to-end: a scene whose glTF mesh brings its own pbrMetallicRoughness materials (docs/scene-format.md,
// "glTF materials") renders; a malformed material field is one line naming the glTF file and the field, exit 2,
// and no image is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::run;

// One triangle facing +Z (POSITION, TEXCOORD_0) in a data-URI buffer; MATERIAL is the material's JSON.
std::string gltf(const std::string& material) {
  return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}],
  "materials": [)" + material + "]}";
}

fs::path write_scene(const std::string& name, const std::string& material) {
  const fs::path dir = shadelab::testing::process_temp_dir("shadelab_cli_gltf_" + name);
  std::ofstream(dir / "m.gltf") << gltf(material);
  std::ofstream(dir / "scene.json") << R"({"units": "radiometric",
    "camera": {"position": [0.3, 0.3, 2], "look_at": [0.3, 0.3, 0], "fov": 40, "width": 16, "height": 16},
    "shapes": [{"type": "mesh", "file": "m.gltf"}],
    "lights": [{"type": "directional", "direction": [0, 0, 1], "intensity": 3}]})";
  return dir;
}

TEST(CliGltf, MaterialsFromTheFileRender) {
  const fs::path dir = write_scene("good", R"({"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1],
                                                 "metallicFactor": 0, "roughnessFactor": 0.5}})");
  const auto r = run("render " + (dir / "scene.json").string() + " --spp 1 --no-png --out " + (dir / "out.exr").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out.exr"));
}

TEST(CliGltf, MalformedMaterialFieldIsExitTwoAndOneLine) {
  const fs::path dir = write_scene("bad", R"({"pbrMetallicRoughness": {"roughnessFactor": 1.5}})");
  const auto r = run("render " + (dir / "scene.json").string() + " --spp 1 --no-png --out " + (dir / "out.exr").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("m.gltf: /materials/0/pbrMetallicRoughness/roughnessFactor: expected a number in [0, 1], got 1.5"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

}  // namespace
