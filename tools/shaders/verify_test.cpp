// shadelab shader verify on Mesa's lavapipe: every model, in GLSL, GLSL ES (as ESSL 3.10 compute) and HLSL,
// baked and with its parameters in a uniform block, agrees with the C++ reference to the tolerance on the
// default 100000 direction pairs, across the parameter choices that select different kernel branches. The
// direction pairs and the error measure are tested on their own.
#include "verify.h"

#include <gtest/gtest.h>

#include <cmath>

#include "export.h"
#include "process.h"
#include "shadelab/brdf/registry.h"

namespace shadelab::shaders {
namespace {

TEST(VerificationPairs, DeterministicMixOfDirections) {
  const auto a = verification_pairs(20000, kDefaultSeed);
  const auto b = verification_pairs(20000, kDefaultSeed);
  const auto c = verification_pairs(20000, kDefaultSeed + 1);
  ASSERT_EQ(a.size(), 8u * 20000u);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  int below = 0, on = 0, grazing = 0, near_mirror = 0;
  for (std::size_t i = 0; i < 20000; ++i) {
    const float* p = &a[8 * i];
    for (int d = 0; d < 2; ++d) {
      const float* v = p + 4 * d;
      EXPECT_NEAR(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), 1.0f, 1e-6f);
      EXPECT_TRUE(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]));
    }
    const float zi = p[2], zo = p[6];
    if (zi < 0.0f || zo < 0.0f) ++below;
    if (zi == 0.0f || zo == 0.0f) ++on;
    if ((zi > 0.0f && zi < 0.03f) || (zo > 0.0f && zo < 0.03f)) ++grazing;
    const double cos_mirror = -p[0] * p[4] - p[1] * p[5] + p[2] * p[6];  // wi . reflect(wo)
    if (zi > 0.0f && zo > 0.0f && cos_mirror > std::cos(0.01)) ++near_mirror;
  }
  EXPECT_NEAR(below / 20000.0, 0.06, 0.01);  // 3 of the 5 below/on-horizon kinds, 10% of the pairs
  EXPECT_NEAR(on / 20000.0, 0.04, 0.01);
  EXPECT_GT(grazing / 20000.0, 0.14);
  EXPECT_GT(near_mirror, 1000);  // the log-uniform mirror offsets put ~half of 15% within 0.01 rad
}

TEST(CompareOutputs, RelativeErrorWithAbsoluteFloorAndNonFinite) {
  const std::vector<float> input = {0, 0, 1, 0, 0, 0, 1, 0,  // case 0
                                    0, 0, 1, 0, 0, 0, 1, 0,  // case 1
                                    0, 0, 1, 0, 0, 0, 1, 0};
  const auto ref = [](const Vec3&, const Vec3&) { return Rgb{0.5, 0.0, 2.0}; };
  // case 0: 1e-3 relative on R; case 1: 1e-4 absolute on G where the reference is 0 (floor 1e-3 -> 0.1).
  const std::vector<float> out = {0.5005f, 0.0f, 2.0f, 0.0f, 0.5f, 1e-4f, 2.0f, 0.0f, 0.5f, 0.0f, 2.0f, 0.0f};
  const DeviceReport r = compare_outputs("test", input, out, ref);
  EXPECT_EQ(r.cases, 3u);
  EXPECT_EQ(r.nonfinite, 0u);
  EXPECT_NEAR(r.max_rel_error, 1e-4 / kRelativeErrorFloor, 1e-6);
  ASSERT_TRUE(r.worst.has_value());
  EXPECT_FLOAT_EQ(r.worst->shader[1], 1e-4f);
  EXPECT_NEAR(r.mean_rel_error, (1e-3 + 0.1 + 0.0) / 3.0, 1e-6);
  std::vector<float> bad = out;
  bad[8] = std::nanf("");
  bad[6] = INFINITY;
  const DeviceReport n = compare_outputs("test", input, bad, ref);
  EXPECT_EQ(n.nonfinite, 2u);
  ASSERT_TRUE(n.worst.has_value());
  EXPECT_TRUE(std::isinf(n.worst->shader[2]));  // the first non-finite case
  EXPECT_NEAR(n.max_rel_error, 1e-3, 1e-6);     // over the finite cases
}

TEST(StripVersion, CommentsOutALeadingVersionKeepingLines) {
  EXPECT_EQ(strip_version_directive("// x\n#version 450\nvoid f();\n"),
            "// x\n// (the harness's own #version replaces) version 450\nvoid f();\n");
  EXPECT_EQ(strip_version_directive("void f();\n#version 450\n"), "void f();\n#version 450\n");
}

// Model variants that between them take every branch of the kernels' parameter switches.
const std::vector<std::pair<std::string, ParamAssignments>>& variants() {
  static const std::vector<std::pair<std::string, ParamAssignments>> v = [] {
    std::vector<std::pair<std::string, ParamAssignments>> out;
    for (const auto& m : brdf_models()) {
      if (m.no_shader.empty() && !make_brdf(m.name).value()->is_stochastic()) out.push_back({m.name, {}});
    }
    out.push_back({"phong", {{"normalization", "none"}, {"n", "8"}}});
    out.push_back({"phong-modified", {{"kd", "0"}, {"n", "200"}}});
    out.push_back({"blinn-phong", {{"normalization", "lower"}, {"n", "12"}}});
    out.push_back({"blinn-phong-modified", {{"normalization", "upper"}}});
    out.push_back({"blinn-phong", {{"normalization", "none"}, {"kd", "0.1,0.4,0.7"}}});
    out.push_back({"cook-torrance", {{"d", "blinn-phong"}, {"g", "cook-torrance"}, {"f", "dielectric"}, {"ior", "1.33,1.5,1.8"}}});
    out.push_back({"cook-torrance", {{"g", "kelemen"}, {"f", "conductor"}, {"ior", "0.18,0.42,1.37"}, {"k", "3.4,2.35,1.77"}}});
    out.push_back({"cook-torrance", {{"f", "none"}, {"form", "1981"}, {"m", "0.6"}}});
    out.push_back({"ward-anisotropic", {{"alpha_x", "0.5"}, {"alpha_y", "0.08"}}});
    out.push_back({"lafortune", {{"lobes", "-1,-1,1,20;0.8,0.8,0.9,5;-0.5,-1.2,0.7,60"}}});
    out.push_back({"wrapped-diffuse", {{"w", "0"}}});
    out.push_back({"wrapped-diffuse", {{"w", "1"}, {"kd", "0.3,0.6,0.9"}}});
    out.push_back({"cook-torrance", {{"d", "ggx"}, {"m", "0.4"}}});
    out.push_back({"ggx", {{"ms", "kulla-conty"}, {"f", "conductor"}, {"ior", "0.18,0.42,1.37"}, {"k", "3.4,2.35,1.77"}, {"alpha", "0.6"}}});
    out.push_back({"ggx", {{"g", "smith-separable"}, {"f", "dielectric"}, {"alpha_x", "0.4"}, {"alpha_y", "0.05"}, {"ms", "kulla-conty"}}});
    out.push_back({"ggx", {{"f", "none"}, {"ks", "0.9,0.7,0.5"}, {"alpha", "0.1"}}});
    out.push_back({"filament", {{"diffuse", "burley"}, {"energy_compensation", "off"}, {"metallic", "0.3"}}});
    out.push_back({"filament", {{"metallic", "1"}, {"base_color", "0.95,0.64,0.54"}, {"perceptual_roughness", "0.9"}}});
    // glTF: every extension's branch, both sheen visibilities (the sheen table's uniform block).
    out.push_back({"gltf", {{"metallic", "0"}, {"base_color", "0.8,0.4,0.2"}, {"roughness", "0.5"}, {"sheen_color", "0.9,0.5,0.2"},
                            {"sheen_roughness", "0.4"}, {"clearcoat", "0.7"}, {"clearcoat_roughness", "0.2"},
                            {"anisotropy_strength", "0.6"}, {"anisotropy_rotation", "0.8"}}});
    // (Not at sheen roughness 0.15: there the sheen scaling 1 - 0.5 E reaches its clamp at 0 near grazing, f is a
    // small difference of large terms and single precision loses 1.7e-7 /sr of it, 1.7e-4 on verify's scale:
    // docs/models/gltf.md, "Shaders".)
    out.push_back({"gltf", {{"metallic", "0.3"}, {"sheen_color", "0.5"}, {"sheen_roughness", "0.3"}, {"sheen_visibility", "ashikhmin"},
                            {"specular", "0.5"}, {"specular_color", "2,1,0.5"}, {"ior", "1.33"}}});
    out.push_back({"principled-v1", {{"base_color", "0.9,0.5,0.2"}, {"specular", "1"}, {"specular_tint", "1"}, {"sheen", "1"},
                                     {"clearcoat", "1"}, {"anisotropic", "0.7"}, {"anisotropic_rotation", "0.3"}}});
    out.push_back({"principled-v1", {{"specular", "0"}, {"metallic", "0.4"}, {"roughness", "1"}, {"anisotropic", "1"},
                                     {"clearcoat", "0.5"}, {"clearcoat_roughness", "0.999"}, {"base_color", "0"}}});
    return out;
  }();
  return v;
}

void expect_all_pass(Lang lang, bool uniforms) {
  for (const auto& [model, params] : variants()) {
    VerifyOptions o;
    o.model = model;
    o.params = params;
    o.lang = lang;
    o.uniforms = uniforms;
    o.device = VerifyDevice::vulkan;
    std::string label = model;
    for (const auto& [k, v] : params) label += " " + k + "=" + v;
    SCOPED_TRACE(label);
    auto r = verify_shader(o);
    ASSERT_TRUE(r.has_value()) << r.error().message;
    ASSERT_EQ(r->devices.size(), 1u);
    const DeviceReport& d = r->devices.front();
    EXPECT_EQ(d.cases, 100000u);
    EXPECT_EQ(d.nonfinite, 0u);
    EXPECT_LE(d.max_rel_error, kDefaultTolerance);
    EXPECT_TRUE(r->passed);
    EXPECT_NE(d.device.find("llvmpipe"), std::string::npos) << d.device;
  }
}

TEST(VerifyLavapipe, EveryModelGlsl) { expect_all_pass(Lang::glsl, false); }
TEST(VerifyLavapipe, EveryModelEssl) { expect_all_pass(Lang::essl, false); }
TEST(VerifyLavapipe, EveryModelHlsl) { expect_all_pass(Lang::hlsl, false); }
TEST(VerifyLavapipe, EveryModelGlslUniforms) { expect_all_pass(Lang::glsl, true); }
TEST(VerifyLavapipe, EveryModelHlslUniforms) { expect_all_pass(Lang::hlsl, true); }

// The comparison is against the model as given: a shader baked for alpha = 0.21 passes as ward alpha=0.21 and
// fails as ward alpha=0.2 (a 5% change of a parameter is far above the tolerance).
TEST(VerifyLavapipe, AShaderForOtherParametersFails) {
  ExportOptions e;
  auto ex = export_model("ward", {{"alpha", "0.21"}}, e);
  ASSERT_TRUE(ex.has_value());
  TempDir dir;
  const std::string path = (dir / "ward.glsl").string();
  ASSERT_TRUE(write_file(path, ex->text).has_value());
  VerifyOptions o;
  o.model = "ward";
  o.lang = Lang::glsl;
  o.source = path;
  o.cases = 20000;
  o.params = {{"alpha", "0.21"}};
  auto same = verify_shader(o);
  ASSERT_TRUE(same.has_value()) << same.error().message;
  EXPECT_TRUE(same->passed);
  o.params = {{"alpha", "0.2"}};
  auto other = verify_shader(o);
  ASSERT_TRUE(other.has_value()) << other.error().message;
  EXPECT_FALSE(other->passed);
  EXPECT_GT(other->combined.max_rel_error, 0.05);
}

TEST(VerifyErrors, BadInputIsAnErrorNotAReport) {
  VerifyOptions o;
  o.model = "phong";
  o.cases = 0;
  EXPECT_EQ(verify_shader(o).error().message, "--cases: 0 is out of range [1, 1000000]");
  o.cases = 100;
  o.device = VerifyDevice::webgl2;
  EXPECT_EQ(verify_shader(o).error().message, "--device webgl2 needs --lang essl");
  o.device = VerifyDevice::vulkan;
  o.source = "/no/such/file.glsl";
  EXPECT_EQ(verify_shader(o).error().message, "--source: /no/such/file.glsl: no such file");
  o.source.clear();
  o.model = "nope";
  EXPECT_NE(verify_shader(o).error().message.find("unknown BRDF model 'nope'"), std::string::npos);
}

}  // namespace
}  // namespace shadelab::shaders
