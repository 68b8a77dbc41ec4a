// glTF-style metallic-roughness textures on a filament material: they multiply base_color, metallic and
// perceptual_roughness (glTF 2.0 section 3.9.2); a model without those parameters is refused at load.
#include "shadelab/render/materials.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "shadelab/brdf/registry.h"
#include "shadelab/scene/scene_json.h"

namespace shadelab {
namespace {

// Constant textures: a checker whose two colours are equal.
const char* const kScene = R"({"textures": {
    "base": {"procedural": "checker", "size": 4, "color_a": [0.5, 0.25, 1], "color_b": [0.5, 0.25, 1]},
    "mr": {"procedural": "checker", "size": 4, "data": true, "color_a": [0, 0.5, 0.75], "color_b": [0, 0.5, 0.75]}},
  "materials": {"m": {"model": "MODEL", "params": PARAMS, "textures": {"base_color": "base", "metallic_roughness": "mr"}}}})";

Result<Scene> scene(const std::string& model, const std::string& params) {
  std::string text = kScene;
  text.replace(text.find("MODEL"), 5, model);
  text.replace(text.find("PARAMS"), 6, params);
  return parse_scene(nlohmann::json::parse(text), ".", "test");
}

TEST(Materials, MetallicRoughnessTexturesMultiplyTheFilamentParameters) {
  auto s = scene("filament", R"({"base_color": [0.8, 0.8, 0.6], "metallic": 1, "perceptual_roughness": 0.8})");
  ASSERT_TRUE(s) << s.error().message;
  MaterialSet set;
  ASSERT_TRUE(set.prepare(*s));
  BrdfPtr holder;
  const Brdf* f = set.brdf(0, {0.3, 0.6}, holder);
  ASSERT_NE(f, nullptr);
  // base_color 0.8 x 0.5, 0.8 x 0.25, 0.6 x 1; metallic 1 x 0.75; roughness 0.8 x 0.5.
  const auto expected =
      make_brdf("filament", {{"base_color", "0.4,0.2,0.6"}, {"metallic", "0.75"}, {"perceptual_roughness", "0.4"}});
  ASSERT_TRUE(expected);
  const Vec3 wi = normalize(Vec3{0.3, -0.2, 0.9});
  const Vec3 wo = normalize(Vec3{-0.5, 0.1, 0.6});
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(f->eval(wi, wo)[c], (*expected)->eval(wi, wo)[c], 1e-6 * (*expected)->eval(wi, wo)[c]) << c;
  }
}

TEST(Materials, MetallicRoughnessTexturesNeedTheParameters) {
  auto s = scene("ggx", "{}");
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("base_color"), std::string::npos) << s.error().message;
}

}  // namespace
}  // namespace shadelab
