// glTF materials in a scene (docs/scene-format.md, "glTF materials"): a mesh shape without a "material" brings the
// file's materials as `gltf` materials. The oracle is `gltf` built directly from the glTF 2.0 rules (section 3.9.2)
// and each extension's README: parameter = factor x texel (the named channel; sRGB-decoded for colour textures,
// code / 255 for data), computed here from the codes written into the PNGs, with the sRGB decode written out.
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
#include "shadelab/core/constants.h"
#include "shadelab/render/path_tracer.h"
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

TEST(GltfMaterials, FactorsAndTexturesGiveTheGltfModel) {
  auto s = load(gltf_text(kTextured));
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->meshes.size(), 3u);  // one mesh per material: 0, 1 and the default
  MaterialSet set;
  ASSERT_TRUE(set.prepare(*s));
  BrdfPtr holder;

  const Material& painted = s->materials[static_cast<std::size_t>(s->meshes[0].material)];
  EXPECT_EQ(painted.model, "gltf");
  EXPECT_NE(painted.name.find("painted"), std::string::npos) << painted.name;
  const Brdf* f = set.brdf(s->meshes[0].material, {0.25, 0.75}, holder);
  ASSERT_NE(f, nullptr);
  const auto want = make_brdf(
      "gltf", {{"base_color", rgb(0.9 * decode_srgb(kBase[0] / 255), 0.7 * decode_srgb(kBase[1] / 255),
                                  0.5 * decode_srgb(kBase[2] / 255))},
               {"metallic", num(0.8 * kMetalCode / 255)},
               {"roughness", num(0.6 * kRoughCode / 255)}});
  ASSERT_TRUE(want) << want.error().message;
  expect_same_brdf(*f, **want);

  // Material 1 has no pbrMetallicRoughness, the third primitive no material: both are glTF's defaults
  // (base colour 1, metallic 1, roughness 1).
  const auto defaults = make_brdf("gltf", {{"base_color", "1"}, {"metallic", "1"}, {"roughness", "1"}});
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
  const auto want = make_brdf("gltf", {{"base_color", "0.2,0.4,0.6"}, {"metallic", "0"}, {"roughness", "0.35"}});
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

// ---- the PBR extensions (KHR_materials_*, KHR_texture_transform) -------------------------------------------------

const fs::path kExtensionsDir = fs::path(SHADELAB_SCENES_DIR) / "meshes" / "gltf_extensions";

const Material& material_named(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials) {
    if (m.name.find("(" + name + ")") != std::string::npos) return m;
  }
  ADD_FAILURE() << "no material " << name;
  return s.materials.front();
}

int material_index(const Scene& s, const std::string& name) {
  return static_cast<int>(&material_named(s, name) - s.materials.data());
}

std::string param(const Material& m, const std::string& name) {
  for (const auto& [k, v] : m.params) {
    if (k == name) return v;
  }
  return "(absent)";
}

// The BRDF the scene builds for `material` at uv against gltf built from `params` (the rest the model's defaults).
void expect_gltf_at(const Scene& s, int material, Vec2 uv, const ParamAssignments& params) {
  MaterialSet set;
  ASSERT_TRUE(set.prepare(s));
  BrdfPtr holder;
  const Brdf* f = set.brdf(material, uv, holder);
  ASSERT_NE(f, nullptr);
  const auto want = make_brdf("gltf", params);
  ASSERT_TRUE(want) << want.error().message;
  SCOPED_TRACE("material " + s.materials[static_cast<std::size_t>(material)].name + " at uv (" + num(uv.x) + ", " + num(uv.y) + ")");
  expect_same_brdf(*f, **want);
}

TEST(GltfExtensions, EachExtensionsFactorReachesItsParameter) {
  auto s = load(gltf_text(R"({"name": "all", "emissiveFactor": [0.5, 0.25, 1],
    "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.4, 0.5, 1], "metallicFactor": 0.25, "roughnessFactor": 0.45},
    "extensions": {
      "KHR_materials_ior": {"ior": 1.33},
      "KHR_materials_specular": {"specularFactor": 0.7, "specularColorFactor": [2, 1, 0.5]},
      "KHR_materials_clearcoat": {"clearcoatFactor": 0.9, "clearcoatRoughnessFactor": 0.15},
      "KHR_materials_sheen": {"sheenColorFactor": [0.2, 0.3, 0.4], "sheenRoughnessFactor": 0.55},
      "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 7.0},
      "KHR_materials_emissive_strength": {"emissiveStrength": 4}}})"));
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_TRUE(s->warnings.empty());
  const Material& m = material_named(*s, "all");
  EXPECT_EQ(m.model, "gltf");
  EXPECT_EQ(param(m, "ior"), "1.33");
  EXPECT_EQ(param(m, "specular"), "0.7");
  EXPECT_EQ(param(m, "specular_color"), "2,1,0.5");
  EXPECT_EQ(param(m, "clearcoat"), "0.9");
  EXPECT_EQ(param(m, "clearcoat_roughness"), "0.15");
  EXPECT_EQ(param(m, "sheen_color"), "0.2,0.3,0.4");
  EXPECT_EQ(param(m, "sheen_roughness"), "0.55");
  EXPECT_EQ(param(m, "anisotropy_strength"), "0.6");
  EXPECT_EQ(std::stod(param(m, "anisotropy_rotation")), std::remainder(7.0, 2.0 * pi));  // the same direction
  EXPECT_EQ(param(m, "emissive"), "0.5,0.25,1");
  EXPECT_EQ(param(m, "emissive_strength"), "4");
  EXPECT_TRUE(m.param_textures.empty());
  // KHR_materials_emissive_strength: emissiveFactor x emissiveStrength is the material's emission (game units:
  // radiance is the same number).
  EXPECT_EQ(m.emission.r, 2.0);
  EXPECT_EQ(m.emission.g, 1.0);
  EXPECT_EQ(m.emission.b, 4.0);
  expect_gltf_at(*s, material_index(*s, "all"), {0.5, 0.5},
                 {{"base_color", "0.3,0.4,0.5"}, {"metallic", "0.25"}, {"roughness", "0.45"}, {"ior", "1.33"},
                  {"specular", "0.7"}, {"specular_color", "2,1,0.5"}, {"clearcoat", "0.9"},
                  {"clearcoat_roughness", "0.15"}, {"sheen_color", "0.2,0.3,0.4"}, {"sheen_roughness", "0.55"},
                  {"anisotropy_strength", "0.6"}, {"anisotropy_rotation", num(std::remainder(7.0, 2.0 * pi))}});
}

// The committed scene's glTF (scripts/make_gltf_extensions_scene.py): every extension's textures, with the
// channels and colour spaces of the specifications. Texel centres: u = (x + 0.5) / 8 of the 8 x 8 images, so that
// the bilinear lookup returns one texel; the textures are constant in each half (x < 4, x >= 4).
TEST(GltfExtensions, EachExtensionsTextureReachesItsParameter) {
  const fs::path d = fs::path(::testing::TempDir()) / ("gltf_extensions_" + std::to_string(::getpid()));
  fs::create_directories(d);
  std::ofstream(d / "scene.json") << R"({"shapes": [{"type": "mesh", "file": ")" + (kExtensionsDir / "spheres.gltf").string() + R"("}]})";
  auto s = load_scene(d / "scene.json");
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->materials.size(), 4u);
  EXPECT_TRUE(s->warnings.empty());
  const Vec2 left{1.5 / 8, 4.5 / 8};
  const Vec2 right{6.5 / 8, 4.5 / 8};
  auto srgb = [](double r, double g, double b) { return Rgb{decode_srgb(r / 255), decode_srgb(g / 255), decode_srgb(b / 255)}; };

  {  // KHR_materials_clearcoat: clearcoatTexture R (with KHR_texture_transform scale [4, 1]), clearcoatRoughnessTexture G
    const Material& m = material_named(*s, "clearcoat");
    ASSERT_EQ(m.param_textures.size(), 2u);
    EXPECT_EQ(m.param_textures[0].param, "clearcoat");
    EXPECT_EQ(m.param_textures[0].channel, 0);
    EXPECT_EQ(m.param_textures[0].transform.m00, 4.0);
    EXPECT_EQ(m.param_textures[1].param, "clearcoat_roughness");
    EXPECT_EQ(m.param_textures[1].channel, 1);
    const ParamAssignments base = {{"base_color", "0.6,0.05,0.03"}, {"metallic", "0"}, {"roughness", "0.5"}};
    // u = 3.5 / 32: the transform's u' = 0.4375 is the centre of stripe texel 3 (R = 64); u = 4.5 / 32: texel 4 (255).
    // Without the transform both would read between texels 0 and 1. Roughness: the left half, G = 64.
    for (const auto& [u, code] : {std::pair{3.5 / 32, 64.0}, std::pair{4.5 / 32, 255.0}}) {
      ParamAssignments p = base;
      p.push_back({"clearcoat", num(1.0 * code / 255)});
      p.push_back({"clearcoat_roughness", num(0.4 * 64 / 255)});
      expect_gltf_at(*s, material_index(*s, "clearcoat"), {u, 4.5 / 8}, p);
    }
  }
  {  // KHR_materials_sheen: sheenColorTexture sRGB RGB, sheenRoughnessTexture alpha
    const Material& m = material_named(*s, "sheen");
    ASSERT_EQ(m.param_textures.size(), 2u);
    EXPECT_EQ(m.param_textures[0].param, "sheen_color");
    EXPECT_EQ(m.param_textures[0].channel, -1);
    EXPECT_EQ(m.param_textures[1].param, "sheen_roughness");
    const Texture& alpha = s->textures[static_cast<std::size_t>(m.param_textures[1].texture)];
    EXPECT_TRUE(alpha.data);
    EXPECT_NE(alpha.name.find("(alpha)"), std::string::npos) << alpha.name;
    const ParamAssignments base = {{"base_color", "0.05,0.05,0.25"}, {"metallic", "0"}, {"roughness", "0.8"}};
    const Rgb white = srgb(255, 255, 255);
    const Rgb pink = srgb(255, 160, 200);
    ParamAssignments l = base;
    l.push_back({"sheen_color", rgb(0.9 * white.r, 0.8 * white.g, 0.7 * white.b)});
    l.push_back({"sheen_roughness", num(0.6 * 128 / 255)});
    expect_gltf_at(*s, material_index(*s, "sheen"), left, l);
    ParamAssignments r = base;
    r.push_back({"sheen_color", rgb(0.9 * pink.r, 0.8 * pink.g, 0.7 * pink.b)});
    r.push_back({"sheen_roughness", num(0.6 * 255 / 255)});
    expect_gltf_at(*s, material_index(*s, "sheen"), right, r);
  }
  {  // KHR_materials_ior and KHR_materials_specular: specularTexture alpha, specularColorTexture sRGB RGB
    const Material& m = material_named(*s, "specular");
    EXPECT_EQ(param(m, "ior"), "1.8");
    ASSERT_EQ(m.param_textures.size(), 2u);
    EXPECT_EQ(m.param_textures[0].param, "specular");
    EXPECT_EQ(m.param_textures[1].param, "specular_color");
    const ParamAssignments base = {{"base_color", "0.05,0.3,0.1"}, {"metallic", "0"}, {"roughness", "0.3"}, {"ior", "1.8"}};
    const Rgb gold = srgb(255, 200, 100);
    ParamAssignments l = base;
    l.push_back({"specular", num(0.8)});
    l.push_back({"specular_color", rgb(1.0, 0.9, 0.8)});
    expect_gltf_at(*s, material_index(*s, "specular"), left, l);
    ParamAssignments r = base;
    r.push_back({"specular", num(0.8 * 64 / 255)});
    r.push_back({"specular_color", rgb(1.0 * gold.r, 0.9 * gold.g, 0.8 * gold.b)});
    expect_gltf_at(*s, material_index(*s, "specular"), right, r);
  }
  {  // KHR_materials_anisotropy: anisotropyTexture RG direction in [-1, 1] (turns the rotation), B x strength
    const Material& m = material_named(*s, "anisotropy");
    ASSERT_EQ(m.param_textures.size(), 1u);
    EXPECT_EQ(m.param_textures[0].use, ParamTexture::Use::anisotropy);
    const ParamAssignments base = {{"base_color", "0.95,0.93,0.88"}, {"metallic", "1"}, {"roughness", "0.35"}};
    const double half = static_cast<double>(static_cast<float>(128.0 / 255));  // the texel as the image stores it
    ParamAssignments l = base;
    l.push_back({"anisotropy_strength", num(0.8)});
    l.push_back({"anisotropy_rotation", num(0.5 + std::atan2(2 * half - 1, 1.0))});
    expect_gltf_at(*s, material_index(*s, "anisotropy"), left, l);
    ParamAssignments r = base;
    r.push_back({"anisotropy_strength", num(0.8 * half)});
    r.push_back({"anisotropy_rotation", num(0.5 + std::atan2(1.0, 2 * half - 1))});
    expect_gltf_at(*s, material_index(*s, "anisotropy"), right, r);
  }
}

TEST(GltfExtensions, TextureTransformIsTheSpecificationsMatrix) {
  // KHR_texture_transform's README example: offset [0, 1], rotation pi/2, scale [0.5, 0.5] "utilizes only the lower
  // left quadrant of the source image, rotated clockwise 90 degrees" (uv (0, 0) is the image's top-left corner).
  const UvTransform t = make_gltf_uv_transform({0.0, 1.0}, pi / 2, {0.5, 0.5});
  const Vec2 corners[4][2] = {{{0, 0}, {0, 1}}, {{1, 0}, {0, 0.5}}, {{0, 1}, {0.5, 1}}, {{1, 1}, {0.5, 0.5}}};
  for (const auto& [in, want] : corners) {
    const Vec2 got = t.apply(in);
    EXPECT_NEAR(got.x, want.x, 1e-15) << in.x << " " << in.y;
    EXPECT_NEAR(got.y, want.y, 1e-15) << in.x << " " << in.y;
  }
  // Offset and scale alone: u' = offset + scale u.
  const UvTransform s = make_gltf_uv_transform({0.25, -0.5}, 0.0, {2.0, 3.0});
  EXPECT_EQ(s.apply({0.5, 0.5}).x, 1.25);
  EXPECT_EQ(s.apply({0.5, 0.5}).y, 1.0);
}

TEST(GltfExtensions, RequiredUnknownIsAnErrorUsedUnknownAWarning) {
  const std::string plain = R"({"name": "plain"})";
  auto s = load(gltf_text(plain, plain, R"(, "extensionsUsed": ["KHR_materials_volume"], "extensionsRequired": ["KHR_materials_volume"])"));
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("m.gltf: extensionsRequired: extension 'KHR_materials_volume' is not supported"),
            std::string::npos)
      << s.error().message;
  EXPECT_EQ(s.error().message.find('\n'), std::string::npos);
  // The six material extensions and KHR_texture_transform may be required.
  s = load(gltf_text(plain, plain,
                     R"(, "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular",
                          "KHR_materials_ior", "KHR_materials_emissive_strength", "KHR_materials_anisotropy", "KHR_texture_transform"],
                         "extensionsRequired": ["KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular",
                          "KHR_materials_ior", "KHR_materials_emissive_strength", "KHR_materials_anisotropy", "KHR_texture_transform"])"));
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_TRUE(s->warnings.empty());
  // Used only: loads, with one warning line naming what is not read (and not what is).
  s = load(gltf_text(plain, plain, R"(, "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_volume", "EXT_x"])"));
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->warnings.size(), 1u);
  const std::string& w = s->warnings[0];
  EXPECT_NE(w.find("scene.json: /shapes/0/file: "), std::string::npos) << w;
  EXPECT_NE(w.find("m.gltf: extensionsUsed: extensions KHR_materials_volume, EXT_x are not read"), std::string::npos) << w;
  EXPECT_EQ(w.find("clearcoat"), std::string::npos) << w;
  EXPECT_EQ(w.find('\n'), std::string::npos) << w;
}

TEST(GltfExtensions, MalformedExtensionFieldsGiveOneLineNamingTheField) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"extensions": {"KHR_materials_ior": {"ior": 0.5}}})", "/materials/0/extensions/KHR_materials_ior/ior"},
      {R"({"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 2}}})",
       "/materials/0/extensions/KHR_materials_clearcoat/clearcoatFactor"},
      {R"({"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1]}}})",
       "/materials/0/extensions/KHR_materials_sheen/sheenColorFactor"},
      {R"({"extensions": {"KHR_materials_specular": {"specularColorFactor": [1, -1, 1]}}})",
       "/materials/0/extensions/KHR_materials_specular/specularColorFactor/1"},
      {R"({"extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": -0.5}}})",
       "/materials/0/extensions/KHR_materials_anisotropy/anisotropyStrength"},
      {R"({"extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": -1}}})",
       "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength"},
      {R"({"extensions": {"KHR_materials_clearcoat": {"clearcoatTexture": {"index": 9}}}})",
       "/materials/0/extensions/KHR_materials_clearcoat/clearcoatTexture/index"},
      {R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [1, "x"]}}}}})",
       "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/scale/1"},
      {R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1}}}}})",
       "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/texCoord"},
      {R"({"emissiveFactor": [2, 0, 0]})", "/materials/0/emissiveFactor/0"},
  };
  for (const auto& [material, field] : cases) {
    auto s = load(gltf_text(material));
    ASSERT_FALSE(s) << field;
    EXPECT_NE(s.error().message.find("m.gltf: " + field + ": "), std::string::npos) << s.error().message;
    EXPECT_EQ(s.error().message.find('\n'), std::string::npos) << s.error().message;
  }
}

// The scene format's own materials: textures by parameter name for gltf, principled-v1 and layered.
TEST(SceneParamTextures, ColourRoughnessAndWeightParametersTakeTextures) {
  const fs::path d = folder();  // base colour.png (200, 100, 50), mr.png (0, 128, 192)
  std::ofstream(d / "scene.json") << R"({
    "textures": {"colour": {"file": "base colour.png"}, "data": {"file": "mr.png", "data": true}},
    "materials": {
      "g": {"model": "gltf", "params": {"clearcoat": 0.5, "sheen_color": [1, 0.5, 0.25], "roughness": 0.5},
            "textures": {"clearcoat": {"texture": "data", "channel": "b"}, "sheen_color": "colour",
                         "roughness": {"texture": "data", "channel": "g"}}},
      "p": {"model": "principled-v1", "params": {"roughness": 0.8, "clearcoat": 1},
            "textures": {"roughness": {"texture": "data", "channel": "g"}, "clearcoat": {"texture": "data", "channel": "b"},
                         "base_color": "colour"}},
      "l": {"model": "layered", "params": {"coat_roughness": 0.4, "coat_color": 1},
            "textures": {"coat_roughness": {"texture": "data", "channel": "b"}, "coat_color": "colour"}}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "g"},
               {"type": "sphere", "center": [3, 0, 0], "radius": 1, "material": "p"},
               {"type": "sphere", "center": [6, 0, 0], "radius": 1, "material": "l"}]})";
  auto s = load_scene(d / "scene.json");
  ASSERT_TRUE(s) << s.error().message;
  MaterialSet set;
  ASSERT_TRUE(set.prepare(*s));
  const double b = kMetalCode / 255;
  const double g = kRoughCode / 255;
  const Rgb c{decode_srgb(kBase[0] / 255), decode_srgb(kBase[1] / 255), decode_srgb(kBase[2] / 255)};
  BrdfPtr holder;
  auto check = [&](const char* name, const char* model, const ParamAssignments& params) {
    int index = -1;
    for (std::size_t i = 0; i < s->materials.size(); ++i) {
      if (s->materials[i].name == name) index = static_cast<int>(i);
    }
    ASSERT_GE(index, 0) << name;
    const Brdf* f = set.brdf(index, {0.3, 0.6}, holder);
    const auto want = make_brdf(model, params);
    ASSERT_TRUE(want) << want.error().message;
    SCOPED_TRACE(name);
    expect_same_brdf(*f, **want);
  };
  check("g", "gltf", {{"clearcoat", num(0.5 * b)}, {"sheen_color", rgb(c.r, 0.5 * c.g, 0.25 * c.b)}, {"roughness", num(0.5 * g)}});
  check("p", "principled-v1", {{"roughness", num(0.8 * g)}, {"clearcoat", num(b)}, {"base_color", rgb(0.8 * c.r, 0.8 * c.g, 0.8 * c.b)}});
  check("l", "layered", {{"coat_roughness", num(0.4 * b)}, {"coat_color", rgb(c.r, c.g, c.b)}});

  // Errors name the field: a number parameter with a colour texture, a channel on a colour, a parameter the
  // model does not have, a choice parameter.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {R"("roughness": "colour")", "/materials/g/textures/roughness: texture 'colour' is a colour texture"},
      {R"("sheen_color": {"texture": "colour", "channel": "r"})", "/materials/g/textures/sheen_color/channel: "},
      {R"("coat_roughness": "data")", "/materials/g/textures/coat_roughness: unknown key 'coat_roughness'"},
      {R"("sheen_visibility": "data")", "/materials/g/textures/sheen_visibility: unknown key"},
      {R"("roughness": {"texture": "data", "channel": "a"})", "/materials/g/textures/roughness/channel: "},
  };
  for (const auto& [textures, want] : bad) {
    std::ofstream(d / "bad.json") << R"({"textures": {"colour": {"file": "base colour.png"}, "data": {"file": "mr.png", "data": true}},
      "materials": {"g": {"model": "gltf", "textures": {)" + textures + R"(}}}})";
    auto r = load_scene(d / "bad.json");
    ASSERT_FALSE(r) << textures;
    EXPECT_NE(r.error().message.find(want), std::string::npos) << r.error().message;
  }
}

// scenes/gltf_extensions.json: the committed glTF under the forest HDRI loads and renders (small, few samples).
TEST(GltfExtensions, TheExampleSceneRenders) {
  auto s = load_scene(fs::path(SHADELAB_SCENES_DIR) / "gltf_extensions.json");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->meshes.size(), 4u);
  EXPECT_TRUE(s->warnings.empty());
  s->camera.width = 64;
  s->camera.height = 24;
  RenderOptions o;
  o.spp = 2;
  o.threads = 2;
  auto r = render_scene(*s, o);
  ASSERT_TRUE(r) << r.error().message;
  double sum = 0.0;
  for (float v : r->beauty.data) {
    ASSERT_TRUE(std::isfinite(v));
    sum += static_cast<double>(v);
  }
  EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace shadelab
