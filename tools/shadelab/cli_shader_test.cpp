// End-to-end tests of `shadelab shader` and `shadelab shader verify`: the exported file, the exact --json shape,
// exit codes, and broken shaders fed through --source — a missing pi, wi and wo swapped in a non-reciprocal
// model, a wrong exponent — that must fail, beside a hand-written correct shader that must pass.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

fs::path write(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p;
}

// The export of `args` with `from` replaced by `to` (which must occur), written to `name`.
fs::path broken(const std::string& args, const std::string& name, const std::string& from, const std::string& to) {
  const auto r = run("shader " + args);
  EXPECT_EQ(r.code, 0) << r.err;
  std::string text = r.out;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the export of " << args;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return write(name, text);
}

TEST(CliShader, ExportsToStdoutAndToAFile) {
  const auto r = run("shader blinn-phong --param n=20 --lang glsl");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("vec3 brdf_blinn_phong(vec3 wi, vec3 wo) {"), std::string::npos);
  EXPECT_NE(r.out.find("  p.n = 20.0;"), std::string::npos);
  EXPECT_NE(r.out.find("vec3 brdf_blinn_phong_punctual_game(vec3 wi, vec3 wo, vec3 colour)"), std::string::npos);
  EXPECT_NE(r.out.find("// Made by: shadelab shader blinn-phong --param n=20 --lang glsl"), std::string::npos);
  const fs::path out = temp_dir() / "ward.hlsl";
  const auto w = run("shader ward-anisotropic --lang hlsl --entry aniso --uniforms --out " + out.string());
  ASSERT_EQ(w.code, 0) << w.err;
  EXPECT_TRUE(w.out.empty());
  const std::string text = read(out);
  EXPECT_NE(text.find("float3 aniso(float3 wi, float3 wo) {"), std::string::npos);
  EXPECT_NE(text.find("cbuffer aniso_block {\n  WardParams aniso_params;\n};"), std::string::npos);
  EXPECT_EQ(text.find("vec3"), std::string::npos);  // no GLSL type names left
}

TEST(CliShader, VerifyJsonHasExactlyTheDocumentedShape) {
  const auto r = run("shader verify phong --lang glsl --json");
  const nlohmann::json j = json_of(r);
  std::set<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.insert(k);
  EXPECT_EQ(keys, (std::set<std::string>{"device", "lang", "cases", "max_rel_error", "mean_rel_error", "nonfinite", "worst"}));
  std::set<std::string> worst;
  for (const auto& [k, v] : j["worst"].items()) worst.insert(k);
  EXPECT_EQ(worst, (std::set<std::string>{"wi", "wo", "shader", "reference"}));
  EXPECT_EQ(j["lang"], "glsl");
  EXPECT_EQ(j["cases"], 100000);
  EXPECT_NE(j["device"].get<std::string>().find("llvmpipe"), std::string::npos);
  EXPECT_LE(j["max_rel_error"].get<double>(), 1e-4);
  EXPECT_EQ(j["nonfinite"], 0);
  EXPECT_EQ(j["worst"]["wi"].size(), 3u);
}

TEST(CliShader, VerifyTextReportsDevicesAndPasses) {
  const auto r = run("shader verify wrapped-diffuse --lang essl --cases 5000");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("device: llvmpipe"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("device: Chromium WebGL 2: ANGLE"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cases: 5000"), std::string::npos);
  EXPECT_NE(r.out.find("max(|reference|, 0.001 /sr)"), std::string::npos);
  EXPECT_NE(r.out.find("PASS (tolerance 0.0001, no NaN or Inf)"), std::string::npos);
}

// A missing pi: Ward's 1/(4 pi ax ay ...) written as 1/(4 ax ay ...).
TEST(CliShader, AMissingPiFails) {
  const fs::path f = broken("ward --lang glsl", "ward_no_pi.glsl", "(4.0 * SL_PI * s.ax * s.ay", "(4.0 * s.ax * s.ay");
  const auto r = run("shader verify ward --lang glsl --json --source " + f.string());
  EXPECT_EQ(r.code, 1) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["max_rel_error"].get<double>(), 1.0);  // the lobe is pi times too bright
  // And the diffuse kd/pi written as kd, in HLSL.
  const fs::path g = broken("lambert --lang hlsl", "lambert_no_pi.hlsl", "p.kd * SL_INV_PI", "p.kd");
  const auto h = run("shader verify lambert --lang hlsl --source " + g.string());
  EXPECT_EQ(h.code, 1) << h.err;
  EXPECT_NE(h.out.find("FAIL"), std::string::npos);
}

// wi and wo swapped: fails for the original Phong (it divides by N.L = wi.z), passes for the reciprocal
// modified Phong, so the check sees exactly the non-reciprocity. GLSL ES: on lavapipe and in WebGL 2.
TEST(CliShader, SwappedDirectionsFailOnlyForANonReciprocalModel) {
  const std::string call = "_eval(phong_prepare(brdf_phong_params()), wi, wo)";
  const fs::path f = broken("phong --lang essl", "phong_swapped.essl", "phong" + call,
                            "phong_eval(phong_prepare(brdf_phong_params()), wo, wi)");
  const auto r = run("shader verify phong --lang essl --json --source " + f.string());
  EXPECT_EQ(r.code, 1) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["max_rel_error"].get<double>(), 1.0);
  EXPECT_NE(j["device"].get<std::string>().find("WebGL 2"), std::string::npos);
  const fs::path g = broken("phong-modified --lang essl", "phong_modified_swapped.essl",
                            "phong_eval(phong_prepare(brdf_phong_modified_params()), wi, wo)",
                            "phong_eval(phong_prepare(brdf_phong_modified_params()), wo, wi)");
  const auto s = run("shader verify phong-modified --lang essl --source " + g.string());
  EXPECT_EQ(s.code, 0) << s.err << s.out;
}

// A wrong exponent: (N.H)^(n+1) for (N.H)^n, and a normalization (n+1) for (n+2).
TEST(CliShader, AWrongExponentFails) {
  const fs::path f = broken("blinn-phong --lang hlsl", "bp_exponent.hlsl", "pow(h.z, s.n)", "pow(h.z, s.n + 1.0)");
  const auto r = run("shader verify blinn-phong --lang hlsl --json --source " + f.string());
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_GT(nlohmann::json::parse(r.out)["max_rel_error"].get<double>(), 1e-2);
  const fs::path g = broken("phong-modified --lang glsl", "pm_norm.glsl", "(n + 2.0) * SL_INV_TWO_PI", "(n + 1.0) * SL_INV_TWO_PI");
  const auto s = run("shader verify phong-modified --lang glsl --json --source " + g.string());
  EXPECT_EQ(s.code, 1) << s.err;
  EXPECT_GT(nlohmann::json::parse(s.out)["max_rel_error"].get<double>(), 1e-3);
}

// A user's own shader, written here from the formula (not exported): the modified Blinn-Phong of the zoo,
// f = kd/pi + ks (n+2)(n+4)/(8 pi (2^(-n/2) + n)) (N.H)^n, with a #version line of its own.
TEST(CliShader, AHandWrittenCorrectShaderPasses) {
  const fs::path f = write("my_blinn.glsl", R"(#version 450
// My engine's Blinn-Phong, normalized as in the zoo article.
vec3 my_blinn(vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return vec3(0.0);
  const float n = 50.0;
  vec3 h = normalize(wi + wo);
  float norm = (n + 2.0) * (n + 4.0) / (8.0 * 3.14159265 * (exp2(-0.5 * n) + n));
  return vec3(0.5 / 3.14159265) + vec3(0.5) * norm * pow(max(h.z, 0.0), n);
}
)");
  const auto r = run("shader verify blinn-phong-modified --lang glsl --entry my_blinn --source " + f.string());
  EXPECT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("PASS"), std::string::npos);
}

// Models with energy compensation read the GGX energy tables from a uniform block; --tables-out writes its
// bytes: 528 vec4 of little-endian float, E(mu, alpha) for 2 x 32 x 32 texels, then 2 x 32 averages. The
// numbers themselves are checked on the driver (VerifyLavapipe, WebGL2); here the file's shape and the
// physics a reader can check without the library: the mirror row (alpha = 0) reflects everything, E = 1, and
// every entry is an albedo in (0, 1], smaller at the roughest row than at the smoothest.
TEST(CliShader, TablesOutWritesTheEnergyTablesBlock) {
  const fs::path out = temp_dir() / "ggx.glsl";
  const fs::path tables = temp_dir() / "ggx_energy.bin";
  const auto r = run("shader ggx --param ms=kulla-conty --lang glsl --out " + out.string() + " --tables-out " +
                     tables.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = read(out);
  EXPECT_NE(text.find("uniform ShadelabGgxEnergy {\n  vec4 shadelab_ggx_energy[528];\n};"), std::string::npos);
  EXPECT_NE(text.find("--tables-out FILE"), std::string::npos);
  std::ifstream f(tables, std::ios::binary);
  std::vector<char> raw((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  ASSERT_EQ(raw.size(), 528u * 16u);
  std::vector<float> v(raw.size() / 4);
  std::memcpy(v.data(), raw.data(), raw.size());
  for (int g = 0; g < 2; ++g) {
    for (int col = 0; col < 32; ++col) EXPECT_EQ(v[(g * 32 + 0) * 32 + col], 1.0f) << g << " " << col;
    EXPECT_EQ(v[2048 + g * 32], 1.0f);                                        // E_avg at alpha = 0
    EXPECT_LT(v[(g * 32 + 31) * 32 + 31], v[(g * 32 + 1) * 32 + 31]);        // rougher reflects less at mu = 1
    EXPECT_LT(v[2048 + g * 32 + 31], v[2048 + g * 32 + 1]);
  }
  for (std::size_t i = 0; i < 2048 + 64; ++i) {
    EXPECT_GT(v[i], 0.0f) << i;
    EXPECT_LE(v[i], 1.0f) << i;
  }
  for (std::size_t i = 2048 + 64; i < v.size(); ++i) EXPECT_EQ(v[i], 0.0f);  // the padding of the last vec4s
  // The HLSL export declares the same block as a cbuffer; a model without tables has none to write.
  const auto h = run("shader filament --lang hlsl");
  ASSERT_EQ(h.code, 0) << h.err;
  EXPECT_NE(h.out.find("cbuffer ShadelabGgxEnergy {\n  float4 shadelab_ggx_energy[528];\n};"), std::string::npos);
  EXPECT_EQ(run("shader lambert --lang glsl").out.find("ShadelabGgxEnergy"), std::string::npos);
  const fs::path none = temp_dir() / "lambert_tables.bin";
  expect_usage_error("shader lambert --lang glsl --tables-out " + none.string(),
                     "--tables-out: the model 'lambert' with these parameters reads no tables");
  EXPECT_FALSE(fs::exists(none));
  expect_usage_error("shader verify ggx --lang glsl --tables-out " + none.string(), "--tables-out: only for shader export");
}

TEST(CliShader, BadInput) {
  const fs::path syntax = write("syntax.glsl", "vec3 brdf_lambert(vec3 wi, vec3 wo) {\n  return vec3(1.0)\n}\n");
  expect_usage_error("shader verify lambert --lang glsl --source " + syntax.string(), syntax.string() + ":3: ");
  const fs::path essl = write("syntax.essl", "vec3 brdf_lambert(vec3 wi, vec3 wo) {\n  return vec3(1.0)\n}\n");
  expect_usage_error("shader verify lambert --lang essl --source " + essl.string(), essl.string() + ":3: ");
  const fs::path none = write("none.glsl", "vec3 other(vec3 wi, vec3 wo) { return wi; }\n");
  expect_usage_error("shader verify lambert --lang glsl --source " + none.string(),
                     none.string() + ": defines no function 'brdf_lambert' (name the entry with --entry NAME)");
  expect_usage_error("shader verify lambert --lang glsl --source /no/such.glsl", "--source: /no/such.glsl: no such file");
  expect_usage_error("shader nope --lang glsl", "unknown BRDF model 'nope'");
  expect_usage_error("shader phong --lang metal", "--lang: unknown language 'metal' (languages: glsl, essl, hlsl)");
  expect_usage_error("shader phong", "--lang");
  expect_usage_error("shader phong --lang glsl --param n=-1", "parameter 'n' = -1 is out of range");
  expect_usage_error("shader phong --lang glsl --entry 2x", "--entry: '2x' is not a valid function name");
  expect_usage_error("shader phong --lang glsl --cases 10", "--cases: only for shader verify");
  expect_usage_error("shader verify phong --lang glsl --out x.glsl", "--out: only for shader export");
  expect_usage_error("shader verify phong --lang glsl --cases 0", "--cases: 0 is out of range [1, 1000000]");
  expect_usage_error("shader verify phong --lang hlsl --device webgl2", "--device webgl2 needs --lang essl");
  expect_usage_error("shader verify phong --lang glsl --device metal", "--device: unknown device 'metal'");
  expect_usage_error("shader verify --lang glsl", "shader verify: expected one MODEL");
  expect_usage_error("shader a b --lang glsl", "shader: expected one MODEL");
}

}  // namespace

namespace ibl {

using shadelab::testing::run;

// One `bake ibl` of forest.exr with its defaults (the files an engine would upload), shared by the tests below.
const fs::path& forest_bake() {
  static const fs::path dir = [] {
    const fs::path d = temp_dir() / "forest_ibl";
    const auto r = run("bake ibl " + (fs::path(SHADELAB_BLENDER_WORLDS) / "forest.exr").string() + " --out-dir " + d.string());
    EXPECT_EQ(r.code, 0) << r.err;
    return d;
  }();
  return dir;
}

TEST(CliShaderIbl, ExportsTheEnvironmentLightingForTheSplitSumModels) {
  for (const char* lang : {"glsl", "essl", "hlsl"}) {
    const auto r = run(std::string("shader ggx --lang ") + lang + " --ibl");
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string v3 = std::string(lang) == "hlsl" ? "float3" : "vec3";
    EXPECT_NE(r.out.find(v3 + " brdf_ggx_ambient_game(" + v3 + " n, " + v3 + " v, Sh9Coefficients sh, int levels, int mapping)"),
              std::string::npos) << lang;
    EXPECT_NE(r.out.find("game_ibl_ambient(n, v, ggx_split_sum(ggx_prepare(brdf_ggx_params()))"), std::string::npos) << lang;
    EXPECT_NE(r.out.find("shadelab_ggx_chain"), std::string::npos) << lang;
    EXPECT_NE(r.out.find("#ifndef SHADELAB_IBL_FETCHES"), std::string::npos) << lang;
    EXPECT_NE(r.out.find("// Made by: shadelab shader ggx --lang " + std::string(lang) + " --ibl"), std::string::npos);
  }
  // The BRDF alone does not carry the IBL kernels.
  EXPECT_EQ(run("shader ggx --lang glsl").out.find("game_ibl_ambient"), std::string::npos);
  // A model without a split sum: one line, exit 2.
  expect_usage_error("shader phong --lang glsl --ibl", "split-sum description");
  expect_usage_error("shader ggx --lang glsl --ibl forest.exr", "--ibl: export takes no value");
  expect_usage_error("shader verify ggx --lang glsl --ibl /nonexistent/forest.exr", "no such file");
  expect_usage_error("shader verify ggx --lang glsl --ibl-size 64", "--ibl-size: only with --ibl");
}

TEST(CliShaderIbl, TheExportedSplitSumMatchesTheGameRendererAndOnePercentOffFails) {
  const fs::path& dir = forest_bake();
  for (const char* model : {"ggx", "filament"}) {
    for (const char* lang : {"glsl", "essl", "hlsl"}) {
      const auto r = run(std::string("shader verify ") + model + " --lang " + lang + " --ibl " + dir.string() + " --json");
      ASSERT_EQ(r.code, 0) << model << " " << lang << ": " << r.out << r.err;
      const auto j = json_of(r);
      EXPECT_EQ(j["lang"], lang);
      EXPECT_GT(j["pixels"].get<int>(), 9000) << "a 128 x 128 sphere";
      EXPECT_LE(j["max_rel_error"].get<double>(), 1e-3) << model << " " << lang;
      EXPECT_LE(j["mean_rel_error"].get<double>(), j["max_rel_error"].get<double>());
      EXPECT_EQ(j["nonfinite"], 0);
      EXPECT_NE(j["device"].get<std::string>().find("llvmpipe"), std::string::npos) << j["device"];
      if (std::string(lang) == "essl") {
        EXPECT_NE(j["device"].get<std::string>().find("WebGL 2"), std::string::npos);
      }
      for (const char* key : {"device", "lang", "max_rel_error", "mean_rel_error", "pixels"}) EXPECT_TRUE(j.contains(key)) << key;
    }
  }
  // The same export with one DFG term scaled by 1.01 (A, in dfg_read) fails, with exit 1. A metal: its specular
  // ambient is f0 A prefiltered (f0 = 0.9), so A x 1.01 moves its pixels by up to 2.5e-3 (seen); with ggx's
  // defaults (a dielectric) the largest move seen was 1.6e-3, still caught.
  const std::string params = "--param metallic=1 --param base_color=0.9 --param perceptual_roughness=0.4";
  const fs::path bad = broken("filament " + params + " --lang glsl --ibl", "bad_dfg.glsl", "ab.a = ", "ab.a = 1.01 * ");
  const auto r = run("shader verify filament " + params + " --lang glsl --ibl " + dir.string() + " --source " + bad.string() + " --json");
  EXPECT_EQ(r.code, 1) << r.out << r.err;
  EXPECT_GT(nlohmann::json::parse(r.out)["max_rel_error"].get<double>(), 1.5e-3);
  const auto good = run("shader verify filament " + params + " --lang glsl --ibl " + dir.string() + " --json");
  EXPECT_EQ(good.code, 0) << good.out << good.err;
}

TEST(CliShaderIbl, VerifyBakesAnEnvironmentImageItself) {
  // --ibl ENV runs `bake ibl ENV` with its defaults into a temporary folder first; the human-readable report.
  const auto r = run("shader verify ggx --lang glsl --ibl " + (fs::path(SHADELAB_BLENDER_WORLDS) / "studio.exr").string() +
                     " --ibl-size 48");
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("environment lighting under"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pixels: "), std::string::npos);
  EXPECT_NE(r.out.find("PASS"), std::string::npos);
}

}  // namespace ibl
