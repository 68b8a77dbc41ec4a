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

// One triangle facing +Z (POSITION, TEXCOORD_0) in a data-URI buffer; MATERIAL is the material's JSON, EXTRA more
// top-level keys (with a leading comma).
std::string gltf(const std::string& material, const std::string& extra = "") {
  return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}],
  "materials": [)" + material + "]" + extra + "}";
}

fs::path write_scene(const std::string& name, const std::string& material, const std::string& extra = "") {
  const fs::path dir = shadelab::testing::process_temp_dir("shadelab_cli_gltf_" + name);
  std::ofstream(dir / "m.gltf") << gltf(material, extra);
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

// glTF extensions (docs/scene-format.md, "glTF materials"): an unknown one in extensionsRequired is exit 2 with one
// line naming it; in extensionsUsed only, one warning line and the render.
TEST(CliGltf, RequiredUnknownExtensionIsExitTwoNamingIt) {
  const fs::path dir = write_scene("required", R"({"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1}}})",
                                   R"(, "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_volume"],
                                      "extensionsRequired": ["KHR_materials_clearcoat", "KHR_materials_volume"])");
  const auto r = run("render " + (dir / "scene.json").string() + " --spp 1 --no-png --out " + (dir / "out.exr").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("m.gltf: extensionsRequired: extension 'KHR_materials_volume' is not supported"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

TEST(CliGltf, UsedUnknownExtensionIsOneWarningLine) {
  const fs::path dir = write_scene("used", R"({"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1]}}})",
                                   R"(, "extensionsUsed": ["KHR_materials_sheen", "KHR_materials_volume"],
                                      "extensionsRequired": ["KHR_materials_sheen"])");
  const auto r = run("render " + (dir / "scene.json").string() + " --spp 1 --no-png --out " + (dir / "out.exr").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("shadelab: warning: " + (dir / "scene.json").string() + ": /shapes/0/file: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("m.gltf: extensionsUsed: extension KHR_materials_volume is not read"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
  EXPECT_TRUE(fs::exists(dir / "out.exr"));
}

TEST(CliGltf, TheExtensionsSceneRendersInBothModes) {
  const fs::path dir = shadelab::testing::process_temp_dir("shadelab_cli_gltf_scene");
  const std::string scene = std::string(SHADELAB_SCENES_DIR) + "/gltf_extensions.json";
  auto r = run("render " + scene + " --spp 1 --threads 2 --no-png --out " + (dir / "ref.exr").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir / "ref.exr"));
  r = run("render " + scene + " --mode game --spp 1 --env-size 16 --specular-size 16 --no-png --out " + (dir / "game.exr").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "game.exr"));
}

}  // namespace
