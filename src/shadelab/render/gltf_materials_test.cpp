// glTF pbrMetallicRoughness materials in a scene (docs/scene-format.md, "glTF materials"): a mesh shape without
// a "material" brings the file's materials, mapped to `filament`. The oracle is `filament` built directly from
// the glTF 2.0 rules (section 3.9.2): base_color = baseColorFactor x the sRGB-decoded baseColorTexture texel,
// perceptual_roughness = roughnessFactor x G / 255, metallic = metallicFactor x B / 255 of the
// metallicRoughnessTexture, reflectance 0.5 (F0 = 0.04), computed here from the codes written into the PNGs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/image/image_io.h"
#include "shadelab/render/materials.h"
#include "shadelab/scene/scene_json.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;

// IEC 61966-2-1 sRGB decode, written out here (the oracle does not call the library's).
double decode_srgb(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned v = (bytes[i] << 16) | ((i + 1 < bytes.size() ? bytes[i + 1] : 0) << 8) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[v & 63] : '=';
  }
  return out;
}

// One triangle (POSITION, TEXCOORD_0) in a data-URI buffer: 36 bytes of positions, 24 of uvs.
std::string triangle_buffer() {
  const float data[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
  std::vector<unsigned char> bytes(sizeof(data));
  std::memcpy(bytes.data(), data, sizeof(data));
  return "data:application/octet-stream;base64," + base64(bytes);
}

// A glTF whose mesh has three primitives on the same triangle: material 0, material 1, and none.
std::string gltf_text(const std::string& material0, const std::string& material1 = R"({"name": "plain"})",
                      const std::string& extra = "") {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0},
                             {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 1},
                             {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}}]}],
  "buffers": [{"byteLength": 60, "uri": ")" +
         triangle_buffer() + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}],
  "images": [{"uri": "base%20colour.png"}, {"uri": "mr.png"}],
  "textures": [{"source": 0}, {"source": 1}],
  "materials": [)" +
         material0 + ", " + material1 + "]" + extra + "}";
}

const char* const kTextured = R"({"name": "painted", "pbrMetallicRoughness": {
    "baseColorFactor": [0.9, 0.7, 0.5, 1.0], "baseColorTexture": {"index": 0},
    "metallicFactor": 0.8, "roughnessFactor": 0.6, "metallicRoughnessTexture": {"index": 1}}})";

// The PNG codes the test writes: base colour (200, 100, 50), metallic-roughness G = 128, B = 192.
constexpr double kBase[3] = {200, 100, 50};
constexpr double kRoughCode = 128;
constexpr double kMetalCode = 192;

// A constant 2 x 2 PNG whose 8-bit codes are `codes` (write_image encodes linear values to sRGB codes).
void write_png(const fs::path& path, const double codes[3]) {
  Image image(2, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 2; ++x) image.set(x, y, {decode_srgb(codes[0] / 255), decode_srgb(codes[1] / 255), decode_srgb(codes[2] / 255)});
  }
  ASSERT_TRUE(write_image(image, path));
}

fs::path folder() {
  const fs::path d = fs::path(::testing::TempDir()) / ("gltf_materials_" + std::to_string(::getpid()));
  fs::create_directories(d);
  const double mr[3] = {0, kRoughCode, kMetalCode};
  write_png(d / "base colour.png", kBase);
  write_png(d / "mr.png", mr);
  return d;
}

Result<Scene> load(const std::string& gltf, const std::string& shape = R"({"type": "mesh", "file": "m.gltf"})") {
  const fs::path d = folder();
  std::ofstream(d / "m.gltf") << gltf;
  const std::string scene = R"({"shapes": [)" + shape + "]}";
  std::ofstream(d / "scene.json") << scene;
  return load_scene(d / "scene.json");
}

void expect_same_brdf(const Brdf& got, const Brdf& want) {
  const Vec3 pairs[4][2] = {{{0.3, -0.2, 0.9}, {-0.5, 0.1, 0.6}},
                            {{0.0, 0.0, 1.0}, {0.0, 0.0, 1.0}},
                            {{0.7, 0.1, 0.2}, {-0.6, -0.3, 0.3}},
                            {{0.1, 0.9, 0.05}, {0.2, -0.8, 0.4}}};
  for (const auto& p : pairs) {
    const Vec3 wi = normalize(p[0]);
    const Vec3 wo = normalize(p[1]);
    const Rgb a = got.eval(wi, wo);
    const Rgb b = want.eval(wi, wo);
    // Texels are float32 (Image): 6e-8 relative rounding in the parameters, well inside 1e-6 of f_r.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-6 * b[c] + 1e-12) << "channel " << c;
  }
}

std::string num(double v) {
  std::ostringstream out;
  out << std::setprecision(17) << v;
  return out.str();
}

std::string rgb(double r, double g, double b) { return num(r) + "," + num(g) + "," + num(b); }

TEST(GltfMaterials, FactorsAndTexturesGiveTheFilamentModel) {
  auto s = load(gltf_text(kTextured));
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->meshes.size(), 3u);  // one mesh per material: 0, 1 and the default
  MaterialSet set;
  ASSERT_TRUE(set.prepare(*s));
  BrdfPtr holder;

  const Material& painted = s->materials[static_cast<std::size_t>(s->meshes[0].material)];
  EXPECT_EQ(painted.model, "filament");
  EXPECT_NE(painted.name.find("painted"), std::string::npos) << painted.name;
  const Brdf* f = set.brdf(s->meshes[0].material, {0.25, 0.75}, holder);
  ASSERT_NE(f, nullptr);
  const auto want = make_brdf(
      "filament", {{"base_color", rgb(0.9 * decode_srgb(kBase[0] / 255), 0.7 * decode_srgb(kBase[1] / 255),
                                      0.5 * decode_srgb(kBase[2] / 255))},
                   {"metallic", num(0.8 * kMetalCode / 255)},
                   {"perceptual_roughness", num(0.6 * kRoughCode / 255)},
                   {"reflectance", "0.5"}});
  ASSERT_TRUE(want) << want.error().message;
  expect_same_brdf(*f, **want);

  // Material 1 has no pbrMetallicRoughness, the third primitive no material: both are glTF's defaults
  // (base colour 1, metallic 1, roughness 1).
  const auto defaults = make_brdf("filament", {{"base_color", "1"}, {"metallic", "1"}, {"perceptual_roughness", "1"}});
  ASSERT_TRUE(defaults);
  for (std::size_t m = 1; m < 3; ++m) {
    const Brdf* g = set.brdf(s->meshes[m].material, {0.5, 0.5}, holder);
    ASSERT_NE(g, nullptr);
    expect_same_brdf(*g, **defaults);
  }
}

TEST(GltfMaterials, FactorsAloneAndTheShapesMaterialWins) {
  auto s = load(gltf_text(R"({"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 0.5],
                                 "metallicFactor": 0, "roughnessFactor": 0.35}})"));
  ASSERT_TRUE(s) << s.error().message;
  MaterialSet set;
  ASSERT_TRUE(set.prepare(*s));
  BrdfPtr holder;
  const auto want = make_brdf("filament", {{"base_color", "0.2,0.4,0.6"}, {"metallic", "0"}, {"perceptual_roughness", "0.35"}});
  ASSERT_TRUE(want);
  expect_same_brdf(*set.brdf(s->meshes[0].material, {0.5, 0.5}, holder), **want);

  // A shape that names a material keeps it for every triangle (one mesh), as before.
  const fs::path d = folder();
  std::ofstream(d / "m.gltf") << gltf_text(kTextured);
  std::ofstream(d / "scene.json")
      << R"({"materials": {"red": {"model": "lambert", "params": {"kd": [0.7, 0.1, 0.1]}}},
             "shapes": [{"type": "mesh", "file": "m.gltf", "material": "red"}]})";
  auto named = load_scene(d / "scene.json");
  ASSERT_TRUE(named) << named.error().message;
  ASSERT_EQ(named->meshes.size(), 1u);
  EXPECT_EQ(named->materials[static_cast<std::size_t>(named->meshes[0].material)].name, "red");
}

TEST(GltfMaterials, MalformedFieldsGiveOneLineNamingTheField) {
  struct Case {
    std::string material0;
    std::string extra;
    std::string field;
  };
  const std::vector<Case> cases = {
      {R"({"pbrMetallicRoughness": {"metallicFactor": 2}})", "", "/materials/0/pbrMetallicRoughness/metallicFactor"},
      {R"({"pbrMetallicRoughness": {"roughnessFactor": "rough"}})", "", "/materials/0/pbrMetallicRoughness/roughnessFactor"},
      {R"({"pbrMetallicRoughness": {"baseColorFactor": [1, 1, -0.5, 1]}})", "",
       "/materials/0/pbrMetallicRoughness/baseColorFactor/2"},
      {R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 7}}})", "",
       "/materials/0/pbrMetallicRoughness/baseColorTexture/index"},
      {R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}}})", "",
       "/materials/0/pbrMetallicRoughness/baseColorTexture/texCoord"},
      {R"({"pbrMetallicRoughness": {"metallicRoughnessTexture": {}}})", "",
       "/materials/0/pbrMetallicRoughness/metallicRoughnessTexture/index"},
  };
  for (const Case& c : cases) {
    auto s = load(gltf_text(c.material0, R"({"name": "plain"})", c.extra));
    ASSERT_FALSE(s) << c.field;
    const std::string& message = s.error().message;
    EXPECT_NE(message.find("m.gltf: " + c.field + ": "), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  // An image that is not there, an embedded image, an unused malformed material.
  std::string missing = gltf_text(kTextured);
  missing.replace(missing.find("mr.png"), 6, "gone.png");
  auto s = load(missing);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("/images/1/uri: "), std::string::npos) << s.error().message;
  std::string embedded = gltf_text(kTextured);
  embedded.replace(embedded.find(R"("uri": "mr.png")"), 15, R"("uri": "data:image/png;base64,AAAA")");
  s = load(embedded);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("/images/1/uri: embedded images"), std::string::npos) << s.error().message;
  s = load(gltf_text(kTextured, R"({"pbrMetallicRoughness": {"metallicFactor": -1}})"));
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("/materials/1/pbrMetallicRoughness/metallicFactor"), std::string::npos)
      << s.error().message;
  // OBJ files have no materials shadelab reads: the shape must name one.
  std::ofstream(folder() / "t.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  s = load("{}", R"({"type": "mesh", "file": "t.obj"})");
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("/shapes/0/material: required key is missing"), std::string::npos)
      << s.error().message;
}

}  // namespace
}  // namespace shadelab
