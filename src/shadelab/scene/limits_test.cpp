// Tests of the scene's bounds (limits.h) and of the inputs that used to crash or hang the renderer (issue 16):
// each is refused with one line naming its JSON pointer, or, for a direction, normalized without underflow.
#include "shadelab/scene/limits.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "shadelab/scene/default_scene.h"
#include "shadelab/scene/scene_json.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("shadelab_limits_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Result<Scene> parse_text(const std::string& text) {
  return parse_scene(json::parse(text), fs::path(::testing::TempDir()), "scene.json");
}

// The error of a scene that must fail, checked to be one line that starts with the file and the pointer.
std::string error_of(const std::string& text, const std::string& pointer) {
  auto r = parse_text(text);
  if (r) {
    ADD_FAILURE() << "no error for " << text;
    return {};
  }
  const std::string& m = r.error().message;
  EXPECT_EQ(m.rfind("scene.json: " + pointer + ": ", 0), 0u) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  return m;
}

const std::string mat = R"("materials": {"m": {"model": "lambert"}, "glow": {"emission": 1}}, )";

// issue 16, 1: a camera coordinate of 2e18 or more (3.5e38 in every example scene) failed Embree's
// ray.valid() assertion (SIGABRT). Positions are bounded by max_scene_coordinate.
TEST(SceneLimits, CoordinatesBeyondTheBoundAreErrors) {
  EXPECT_NE(error_of(R"({"camera": {"position": [0, 1, 3.5e38]}})", "/camera/position").find("beyond +-1e+09"),
            std::string::npos);
  error_of(R"({"camera": {"look_at": [2e18, 0, 0]}})", "/camera/look_at");
  error_of("{" + mat + R"("shapes": [{"type": "sphere", "center": [0, -1e10, 0], "radius": 1, "material": "m"}]})",
           "/shapes/0/center");
  error_of("{" + mat + R"("shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1e12, "material": "m"}]})",
           "/shapes/0/radius");
  error_of(R"({"lights": [{"type": "point", "position": [1e300, 0, 0]}]})", "/lights/0/position");
  // At the bound itself the scene is accepted.
  EXPECT_TRUE(parse_text(R"({"camera": {"position": [0, 1, 1e9]}})"));
}

// issue 16, 1 and 3: an up of [0, 1e-300, 0] underflowed when normalized (NaN camera basis, SIGABRT), a spot
// direction of [0, 1e-300, 0] gave NaN pixels. Directions are normalized after scaling by their largest
// component, so any non-zero vector keeps its direction.
TEST(SceneLimits, TinyAndHugeDirectionsAreNormalizedExactly) {
  auto s = parse_text(R"({"camera": {"up": [0, 1e-300, 0]},
      "lights": [{"type": "spot", "position": [0, 3, 0], "direction": [0, -1e-300, 0]},
                 {"type": "directional", "direction": [1e300, 1e300, 0]}]})");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->camera.up.y, 1.0);
  EXPECT_EQ(std::get<SpotLight>(s->lights[0]).axis.y, -1.0);
  EXPECT_NEAR(std::get<DirectionalLight>(s->lights[1]).to_light.x, std::sqrt(0.5), 1e-15);
  error_of(R"({"camera": {"up": [0, 0, 0]}})", "/camera/up");
}

// issue 16, 3: an emissive quad with u or v of 1e-300 (its area underflows to 0: infinite light pdf), a sun
// angular radius of 1e-300 (radiance E / (pi sin^2) overflows), gloss_range [2, 1e308] and uv_scale 1e308
// rendered NaN/Inf pixels with exit 0. Each is refused.
TEST(SceneLimits, DegenerateValuesAreRefused) {
  error_of("{" + mat + R"("shapes": [{"type": "quad", "corner": [0, 0, 0], "u": [1e-300, 0, 0], "v": [0, 0, 1], "material": "glow"}]})",
           "/shapes/0/u");
  error_of("{" + mat + R"("shapes": [{"type": "disk", "center": [0, 0, 0], "radius": 1e-300, "material": "glow"}]})",
           "/shapes/0/radius");
  error_of(R"({"environment": {"sky": {"sun_angular_radius": 1e-300}}})", "/environment/sky/sun_angular_radius");
  error_of(R"({"materials": {"m": {"model": "blinn-phong", "gloss_range": [2, 1e308]}}})",
           "/materials/m/gloss_range/1");
  error_of(R"({"materials": {"m": {"model": "lambert", "uv_scale": 1e308}}})", "/materials/m/uv_scale");
  error_of(R"({"materials": {"m": {"model": "lambert", "uv_scale": [1, 1e7]}}})", "/materials/m/uv_scale/1");
}

// issue 16, 3: a radiance above float max (1e39) gave "internal error: std::get: wrong index for variant"
// (exit 3) from the environment sampler. Light values are bounded by max_light_value after conversion.
TEST(SceneLimits, LightValuesAboveTheBoundAreErrors) {
  EXPECT_NE(error_of(R"({"environment": {"uniform": 1e39}})", "/environment/uniform").find("1e+30"), std::string::npos);
  error_of(R"({"environment": {"sky": {"zenith": [0, 1e39, 0]}}})", "/environment/sky/zenith");
  error_of(R"({"environment": {"sky": {"sun_irradiance": 1e31}}})", "/environment/sky/sun_irradiance");
  error_of(R"({"lights": [{"type": "hemisphere", "sky": 1e39}]})", "/lights/0/sky");
  error_of(R"({"lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1e30}]})", "/lights/0/intensity");
  error_of(R"({"materials": {"m": {"emission": [1e39, 0, 0]}}})", "/materials/m/emission");
  // Game units multiply by pi: 1e30 / pi is inside, 1e30 is not (pi x 1e30 after conversion).
  EXPECT_TRUE(parse_text(R"({"lights": [{"type": "directional", "direction": [0, 1, 0], "intensity": 3e29}]})"));
}

// issue 16, 2: JSON 100,000 deep (any key) took quadratic time and memory before its error: the pointer
// tracker copied the path into every frame. Depth is bounded at max_json_depth, tracked in O(1) per event.
TEST(SceneLimits, DeeplyNestedJsonIsAnErrorAtTheBound) {
  const fs::path dir = temp_dir("deep");
  const fs::path file = dir / "deep.json";
  {
    std::ofstream out(file);
    out << "{\"description\": " << std::string(100000, '[') << std::string(100000, ']') << "}";
  }
  auto r = load_scene(file);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("nested deeper than 64 levels"), std::string::npos) << r.error().message;
  // The pointer names where it happened: /description/0/0/... (63 levels of arrays).
  EXPECT_NE(r.error().message.find(file.string() + ": /description/0/0/"), std::string::npos) << r.error().message;
  // A parsed document is bounded too (messages quote values through a recursive dump).
  json deep = json::array();
  for (int i = 0; i < 1000; ++i) deep = json::array({deep});
  auto p = parse_scene(json{{"description", deep}}, dir, "doc");
  ASSERT_FALSE(p);
  EXPECT_NE(p.error().message.find("nested deeper"), std::string::npos);
  // 64 levels (the object and 63 arrays) pass the depth check (and fail later: a description is a string).
  json ok = json::array();
  for (int i = 0; i < 62; ++i) ok = json::array({ok});
  auto at_bound = parse_scene(json{{"description", ok}}, dir, "doc");
  ASSERT_FALSE(at_bound);
  EXPECT_EQ(at_bound.error().message.find("nested deeper"), std::string::npos) << at_bound.error().message;
  EXPECT_NE(at_bound.error().message.find("expected a string"), std::string::npos) << at_bound.error().message;
}

// issue 16, 2: the scene copies a mesh per instance: the scene's triangles are bounded (max_scene_triangles)
// before each copy. A 200,000-triangle OBJ used 51 times is 10.2 M triangles: refused, naming the instance.
TEST(SceneLimits, TrianglesOfAllMeshInstancesAreBounded) {
  const fs::path dir = temp_dir("instances");
  {
    std::ofstream obj(dir / "many.obj");
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int i = 0; i < 200000; ++i) obj << "f 1 2 3\n";
  }
  json shapes = json::array();
  for (int i = 0; i < 51; ++i) shapes.push_back({{"type", "mesh"}, {"file", "many.obj"}, {"material", "m"}});
  const json doc = {{"materials", {{"m", {{"model", "lambert"}}}}}, {"shapes", shapes}};
  auto r = parse_scene(doc, dir, "scene.json");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message.rfind("scene.json: /shapes/50/file: ", 0), 0u) << r.error().message;
  EXPECT_NE(r.error().message.find("above the limit of 10000000"), std::string::npos) << r.error().message;
}

// A mesh whose vertices leave the coordinate bound after the scene's transform is refused.
TEST(SceneLimits, MeshVerticesAreBoundedAfterTheTransform) {
  const fs::path dir = temp_dir("mesh_transform");
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const json doc = {{"materials", {{"m", {{"model", "lambert"}}}}},
                    {"shapes", {{{"type", "mesh"}, {"file", "tri.obj"}, {"material", "m"},
                                 {"transform", {{"scale", 1e9}, {"translate", {0, 5e8, 0}}}}}}}};
  auto r = parse_scene(doc, dir, "scene.json");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message.rfind("scene.json: /shapes/0/transform: vertex 2", 0), 0u) << r.error().message;
}

// The renderers' backstop: a Scene built in code is checked as a file would be.
TEST(SceneLimits, CheckSceneLimitsNamesWhatIsWrong) {
  Scene s = default_scene();
  EXPECT_TRUE(check_scene_limits(s)) << check_scene_limits(s).error().message;
  Scene far = s;
  far.camera.position = {0.0, 2e18, 0.0};
  ASSERT_FALSE(check_scene_limits(far));
  EXPECT_EQ(check_scene_limits(far).error().message.rfind("camera position: coordinate 2e+18", 0), 0u);
  Scene bright = s;
  bright.environment.kind = Environment::Kind::uniform;
  bright.environment.uniform = Rgb::gray(1e39);
  ASSERT_FALSE(check_scene_limits(bright));
  EXPECT_EQ(check_scene_limits(bright).error().message.rfind("environment uniform", 0), 0u);
  Scene flat = s;
  flat.quads.push_back({{0, 0, 0}, {1e-300, 0, 0}, {0, 0, 1}, 0});
  EXPECT_FALSE(check_scene_limits(flat));
  Scene nan_up = s;
  nan_up.camera.up = {0.0, std::nan(""), 0.0};
  EXPECT_FALSE(check_scene_limits(nan_up));
}

// issue 16, 1: a huge uv_scale (1e308) made sample_texture compute inf -> fmod NaN -> a wild index
// (out-of-bounds read, SIGSEGV). Any coordinate, finite or not, reads a texel of the image: the result is
// within the texels' range, and whole-number coordinates read the same point as 0.
TEST(SceneLimits, TextureLookupsOfAnyCoordinateStayInTheImage) {
  Texture t;
  t.image = Image(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) t.image.set(x, y, Rgb::gray(1.0 + x + 3 * y));  // texels 1 .. 6
  const Rgb origin = sample_texture(t, {0.0, 0.0});
  for (double u : {1e308, -1e308, std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), std::nan(""), 0x1p60,
                   -0x1p60, 1e-320, -1e-320, 4.0, -7.0, 0.999999999999999999}) {
    for (double v : {0.0, 1e308, std::nan(""), -3.0}) {
      const Rgb c = sample_texture(t, {u, v});
      EXPECT_TRUE(std::isfinite(c.r)) << u << ", " << v;
      EXPECT_GE(c.r, 1.0) << u << ", " << v;
      EXPECT_LE(c.r, 6.0) << u << ", " << v;
    }
  }
  // Whole numbers (and huge values, which are whole) wrap to the origin exactly.
  for (double u : {1e308, 4.0, -7.0, 0x1p60}) EXPECT_EQ(sample_texture(t, {u, 0.0}).r, origin.r) << u;
  // The lookup is still periodic at ordinary coordinates: u and u + 1 read the same value.
  EXPECT_NEAR(sample_texture(t, {0.3, 0.6}).r, sample_texture(t, {1.3, -0.4}).r, 1e-12);
}

}  // namespace
}  // namespace shadelab
