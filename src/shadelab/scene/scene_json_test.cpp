#include "shadelab/scene/scene_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadelab/core/constants.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/srgb.h"
#include "shadelab/light/units.h"
#include "shadelab/scene/default_scene.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path scenes_dir = SHADELAB_SCENES_DIR;

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("shadelab_scene_json_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Parses `text` as the file scene.json in `dir` (relative names resolve there).
Result<Scene> parse_text(const std::string& text, const fs::path& dir = fs::path(::testing::TempDir())) {
  return parse_scene(json::parse(text), dir, "scene.json");
}

// The one-line error of a scene given as text, through load_scene, with the file's full path shortened to
// "scene.json".
std::string load_error(const std::string& text, const fs::path& dir) {
  const fs::path file = dir / "scene.json";
  write_text(file, text);
  auto r = load_scene(file);
  if (r) return "(no error)";
  std::string message = r.error().message;
  const std::string prefix = file.string();
  if (message.rfind(prefix, 0) == 0) message = "scene.json" + message.substr(prefix.size());
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
  return message;
}

std::string error_of(const std::string& text, const fs::path& dir = fs::path(::testing::TempDir())) {
  auto r = parse_text(text, dir);
  if (r) return "(no error)";
  EXPECT_EQ(r.error().message.find('\n'), std::string::npos) << "not one line: " << r.error().message;
  return r.error().message;
}

template <typename T>
const T& light(const Scene& s, std::size_t i) {
  return std::get<T>(s.lights.at(i));
}

// ---- the example scenes -------------------------------------------------------------------------------

TEST(SceneJson, EveryExampleSceneLoads) {
  std::set<std::string> found;
  for (const auto& entry : fs::directory_iterator(scenes_dir)) {
    const fs::path p = entry.path();
    if (p.extension() != ".json" || p.filename() == "scene.schema.json") continue;
    auto scene = load_scene(p);
    ASSERT_TRUE(scene) << scene.error().message;
    EXPECT_EQ(scene->source, p.string());
    EXPECT_FALSE(scene->materials.empty()) << p;
    for (const auto& m : scene->materials) EXPECT_NE(m.brdf, nullptr) << p << " " << m.name;
    found.insert(p.filename().string());
  }
  for (const char* name : {"default.json", "furnace.json", "cornell.json", "hdri.json", "lights.json", "split_sum.json"}) {
    EXPECT_EQ(found.count(name), 1u) << name;
  }
}

TEST(SceneJson, DefaultSceneIsTheFileAndHasEveryFamily) {
  EXPECT_EQ(json::parse(default_scene_json()), json::parse(read_text(scenes_dir / "default.json")));
  const Scene s = default_scene();
  EXPECT_EQ(s.source, "(built-in default)");
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_EQ(s.camera.height, 360);
  EXPECT_EQ(s.settings.spp, 64);
  std::set<std::string> sphere_models;
  for (const auto& sphere : s.spheres)
    sphere_models.insert(s.materials.at(static_cast<std::size_t>(sphere.material)).model);
  const std::set<std::string> families = {"lambert",       "phong-modified",           "blinn-phong-modified",
                                          "cook-torrance", "minimalist-cook-torrance", "ward-anisotropic",
                                          "lafortune",     "wrapped-diffuse"};
  EXPECT_EQ(sphere_models, families);
  // The ground: the zoo's asphalt, constant F0 = 0.04, detail in the gloss map.
  ASSERT_EQ(s.quads.size(), 1u);
  const Material& ground = s.materials.at(static_cast<std::size_t>(s.quads[0].material));
  EXPECT_EQ(ground.name, "asphalt");
  EXPECT_GE(ground.gloss_texture, 0);
  EXPECT_GE(ground.kd_texture, 0);
  EXPECT_EQ(ground.ks_texture, -1);
  EXPECT_TRUE(s.textures.at(static_cast<std::size_t>(ground.gloss_texture)).data);
  EXPECT_FALSE(s.textures.at(static_cast<std::size_t>(ground.kd_texture)).data);
  bool f0 = false;
  for (const auto& [k, v] : ground.params) f0 = f0 || (k == "f0" && v == "0.04");
  EXPECT_TRUE(f0);
  // Contre-jour: a low sun in front of the camera.
  ASSERT_EQ(s.environment.kind, Environment::Kind::sky);
  const Vec3 sun = s.environment.sky.sun_direction;
  const Vec3 view = normalize(s.camera.look_at - s.camera.position);
  EXPECT_LT(std::asin(sun.y), deg_to_rad(20.0));
  EXPECT_GT(dot(Vec3{sun.x, 0.0, sun.z}, Vec3{view.x, 0.0, view.z}), 0.0);
}

TEST(SceneJson, SchemaListsTheTopLevelKeys) {
  const json schema = json::parse(read_text(scenes_dir / "scene.schema.json"));
  EXPECT_EQ(schema.at("$schema"), "https://json-schema.org/draft/2020-12/schema");
  EXPECT_EQ(schema.at("type"), "object");
  EXPECT_EQ(schema.at("additionalProperties"), false);
  std::set<std::string> in_schema;
  for (const auto& [key, value] : schema.at("properties").items()) in_schema.insert(key);
  std::set<std::string> in_parser;
  for (auto key : scene_top_level_keys()) in_parser.insert(std::string(key));
  EXPECT_EQ(in_schema, in_parser);
  // The documentation names every top-level key too.
  const std::string doc = read_text(fs::path(SHADELAB_SCENES_DIR).parent_path() / "docs" / "scene-format.md");
  for (const auto& key : in_parser) EXPECT_NE(doc.find("`" + key + "`"), std::string::npos) << key;
}

// ---- contents -----------------------------------------------------------------------------------------

TEST(SceneJson, DefaultsWhenKeysAreAbsent) {
  auto s = parse_text("{}");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->camera.width, 640);
  EXPECT_EQ(s->settings.spp, 64);
  EXPECT_EQ(s->environment.kind, Environment::Kind::none);
  EXPECT_TRUE(s->lights.empty());
}

TEST(SceneJson, CameraAndRenderSettings) {
  auto s = parse_text(R"({
    "camera": {"position": [1, 2, 3], "look_at": [1, 2, 0], "up": [0, 2, 0], "fov": 30, "width": 320, "height": 200.0},
    "render": {"spp": 16, "max_depth": 4, "seed": 18446744073709551615, "threads": 2, "rr_depth": 0}})");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->camera.position.z, 3.0);
  EXPECT_EQ(s->camera.up.y, 1.0);  // normalized
  EXPECT_EQ(s->camera.vfov_deg, 30.0);
  EXPECT_EQ(s->camera.height, 200);
  EXPECT_EQ(s->settings.spp, 16);
  EXPECT_EQ(s->settings.max_depth, 4);
  EXPECT_EQ(s->settings.seed, 18446744073709551615ULL);
  EXPECT_EQ(s->settings.threads, 2);
  EXPECT_EQ(s->settings.rr_depth, 0);
}

TEST(SceneJson, MaterialsAndShapes) {
  auto s = parse_text(R"({
    "textures": {"c": {"procedural": "checker", "size": 16, "squares": 2}},
    "materials": {
      "b": {"model": "phong", "params": {"n": 20, "kd": [0.1, 0.2, 0.3], "normalization": "none"},
            "textures": {"kd": "c"}, "uv_scale": [2, 3]},
      "a": {"model": "lafortune", "params": {"lobes": [[-1, -1, 1, 10], [0, 0, 1, 5]]}},
      "glow": {"emission": [1, 2, 3]}
    },
    "shapes": [
      {"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "a"},
      {"type": "quad", "corner": [0, 0, 0], "u": [1, 0, 0], "v": [0, 0, -1], "material": "b"},
      {"type": "disk", "center": [0, 2, 0], "normal": [0, -3, 0], "radius": 0.25, "material": "glow"}
    ]})");
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->materials.size(), 3u);
  // Materials are kept in name order; shapes refer to them by index.
  EXPECT_EQ(s->materials[0].name, "a");
  EXPECT_EQ(s->materials[1].name, "b");
  EXPECT_EQ(s->materials[2].name, "glow");
  EXPECT_EQ(s->spheres.at(0).material, 0);
  EXPECT_EQ(s->quads.at(0).material, 1);
  EXPECT_EQ(s->disks.at(0).material, 2);
  EXPECT_EQ(s->disks[0].normal.y, -1.0);
  const Material& b = s->materials[1];
  EXPECT_EQ(b.params, (ParamAssignments{{"kd", "0.1,0.2,0.3"}, {"n", "20"}, {"normalization", "none"}}));
  EXPECT_EQ(b.kd_texture, 0);
  EXPECT_EQ(b.uv_scale.x, 2.0);
  EXPECT_EQ(b.uv_scale.y, 3.0);
  EXPECT_EQ(s->materials[0].params, (ParamAssignments{{"lobes", "-1,-1,1,10;0,0,1,5"}}));
  // Purely emissive: no model, a black BRDF, the emission as radiance.
  const Material& glow = s->materials[2];
  EXPECT_EQ(glow.model, "");
  ASSERT_NE(glow.brdf, nullptr);
  EXPECT_TRUE(glow.brdf->eval({0, 0, 1}, {0, 0, 1}).is_black());
  EXPECT_EQ(glow.emission.b, 3.0);
  // The BRDF was built from the parameters: phong with normalization none at n = 20, kd 0.1 (no pi).
  const Rgb f = b.brdf->eval({0.0, 0.0, 1.0}, {0.6, 0.0, 0.8});
  EXPECT_NEAR(f.r, 0.1 + 0.5 * std::pow(0.8, 20.0), 1e-12);  // kd + ks (R.L)^n / (N.L), R.L = 0.8
}

TEST(SceneJson, GameUnits) {
  // The definition of the game unit: a directional light of colour 1 has E_perp = pi.
  auto s = parse_text(R"({"lights": [
    {"type": "directional", "direction": [0, 2, 0], "color": 1},
    {"type": "directional", "direction": [0, 1, 0], "color": [1, 0.5, 0], "intensity": 2},
    {"type": "point", "position": [0, 1, 0], "intensity": 1},
    {"type": "sphere", "center": [0, 5, 0], "radius": 1, "radiance": 3},
    {"type": "hemisphere", "sky": [0.5, 0.6, 0.7], "ground": 0.1}],
    "materials": {"glow": {"emission": 2}},
    "environment": {"sky": {"sun_irradiance": 1, "zenith": 0.25}}})");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_NEAR(light<DirectionalLight>(*s, 0).irradiance.g, pi, 1e-15);
  EXPECT_EQ(light<DirectionalLight>(*s, 0).to_light.y, 1.0);
  EXPECT_NEAR(light<DirectionalLight>(*s, 1).irradiance.g, pi, 1e-15);
  EXPECT_NEAR(light<DirectionalLight>(*s, 1).irradiance.r, 2 * pi, 1e-15);
  EXPECT_NEAR(light<PointLight>(*s, 2).intensity.r, pi, 1e-15);  // I = pi x colour (at 1 m)
  EXPECT_EQ(light<SphereLight>(*s, 3).radiance.r, 3.0);          // radiance: the same number
  EXPECT_EQ(light<HemisphereLight>(*s, 4).sky.b, 0.7);
  EXPECT_EQ(s->materials[0].emission.r, 2.0);
  EXPECT_NEAR(s->environment.sky.sun_irradiance.r, pi, 1e-15);  // the sun is a directional light value
  EXPECT_EQ(s->environment.sky.zenith.r, 0.25);
  EXPECT_EQ(s->environment.sky.horizon.r, SkyModel{}.horizon.r);  // absent: the built-in default
}

TEST(SceneJson, RadiometricUnits) {
  auto s = parse_text(R"({"units": "radiometric", "lights": [
    {"type": "directional", "direction": [0, 1, 0], "color": 2},
    {"type": "point", "position": [0, 1, 0], "power": 12.566370614359172},
    {"type": "point", "position": [0, 1, 0], "intensity": 5},
    {"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "outer_angle": 60, "inner_angle": 30, "power": 3.141592653589793},
    {"type": "point", "position": [0, 1, 0], "blender_watts": 100}]})");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(light<DirectionalLight>(*s, 0).irradiance.r, 2.0);
  EXPECT_NEAR(light<PointLight>(*s, 1).intensity.r, 1.0, 1e-15);  // I = Phi / (4 pi)
  EXPECT_EQ(light<PointLight>(*s, 2).intensity.r, 5.0);
  const SpotLight& spot = light<SpotLight>(*s, 3);
  EXPECT_NEAR(spot.cos_outer, 0.5, 1e-15);
  EXPECT_NEAR(spot.cos_inner, std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(spot.intensity.r, 1.0, 1e-15);  // I = Phi / (2 pi (1 - cos 60)) = pi / pi
  EXPECT_NEAR(light<PointLight>(*s, 4).intensity.r, 100.0 / (4 * pi), 1e-12);  // Blender: P / (4 pi)
}

TEST(SceneJson, PhotometricUnits) {
  auto s = parse_text(R"({"units": "photometric", "lights": [
    {"type": "directional", "direction": [0, 1, 0], "intensity": 683},
    {"type": "directional", "direction": [0, 1, 0], "color": [1, 0.1, 0.1], "intensity": 100},
    {"type": "point", "position": [0, 1, 0], "intensity": 683},
    {"type": "point", "position": [0, 1, 0], "power": )" +
                      json(683.0 * 4.0 * pi).dump() + R"(},
    {"type": "sphere", "center": [0, 5, 0], "radius": 1, "radiance": [683, 1366, 0]},
    {"type": "sphere", "center": [0, 5, 0], "radius": 1, "intensity": 683}],
    "materials": {"glow": {"emission": 683}},
    "environment": {"uniform": 6830}})");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_NEAR(light<DirectionalLight>(*s, 0).irradiance.r, 1.0, 1e-15);  // 683 lux -> 1 W/m^2
  const Rgb red = light<DirectionalLight>(*s, 1).irradiance;             // keeps 100 lux and its chromaticity
  EXPECT_NEAR(photometric_from_radiometric(red), 100.0, 1e-12);
  EXPECT_NEAR(red.g / red.r, 0.1, 1e-15);
  EXPECT_NEAR(light<PointLight>(*s, 2).intensity.r, 1.0, 1e-15);  // 683 cd -> 1 W/sr
  EXPECT_NEAR(light<PointLight>(*s, 3).intensity.r, 1.0, 1e-12);  // 683 x 4 pi lm -> 1 W/sr
  EXPECT_NEAR(light<SphereLight>(*s, 4).radiance.g, 2.0, 1e-15);  // nits per channel
  EXPECT_NEAR(light<SphereLight>(*s, 5).radiance.b, 1.0, 1e-15);
  EXPECT_NEAR(s->materials[0].emission.r, 1.0, 1e-15);
  EXPECT_NEAR(s->environment.uniform.g, 10.0, 1e-13);
}

TEST(SceneJson, EnvironmentImageScaleCarriesTheUnits) {
  const std::string world = std::string(SHADELAB_BLENDER_WORLDS) + "/studio.exr";
  ASSERT_TRUE(fs::exists(world)) << world << " missing: scripts/setup.sh installs Debian package blender-data";
  auto s = parse_text(R"({"units": "photometric", "environment": {"file": ")" + world +
                      R"(", "rotation": 30, "scale": 683}})");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->environment.kind, Environment::Kind::image);
  EXPECT_EQ(s->environment.latlong.width, 2 * s->environment.latlong.height);
  EXPECT_EQ(s->environment.rotation_deg, 30.0);
  EXPECT_NEAR(s->environment.scale, 1.0, 1e-15);  // 683 nit-per-texel units -> x1 W/m^2/sr
}

TEST(SceneJson, FileTexturesAndDataPngs) {
  const fs::path dir = temp_dir("textures");
  // A PNG whose stored 8-bit codes are k = 0, 1, 2, ..., 255.
  Image codes(256, 1);
  for (int k = 0; k < 256; ++k) codes.set(k, 0, Rgb::gray(srgb_to_linear(k / 255.0)));
  ASSERT_TRUE(write_image(codes, dir / "codes.png"));
  auto s = parse_text(R"({"textures": {
      "colour": {"file": "codes.png"},
      "gloss": {"file": "codes.png", "data": true}},
    "materials": {"m": {"model": "blinn-phong-modified", "textures": {"kd": "colour", "gloss": "gloss", "ks": "gloss"}, "gloss_range": [1, 4096]}}})",
                      dir);
  ASSERT_TRUE(s) << s.error().message;
  const Texture& colour = s->textures.at(0);
  const Texture& gloss = s->textures.at(1);
  EXPECT_FALSE(colour.data);
  EXPECT_TRUE(gloss.data);
  EXPECT_EQ(gloss.source, (dir / "codes.png").string());
  for (int k = 0; k < 256; ++k) {
    // A data texture holds code / 255 exactly; a colour texture the sRGB decode.
    EXPECT_EQ(gloss.image.at(k, 0).g, static_cast<double>(static_cast<float>(k / 255.0))) << k;
    EXPECT_NEAR(colour.image.at(k, 0).g, srgb_to_linear(k / 255.0), 1e-7) << k;
  }
  const Material& m = s->materials.at(0);
  EXPECT_EQ(m.gloss_texture, 1);
  EXPECT_EQ(m.ks_texture, 1);
  EXPECT_EQ(m.kd_texture, 0);
  EXPECT_EQ(m.gloss_encoding.n_black, 1.0);
  EXPECT_EQ(m.gloss_encoding.n_white, 4096.0);
}

TEST(SceneJson, MeshesWithTransforms) {
  const fs::path dir = temp_dir("meshes");
  write_text(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  auto s = parse_text(R"({"materials": {"m": {"model": "lambert"}}, "shapes": [
    {"type": "mesh", "file": "tri.obj", "material": "m"},
    {"type": "mesh", "file": "tri.obj", "material": "m", "transform": {"scale": 2, "rotate_y": 90, "translate": [0, 0, 5]}},
    {"type": "mesh", "file": "tri.obj", "material": "m", "transform": {"scale": [1, 3, 1], "rotate": [0, 0, 1, 180]}}]})",
                      dir);
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->meshes.size(), 3u);
  EXPECT_EQ(s->meshes[0].positions[1].x, 1.0);
  EXPECT_EQ(s->meshes[0].source, (dir / "tri.obj").string());
  // Scale 2, then 90 degrees about +Y (x -> -z), then translate.
  EXPECT_NEAR(s->meshes[1].positions[1].x, 0.0, 1e-12);
  EXPECT_NEAR(s->meshes[1].positions[1].z, 3.0, 1e-12);
  EXPECT_NEAR(s->meshes[2].positions[2].y, -3.0, 1e-12);
}

// ---- errors: each one line with the file and the JSON pointer -----------------------------------------

TEST(SceneJsonErrors, TheBriefsExamples) {
  EXPECT_EQ(error_of(R"({"materials": {"ground": {"model": "phong", "params": {"n": -1}}}})"),
            "scene.json: /materials/ground/params/n: brdf phong: parameter 'n' = -1 is out of range [0, 1e+06]");
  EXPECT_EQ(error_of(R"({"materials": {"m": {"model": "lambert"}}, "shapes": [
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"},
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"},
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"},
      {"type": "sphere", "center": [0, 0, 0], "radius": -2, "material": "m"}]})"),
            "scene.json: /shapes/3/radius: expected a number > 0, got -2");
  EXPECT_EQ(error_of(R"({"camera": {"fov": "wide"}})"), R"(scene.json: /camera/fov: expected a number, got "wide")");
}

TEST(SceneJsonErrors, UnknownKeysAreErrors) {
  EXPECT_EQ(error_of(R"({"camera": {"fvo": 30}})"),
            "scene.json: /camera/fvo: unknown key 'fvo' (keys of a camera: position, look_at, up, fov, width, height)");
  EXPECT_EQ(error_of(R"({"lihgts": []})"),
            "scene.json: /lihgts: unknown key 'lihgts' (keys of a scene: $schema, description, units, camera, render, "
            "textures, materials, shapes, lights, environment)");
  EXPECT_EQ(
      error_of(R"({"lights": [{"type": "point", "position": [0, 0, 0], "colour": 1}]})"),
      "scene.json: /lights/0/colour: unknown key 'colour' (keys of a point light: type, position, color, intensity, "
      "power, blender_watts)");
  EXPECT_EQ(error_of(R"({"materials": {"a/b": {"model": "lambert", "parms": {}}}})"),
            "scene.json: /materials/a~1b/parms: unknown key 'parms' (keys of a material: model, params, textures, "
            "gloss_range, uv_scale, emission)");
  EXPECT_EQ(error_of(R"({"materials": {"m": {"model": "lambert", "params": {"ks": 0.5}}}})"),
            "scene.json: /materials/m/params/ks: brdf lambert: unknown parameter 'ks' (parameters: kd)");
}

TEST(SceneJsonErrors, FileAndSyntax) {
  const fs::path dir = temp_dir("syntax");
  auto missing = load_scene(dir / "nothere.json");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message, (dir / "nothere.json").string() + ": file not found");
  EXPECT_EQ(load_error("{\n  \"camera\": {\n    \"fov\": 30,\n  }\n}\n", dir),
            "scene.json: line 4, column 3: malformed JSON: syntax error while parsing object key - unexpected '}'; "
            "expected string literal");
  EXPECT_EQ(load_error("", dir),
            "scene.json: line 1, column 1: malformed JSON: syntax error while parsing value - unexpected end of input; "
            "expected '[', '{', or a literal");
  // Duplicate keys would otherwise silently keep the last value.
  EXPECT_EQ(load_error(R"({"camera": {"fov": 30, "width": 10, "fov": 40}})", dir),
            "scene.json: /camera/fov: duplicate key 'fov'");
  EXPECT_EQ(load_error(R"({"lights": [{"type": "point"}, {"type": "point", "type": "spot"}]})", dir),
            "scene.json: /lights/1/type: duplicate key 'type'");
  // A number beyond the range of a double.
  EXPECT_EQ(load_error(R"({"shapes": [{}, {"radius": 1e999}]})", dir),
            "scene.json: /shapes/1/radius: malformed JSON: number overflow parsing '1e999'");
  EXPECT_EQ(load_error("[1, 2]", dir), "scene.json: expected a scene (a JSON object), got [1,2]");
  // JSON lets a string hold DEL (0x7f) raw; the message shows it escaped (the fuzzer's finding, 2026-12-06).
  EXPECT_EQ(load_error("\"ga\x7f" "e\"", dir), "scene.json: expected a scene (a JSON object), got \"ga\\x7fe\"");
  // A good file loads through the same path.
  EXPECT_EQ(load_error(R"({"camera": {"fov": 30}})", dir), "(no error)");
}

TEST(SceneJsonErrors, TypesAndValues) {
  EXPECT_EQ(error_of(R"({"camera": []})"), "scene.json: /camera: expected a camera (a JSON object), got []");
  EXPECT_EQ(error_of(R"({"camera": {"fov": "NaN"}})"), R"(scene.json: /camera/fov: expected a number, got "NaN")");
  EXPECT_EQ(error_of(R"({"camera": {"fov": 180}})"), "scene.json: /camera/fov: expected a number in (0, 180), got 180");
  EXPECT_EQ(error_of(R"({"camera": {"width": -5}})"),
            "scene.json: /camera/width: expected an integer in [1, 16384], got -5");
  EXPECT_EQ(error_of(R"({"camera": {"height": 2.5}})"),
            "scene.json: /camera/height: expected an integer in [1, 16384], got 2.5");
  EXPECT_EQ(error_of(R"({"camera": {"position": [0, 1]}})"),
            "scene.json: /camera/position: expected [x, y, z], got [0,1]");
  EXPECT_EQ(error_of(R"({"camera": {"position": [0, "1", 2]}})"),
            R"(scene.json: /camera/position/1: expected a number, got "1")");
  EXPECT_EQ(error_of(R"({"camera": {"position": [0, 1, 0], "look_at": [0, 1, 0]}})"),
            "scene.json: /camera/look_at: look_at equals position: the view direction is undefined");
  EXPECT_EQ(error_of(R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0]}})"),
            "scene.json: /camera/up: up is parallel to the view direction (look_at - position)");
  EXPECT_EQ(error_of(R"({"render": {"seed": -1}})"), "scene.json: /render/seed: expected an integer >= 0, got -1");
  EXPECT_EQ(error_of(R"({"render": {"spp": 0}})"),
            "scene.json: /render/spp: expected an integer in [1, 1000000], got 0");
  EXPECT_EQ(error_of(R"({"units": "metric"})"),
            R"(scene.json: /units: expected one of "game", "radiometric", "photometric", got "metric")");
  EXPECT_EQ(error_of(R"({"lights": [{"type": "directional", "direction": [0, 0, 0]}]})"),
            "scene.json: /lights/0/direction: expected a non-zero vector, got [0,0,0]");
  EXPECT_EQ(error_of(R"({"lights": [{"type": "directional", "direction": [0, 1, 0], "color": [1, -1, 1]}]})"),
            "scene.json: /lights/0/color/1: expected a number >= 0, got -1");
  EXPECT_EQ(
      error_of(R"({"lights": [{"type": "laser"}]})"),
      R"(scene.json: /lights/0/type: expected one of "directional", "point", "spot", "sphere", "hemisphere", got "laser")");
  EXPECT_EQ(error_of(R"({"lights": [{"position": [0, 0, 0]}]})"),
            "scene.json: /lights/0/type: required key is missing");
  EXPECT_EQ(
      error_of(R"({"lights": [{"type": "point", "position": [0, 0, 0], "power": 100}]})"),
      R"(scene.json: /lights/0/power: 'power' needs "units": "radiometric" (watts) or "photometric" (lumens); game units have no power)");
  EXPECT_EQ(error_of(R"({"lights": [{"type": "point", "position": [0, 0, 0], "intensity": 1, "power": 100}]})"),
            "scene.json: /lights/0/power: give one of 'intensity', 'power' or 'blender_watts', not several");
  EXPECT_EQ(
      error_of(
          R"({"lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, -1, 0], "outer_angle": 30, "inner_angle": 30}]})"),
      "scene.json: /lights/0/inner_angle: expected a number in [0, 30), got 30");
  EXPECT_EQ(error_of(R"({"lights": [{"type": "sphere", "center": [0, 0, 0], "radius": 0}]})"),
            "scene.json: /lights/0/radius: expected a number > 0, got 0");
  EXPECT_EQ(error_of(R"({"environment": {"uniform": 1, "sky": {}}})"),
            "scene.json: /environment/sky: give one of 'file', 'uniform' or 'sky', not several");
  EXPECT_EQ(error_of(R"({"environment": {"sky": {"sun_angular_radius": 0}}})"),
            "scene.json: /environment/sky/sun_angular_radius: expected a number in [0.001, 45], got 0");
  // A NaN can only come from a document built in code.
  json doc = {{"camera", {{"fov", std::nan("")}}}};
  auto nan = parse_scene(doc, ".", "scene.json");
  ASSERT_FALSE(nan);
  EXPECT_EQ(nan.error().message, "scene.json: /camera/fov: expected a finite number, got NaN");
}

TEST(SceneJsonErrors, ShapesAndMaterials) {
  const std::string m = R"("materials": {"m": {"model": "lambert"}}, )";
  EXPECT_EQ(error_of("{" + m + R"("shapes": [{"type": "sphere", "center": [0, 0, 0], "material": "m"}]})"),
            "scene.json: /shapes/0/radius: required key is missing");
  EXPECT_EQ(
      error_of("{" + m + R"("shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "stone"}]})"),
      "scene.json: /shapes/0/material: unknown material 'stone' (materials: m)");
  EXPECT_EQ(
      error_of(
          "{" + m +
          R"("shapes": [{"type": "quad", "corner": [0, 0, 0], "u": [1, 0, 0], "v": [2, 0, 0], "material": "m"}]})"),
      "scene.json: /shapes/0/v: u and v are parallel: the quad has no area");
  EXPECT_EQ(
      error_of(
          "{" + m +
          R"("shapes": [{"type": "quad", "corner": [0, 0, 0], "u": [0, 0, 0], "v": [2, 0, 0], "material": "m"}]})"),
      "scene.json: /shapes/0/u: expected a non-zero vector, got [0,0,0]");
  EXPECT_EQ(
      error_of(
          "{" + m +
          R"("shapes": [{"type": "disk", "center": [0, 0, 0], "radius": 1, "normal": [0, 0, 0], "material": "m"}]})"),
      "scene.json: /shapes/0/normal: expected a non-zero vector, got [0,0,0]");
  EXPECT_EQ(error_of(R"({"materials": {"m": {"model": "phongg"}}})"),
            "scene.json: /materials/m/model: unknown BRDF model 'phongg' (models: lambert, phong, phong-modified, "
            "blinn-phong, blinn-phong-modified, cook-torrance, minimalist-cook-torrance, ward, ward-anisotropic, "
            "lafortune, wrapped-diffuse, ggx, burley, filament, gltf, layered, principled-v1, openpbr, measured)");
  EXPECT_EQ(error_of(R"({"materials": {"m": {"model": "cook-torrance", "params": {"m": 0.2, "n": 100}}}})"),
            "scene.json: /materials/m/params: brdf cook-torrance: give parameter 'm' or 'n', not both (n = 2/m^2 - 2)");
  EXPECT_EQ(error_of(R"({"materials": {"m": {"model": "phong", "params": {"kd": true}}}})"),
            "scene.json: /materials/m/params/kd: expected a number, [r, g, b], a word or lobes, got true");
  EXPECT_EQ(error_of(R"({"materials": {"m": {"model": "phong", "params": {"kd": [0.1, 0.2]}}}})"),
            "scene.json: /materials/m/params/kd: brdf phong: parameter 'kd' takes a number or r,g,b, got '0.1,0.2'");
  EXPECT_EQ(error_of(R"({"materials": {"m": {"model": "lambert", "textures": {"kd": "bricks"}}}})"),
            "scene.json: /materials/m/textures/kd: unknown texture 'bricks' (textures: none)");
  EXPECT_EQ(error_of(R"({"textures": {"g": {"procedural": "asphalt-gloss", "size": 8}},
                        "materials": {"m": {"model": "lambert", "textures": {"kd": "g"}}}})"),
            "scene.json: /materials/m/textures/kd: texture 'g' is a data texture; a diffuse colour map needs a colour "
            "texture (\"data\": false)");
  EXPECT_EQ(error_of(R"({"textures": {"g": {"procedural": "asphalt-gloss", "size": 8}},
                        "materials": {"m": {"model": "ward", "textures": {"gloss": "g"}}}})"),
            "scene.json: /materials/m/textures/gloss: brdf ward has no exponent 'n' for a gloss map to drive");
  EXPECT_EQ(error_of(R"({"textures": {"t": {"procedural": "asphalt-gloss", "size": 0}}})"),
            "scene.json: /textures/t/size: expected an integer in [1, 8192], got 0");
  EXPECT_EQ(
      error_of(R"({"textures": {"t": {"procedural": "asphalt-gloss", "squares": 4}}})"),
      "scene.json: /textures/t/squares: unknown key 'squares' (keys of an asphalt-gloss texture: procedural, size, "
      "seed, wet_fraction)");
  EXPECT_EQ(
      error_of(R"({"materials": {"m": {"model": "lambert", "gloss_range": [100, 10]}}})"),
      "scene.json: /materials/m/gloss_range: gloss encoding: need 0 < n_black < n_white (got n_black = 100.000000, "
      "n_white = 10.000000)");
  EXPECT_EQ(error_of(R"({"materials": {"m": {}}})"),
            "scene.json: /materials/m: a material needs a 'model' (a BRDF), an 'emission', or both");
}

TEST(SceneJsonErrors, MissingAndBadFiles) {
  const fs::path dir = temp_dir("files");
  const std::string m = R"("materials": {"m": {"model": "lambert"}}, )";
  EXPECT_EQ(error_of("{" + m + R"("shapes": [{"type": "mesh", "file": "meshes/nothere.obj", "material": "m"}]})", dir),
            "scene.json: /shapes/0/file: file not found: '" + (dir / "meshes" / "nothere.obj").string() + "'");
  EXPECT_EQ(error_of(R"({"textures": {"t": {"file": "nothere.png"}}})", dir),
            "scene.json: /textures/t/file: file not found: '" + (dir / "nothere.png").string() + "'");
  EXPECT_EQ(error_of(R"({"environment": {"file": "/nonexistent/sky.exr"}})", dir),
            "scene.json: /environment/file: file not found: '/nonexistent/sky.exr'");
  // A mesh file that exists but is broken: the loader's message, after the field.
  write_text(dir / "bad.obj", "v 0 0 0\nf 1 2 3\n");
  EXPECT_EQ(error_of("{" + m + R"("shapes": [{"type": "mesh", "file": "bad.obj", "material": "m"}]})", dir),
            "scene.json: /shapes/0/file: " + (dir / "bad.obj").string() + ": a face refers to vertex 2 of 1");
  EXPECT_EQ(
      error_of(
          "{" + m +
              R"("shapes": [{"type": "mesh", "file": "bad.obj", "material": "m", "transform": {"scale": [1, 0, 1]}}]})",
          dir),
      "scene.json: /shapes/0/transform/scale/1: expected a number > 0, got 0");
  EXPECT_EQ(
      error_of(
          "{" + m +
              R"("shapes": [{"type": "mesh", "file": "bad.obj", "material": "m", "transform": {"rotate": [0, 1, 0, 9], "rotate_y": 9}}]})",
          dir),
      "scene.json: /shapes/0/transform/rotate_y: give 'rotate' or 'rotate_y', not both");
  // An environment image that is not 2:1.
  ASSERT_TRUE(write_image(Image(4, 4), dir / "square.exr"));
  EXPECT_EQ(error_of(R"({"environment": {"file": "square.exr"}})", dir),
            "scene.json: /environment/file: '" + (dir / "square.exr").string() +
                "' is 4 x 4; a lat-long map is twice as wide as it is high");
}

}  // namespace
}  // namespace shadelab
