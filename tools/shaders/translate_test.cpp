// The token map: each dialect name becomes its target spelling, comments and layout stay as they are, and the
// HLSL-only rewrites (static const at file scope) and GLSL's array constructor apply where they must.
#include "translate.h"

#include <gtest/gtest.h>

namespace shadelab::shaders {
namespace {

std::string tr(const std::string& text, Lang lang) {
  auto r = translate(text, lang, "test.sl");
  EXPECT_TRUE(r.has_value()) << (r ? "" : r.error().message);
  return r ? *r : std::string();
}

TEST(Translate, TypeAndFunctionNames) {
  const std::string sl = "inline rgb f(real a, vec3 v) { return mix(rgb(a), rgb(atan2(v.y, v.x)), 0.5); }";
  EXPECT_EQ(tr(sl, Lang::glsl), "vec3 f(float a, vec3 v) { return mix(vec3(a), vec3(atan(v.y, v.x)), 0.5); }");
  EXPECT_EQ(tr(sl, Lang::essl), "vec3 f(float a, vec3 v) { return mix(vec3(a), vec3(atan(v.y, v.x)), 0.5); }");
  EXPECT_EQ(tr(sl, Lang::hlsl), "float3 f(float a, float3 v) { return lerp(float3(a), float3(atan2(v.y, v.x)), 0.5); }");
}

TEST(Translate, CommentsAndLayoutStayIntact) {
  const std::string sl = "// real rgb mix atan2 inline const\n/* vec3\n real */\nreal  x;\n";
  EXPECT_EQ(tr(sl, Lang::hlsl), "// real rgb mix atan2 inline const\n/* vec3\n real */\nfloat  x;\n");
  EXPECT_EQ(tr(sl, Lang::glsl), "// real rgb mix atan2 inline const\n/* vec3\n real */\nfloat  x;\n");
}

TEST(Translate, FileScopeConstants) {
  const std::string sl = "const real A = 1.0;\nconst int N = 3;\ninline real f(real x) { real y = x; return y; }\n";
  EXPECT_EQ(tr(sl, Lang::hlsl), "static const float A = 1.0;\nstatic const int N = 3;\nfloat f(float x) { float y = x; return y; }\n");
  EXPECT_EQ(tr(sl, Lang::glsl), "const float A = 1.0;\nconst int N = 3;\nfloat f(float x) { float y = x; return y; }\n");
}

TEST(Translate, ConstantArrays) {
  const std::string sl = "const real TABLE[3] = {0.5, 0.25,\n  0.125};\n";
  EXPECT_EQ(tr(sl, Lang::glsl), "float TABLE[3] = float[3](0.5, 0.25,\n  0.125);\n");
  EXPECT_EQ(tr(sl, Lang::essl), "float TABLE[3] = float[3](0.5, 0.25,\n  0.125);\n");
  EXPECT_EQ(tr(sl, Lang::hlsl), "static const float TABLE[3] = {0.5, 0.25,\n  0.125};\n");
  EXPECT_FALSE(translate("const real T[2] = 1.0;", Lang::glsl, "t.sl").has_value());
  EXPECT_FALSE(translate("const real T[2] = {{1.0}, {2.0}};", Lang::glsl, "t.sl").has_value());
}

TEST(Translate, NamesInsideIdentifiersAreLeftAlone) {
  EXPECT_EQ(tr("real realness = mixer + rgb_value;", Lang::hlsl), "float realness = mixer + rgb_value;");
}

TEST(Translate, Languages) {
  EXPECT_EQ(*parse_lang("glsl"), Lang::glsl);
  EXPECT_EQ(*parse_lang("essl"), Lang::essl);
  EXPECT_EQ(*parse_lang("hlsl"), Lang::hlsl);
  const auto bad = parse_lang("metal");
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().message, "--lang: unknown language 'metal' (languages: glsl, essl, hlsl)");
}

}  // namespace
}  // namespace shadelab::shaders
