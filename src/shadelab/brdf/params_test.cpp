#include "shadelab/brdf/params.h"

#include <gtest/gtest.h>

#include "shadelab/brdf/registry.h"

namespace shadelab {
namespace {

std::string error_of(const std::string& model, const ParamAssignments& p) {
  auto r = make_brdf(model, p);
  return r ? std::string() : r.error().message;
}

TEST(Params, DefaultsFillUnsetValues) {
  const ModelInfo* info = find_brdf_model("phong");
  ASSERT_NE(info, nullptr);
  auto v = parse_params(info->name, info->params, {{"n", "7"}});
  ASSERT_TRUE(v.has_value());
  EXPECT_DOUBLE_EQ(v->scalar("n"), 7.0);
  EXPECT_TRUE(v->is_set("n"));
  EXPECT_FALSE(v->is_set("kd"));
  EXPECT_EQ(v->choice("normalization"), "exact");
}

TEST(Params, ColorTakesScalarOrTriple) {
  const ModelInfo* info = find_brdf_model("lambert");
  auto a = parse_params(info->name, info->params, {{"kd", "0.25"}});
  auto b = parse_params(info->name, info->params, {{"kd", "0.1,0.2,0.3"}});
  ASSERT_TRUE(a && b);
  EXPECT_DOUBLE_EQ(a->color("kd").b, 0.25);
  EXPECT_DOUBLE_EQ(b->color("kd").g, 0.2);
}

TEST(Params, ErrorsNameModelAndParameter) {
  EXPECT_EQ(error_of("phong", {{"n", "-1"}}), "brdf phong: parameter 'n' = -1 is out of range [0, 1e+06]");
  EXPECT_NE(error_of("phong", {{"shininess", "3"}}).find("unknown parameter 'shininess'"), std::string::npos);
  EXPECT_NE(error_of("phong", {{"n", "abc"}}).find("'abc' is not a number"), std::string::npos);
  EXPECT_NE(error_of("phong", {{"n", "nan"}}).find("not finite"), std::string::npos);
  EXPECT_NE(error_of("phong", {{"n", "inf"}}).find("not finite"), std::string::npos);
  EXPECT_NE(error_of("phong", {{"kd", "0.1,0.2"}}).find("a number or r,g,b"), std::string::npos);
  EXPECT_NE(error_of("phong", {{"normalization", "half"}}).find("is not one of none | exact"), std::string::npos);
  EXPECT_NE(error_of("nope", {}).find("unknown BRDF model 'nope'"), std::string::npos);
}

// Every message quotes user text as one printable line (docs/testing.md, "Classes of bad input"): a control
// byte or a byte that is not UTF-8 in a value, a name or a malformed assignment never reaches the message raw.
// Found by the scene fuzzer: "f": "conduct\x7fr" (fuzz/regressions/scene/crash-5512...).
bool one_printable_line(const std::string& s) {
  for (const unsigned char c : s) {
    if (c < 0x20 || c == 0x7f || c >= 0x80) return false;
  }
  return !s.empty();
}

TEST(Params, ErrorsQuoteUserTextAsOnePrintableLine) {
  const std::vector<std::pair<std::string, ParamAssignments>> cases = {
      {"choice value", {{"f", "conduct\x7fr"}}},
      {"choice value, not UTF-8", {{"d", "beck\xffmann"}}},
      {"scalar, not a number", {{"m", "0.3\n"}}},
      {"scalar, two numbers then a control byte", {{"m", "0.3,\x01"}}},
      {"color, empty number", {{"kd", "0.1,,\t\x1b[31m"}}},
      {"unknown name", {{"k\rs", "1"}}},
  };
  for (const auto& [what, p] : cases) {
    const std::string e = error_of("cook-torrance", p);
    EXPECT_TRUE(one_printable_line(e)) << what << ": " << e;
    EXPECT_NE(e.find("brdf cook-torrance"), std::string::npos) << what << ": " << e;
  }
  const auto bad = split_assignment("kd\x7f" "0.5");
  ASSERT_FALSE(bad.has_value());
  EXPECT_TRUE(one_printable_line(bad.error().message)) << bad.error().message;
  const auto lobes = error_of("lafortune", {{"lobes", "1,1,1\x02;"}});
  EXPECT_TRUE(one_printable_line(lobes)) << lobes;
  // The model name itself (the scene fuzzer's finding of 2026-12-05: a DEL byte inside "cook-torrance").
  const auto model = error_of("c\x7fok-torrance", {});
  EXPECT_TRUE(one_printable_line(model)) << model;
  EXPECT_NE(model.find("unknown BRDF model 'c\\x7fok-torrance'"), std::string::npos) << model;
}

TEST(Params, SplitAssignment) {
  auto a = split_assignment("kd=0.5,0.5,0.5");
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->first, "kd");
  EXPECT_EQ(a->second, "0.5,0.5,0.5");
  EXPECT_FALSE(split_assignment("kd").has_value());
  EXPECT_FALSE(split_assignment("=3").has_value());
}

TEST(Params, EveryRegisteredDefaultIsValid) {
  for (const auto& m : brdf_models()) {
    if (needs_input_file(m)) {  // measured: no default file; refused by name (Registry.* in measured_registry_test)
      auto r = make_brdf(m.name);
      ASSERT_FALSE(r.has_value()) << m.name;
      EXPECT_EQ(r.error().message.rfind("brdf " + m.name + ": parameter 'file' is required", 0), 0u) << r.error().message;
      continue;
    }
    auto r = make_brdf(m.name);
    EXPECT_TRUE(r.has_value()) << m.name << ": " << (r ? "" : r.error().message);
  }
}

}  // namespace
}  // namespace shadelab
