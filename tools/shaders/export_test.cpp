// Every model of the registry exports in every language, baked and with --uniforms, and the result compiles with
// glslang (GLSL 4.50, GLSL ES 3.00 and 3.10, HLSL); the uniform block's std140 offsets agree with glslang's own
// reflection; a binding that does not match its kernel struct is refused.
#include "export.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>

#include "glslang.h"
#include "process.h"
#include "shadelab/brdf/registry.h"

namespace shadelab::shaders {
namespace {

constexpr Lang kLangs[] = {Lang::glsl, Lang::essl, Lang::hlsl};

ShaderExport exported(const std::string& model, Lang lang, bool uniforms = false, ParamAssignments params = {}) {
  ExportOptions o;
  o.lang = lang;
  o.uniforms = uniforms;
  auto ex = export_model(model, params, o);
  EXPECT_TRUE(ex.has_value()) << model << ": " << (ex ? "" : ex.error().message);
  return ex ? *ex : ShaderExport{};
}

TEST(Export, FloatLiteralsReadBackAsTheNearestFloat) {
  EXPECT_EQ(float_literal(0.5), "0.5");
  EXPECT_EQ(float_literal(50.0), "50.0");
  EXPECT_EQ(float_literal(-1.0), "-1.0");
  EXPECT_EQ(float_literal(1e6), "1000000.0");
  for (double v : {0.1, 1.0 / 3.0, 3.14159265358979, 1e-5, 2.5e-12, 123456789.0, 1e20, -7.25e-3}) {
    const std::string s = float_literal(v);
    EXPECT_TRUE(s.find('.') != std::string::npos) << s;  // GLSL ES has no implicit int -> float
    EXPECT_EQ(std::strtof(s.c_str(), nullptr), static_cast<float>(v)) << s;
  }
}

// The layered ground truth's eval is a random walk: no kernel, and the exporter says so in one line.
TEST(Export, AStochasticModelIsRefusedByName) {
  auto ex = export_model("layered", {}, ExportOptions{});
  ASSERT_FALSE(ex.has_value());
  EXPECT_EQ(ex.error().message,
            "model 'layered' has no shader: its eval is a Monte Carlo estimate (a random walk), the ground truth that "
            "shaders are measured against");
}

// openpbr's kernel is C++-only (its dielectric table exceeds a GLSL ES uniform block): one line says so.
TEST(Export, AModelWithoutAShaderIsRefusedByName) {
  auto ex = export_model("openpbr", {}, ExportOptions{});
  ASSERT_FALSE(ex.has_value());
  EXPECT_EQ(ex.error().message,
            "model 'openpbr' has no shader: its dielectric albedo table (48 x 32 x 32) exceeds a GLSL ES uniform block "
            "and the kernel is not in the exporter's list (docs/models/openpbr.md, \"Shaders\")");
  // measured: refused before it is built, so without its (required) file and whatever the file is
  for (const ParamAssignments& p : {ParamAssignments{}, ParamAssignments{{"file", "/nonexistent/table.binary"}}}) {
    auto m = export_model("measured", p, ExportOptions{});
    ASSERT_FALSE(m.has_value());
    EXPECT_EQ(m.error().message, "model 'measured' has no shader: it reads a measured table (35 MB) from a file at run time; no shader binds one");
  }
}

TEST(Export, EveryModelHasABindingThatMatchesItsKernelStruct) {
  for (const auto& m : brdf_models()) {
    if (!m.no_shader.empty() || make_brdf(m.name).value()->is_stochastic()) continue;  // no shader: openpbr, measured (ModelInfo::no_shader; measured has no default file); the Monte Carlo ground truth
    auto brdf = make_brdf(m.name);
    ASSERT_TRUE(brdf.has_value()) << m.name;
    const auto binding = (*brdf)->kernel_binding();
    ASSERT_TRUE(binding.has_value()) << m.name << " has no kernel binding";
    const KernelLibrary& lib = KernelLibrary::embedded();
    const auto type = lib.prepare_parameter_type(binding->kernel);
    ASSERT_TRUE(type.has_value()) << m.name << ": no " << binding->kernel << "_prepare";
    const StructDecl* decl = lib.find_struct(*type);
    ASSERT_NE(decl, nullptr);
    EXPECT_TRUE(pack_std140(*decl, *binding).has_value()) << m.name;
  }
}

TEST(Export, ABindingThatDriftsFromItsStructIsRefused) {
  const StructDecl* decl = KernelLibrary::embedded().find_struct("WardParams");
  ASSERT_NE(decl, nullptr);
  const Rgb c{0.1, 0.2, 0.3};
  KernelBinding ok{"ward", {}};
  ok.add("kd", c).add("ks", c).add("alpha_x", 0.2).add("alpha_y", 0.1);
  EXPECT_TRUE(pack_std140(*decl, ok).has_value());
  KernelBinding swapped{"ward", {}};
  swapped.add("kd", c).add("ks", c).add("alpha_y", 0.1).add("alpha_x", 0.2);
  auto e1 = pack_std140(*decl, swapped);
  ASSERT_FALSE(e1.has_value());
  EXPECT_EQ(e1.error().message, "kernel binding of 'ward' field 2 is 'alpha_y', struct WardParams has 'alpha_x' there");
  KernelBinding short_colour{"ward", {}};
  short_colour.add("kd", 0.5).add("ks", c).add("alpha_x", 0.2).add("alpha_y", 0.1);
  EXPECT_FALSE(pack_std140(*decl, short_colour).has_value());
  KernelBinding missing{"ward", {}};
  missing.add("kd", c).add("ks", c).add("alpha_x", 0.2);
  EXPECT_FALSE(pack_std140(*decl, missing).has_value());
}

TEST(Export, OnlyTheKernelsAModelNeeds) {
  const std::string lambert = exported("lambert", Lang::glsl).text;
  EXPECT_NE(lambert.find("#ifndef SHADELAB_KERNEL_LAMBERT_SL"), std::string::npos);
  EXPECT_EQ(lambert.find("SHADELAB_KERNEL_FRESNEL_SL"), std::string::npos);
  EXPECT_EQ(lambert.find("float erf("), std::string::npos);
  EXPECT_EQ(lambert.find("PhongParams"), std::string::npos);
  const std::string ct = exported("cook-torrance", Lang::hlsl).text;
  EXPECT_NE(ct.find("float erf(float x)"), std::string::npos);
  EXPECT_LT(ct.find("SHADELAB_KERNEL_FRESNEL_SL"), ct.find("SHADELAB_KERNEL_COOK_TORRANCE_SL"));
  EXPECT_EQ(ct.find("SHADELAB_KERNEL_WARD_SL"), std::string::npos);
  // The game-shading pieces are in every export.
  for (const char* piece : {"float3 punctual_game(", "float3 sh9_irradiance_game(", "brdf_cook_torrance_punctual_radiometric("}) {
    EXPECT_NE(ct.find(piece), std::string::npos) << piece;
  }
}

TEST(Export, ParametersAreBakedFromTheBinding) {
  const std::string t = exported("phong", Lang::glsl, false, {{"n", "37"}, {"kd", "0.25,0.5,0.75"}, {"normalization", "none"}}).text;
  EXPECT_NE(t.find("  p.n = 37.0;\n"), std::string::npos);
  EXPECT_NE(t.find("  p.kd = vec3(0.25, 0.5, 0.75);\n"), std::string::npos);
  EXPECT_NE(t.find("  p.normalization = 0;\n"), std::string::npos);
  EXPECT_NE(t.find("Parameters: kd = 0.25,0.5,0.75, ks = 0.5,0.5,0.5, n = 37, normalization = none"), std::string::npos);
  const std::string h = exported("lafortune", Lang::hlsl, false, {{"lobes", "-1,-1,1,20;0.5,0.5,0.8,4"}}).text;
  EXPECT_NE(h.find("  p.count = 2;\n"), std::string::npos);
  EXPECT_NE(h.find("  p.cz[1] = 0.800000012;\n"), std::string::npos);
  EXPECT_NE(h.find("  p.n[7] = 0.0;\n"), std::string::npos);
}

TEST(Export, EntryNames) {
  EXPECT_EQ(default_entry("cook-torrance"), "brdf_cook_torrance");
  ExportOptions o;
  o.entry = "my_brdf";
  auto ex = export_model("ward", {}, o);
  ASSERT_TRUE(ex.has_value());
  EXPECT_NE(ex->text.find("vec3 my_brdf(vec3 wi, vec3 wo) {"), std::string::npos);
  for (const char* bad : {"1abc", "a-b", "gl_brdf", "a__b"}) {
    o.entry = bad;
    auto e = export_model("ward", {}, o);
    ASSERT_FALSE(e.has_value()) << bad;
    EXPECT_EQ(e.error().message, "--entry: '" + std::string(bad) + "' is not a valid function name");
  }
  auto unknown = export_model("no-such-model", {}, ExportOptions{});
  ASSERT_FALSE(unknown.has_value());
  EXPECT_NE(unknown.error().message.find("unknown BRDF model 'no-such-model'"), std::string::npos);
  auto bad_param = export_model("phong", {{"n", "-3"}}, ExportOptions{});
  ASSERT_FALSE(bad_param.has_value());
  EXPECT_EQ(bad_param.error().message, "brdf phong: parameter 'n' = -3 is out of range [0, 1e+06]");
}

// Every model, every language, baked and uniform: the file compiles (compute harness) and, for GLSL ES, passes
// glslang's ES 3.00 rules.
TEST(Export, EveryModelCompilesInEveryLanguage) {
  for (const auto& m : brdf_models()) {
    if (!m.no_shader.empty() || make_brdf(m.name).value()->is_stochastic()) continue;  // no shader: openpbr, measured (ModelInfo::no_shader; measured has no default file); the Monte Carlo ground truth
    for (Lang lang : kLangs) {
      for (bool uniforms : {false, true}) {
        SCOPED_TRACE(m.name + " " + lang_name(lang) + (uniforms ? " --uniforms" : ""));
        const ShaderExport ex = exported(m.name, lang, uniforms);
        const std::string expr = ex.entry + "(wi, wo) + " + ex.entry + "_punctual_game(wi, wo, wo) + " + ex.entry +
                                 "_punctual_radiometric(wi, wo, wi)";
        auto spirv = compile_compute(lang, compute_harness(lang, ex.text, expr), "exported");
        EXPECT_TRUE(spirv.has_value()) << (spirv ? "" : spirv.error().message);
        if (lang == Lang::essl) {
          auto ok = validate_essl300(ex.text, expr, "exported");
          EXPECT_TRUE(ok.has_value()) << (ok ? "" : ok.error().message);
        }
      }
    }
  }
}

TEST(Export, TwoExportsShareOneShader) {
  for (Lang lang : kLangs) {
    const std::string a = exported("phong", lang).text;
    const std::string b = exported("cook-torrance", lang).text;
    auto spirv = compile_compute(lang, compute_harness(lang, a + b, "brdf_phong(wi, wo) + brdf_cook_torrance(wi, wo)"), "two");
    EXPECT_TRUE(spirv.has_value()) << lang_name(lang) << ": " << (spirv ? "" : spirv.error().message);
  }
}

// The dialect's constant tables (as a model's E(mu, alpha) table would be) compile in every language and are
// read with a run-time index.
TEST(Export, ConstantTablesCompileInEveryLanguage) {
  const std::string sl = "const int TABLE_SIZE = 4;\nconst real TABLE[TABLE_SIZE] = {0.5, 0.25,\n  0.125, 0.0625};\n"
                         "inline rgb table_lookup(vec3 wi) {\n  int i = int(clamp(wi.z, 0.0, 0.999) * 4.0);\n"
                         "  return rgb(TABLE[i]);\n}\n";
  for (Lang lang : kLangs) {
    auto text = translate(sl, lang, "table.sl");
    ASSERT_TRUE(text.has_value()) << text.error().message;
    auto spirv = compile_compute(lang, compute_harness(lang, *text, "table_lookup(wi)"), "table");
    EXPECT_TRUE(spirv.has_value()) << lang_name(lang) << ": " << (spirv ? "" : spirv.error().message) << "\n" << *text;
    if (lang == Lang::essl) {
      auto ok = validate_essl300(*text, "table_lookup(wi)", "table");
      EXPECT_TRUE(ok.has_value()) << (ok ? "" : ok.error().message);
    }
  }
}

// kernels/display.sl's view transforms (the explorer's sphere runs them in WebGL 2) compile in every language.
TEST(Export, ViewTransformsCompileInEveryLanguage) {
  for (Lang lang : kLangs) {
    auto text = kernel_section({"view_transform", "srgb8_code"}, lang);
    ASSERT_TRUE(text.has_value()) << text.error().message;
    const std::string expr = "view_transform(VIEW_AGX, 0.5, wi) + view_transform(VIEW_PBR_NEUTRAL, -1.0, wo) + "
                             "view_transform(VIEW_ACES, 0.0, wi) * srgb8_code(wo.x)";
    auto spirv = compile_compute(lang, compute_harness(lang, *text, expr), "display");
    EXPECT_TRUE(spirv.has_value()) << lang_name(lang) << ": " << (spirv ? "" : spirv.error().message);
    if (lang == Lang::essl) {
      auto ok = validate_essl300(*text, expr, "display");
      EXPECT_TRUE(ok.has_value()) << (ok ? "" : ok.error().message);
    }
  }
}

// glslang's reflection (-q) lists each block member's byte offset: an independent reading of the layout rules.
TEST(Export, UniformOffsetsAgreeWithGlslangReflection) {
  for (const auto& m : brdf_models()) {
    if (!m.no_shader.empty() || make_brdf(m.name).value()->is_stochastic()) continue;  // no shader: openpbr, measured (ModelInfo::no_shader; measured has no default file); the Monte Carlo ground truth
    for (Lang lang : {Lang::glsl, Lang::hlsl}) {
      SCOPED_TRACE(m.name + " " + lang_name(lang));
      const ShaderExport ex = exported(m.name, lang, true);
      TempDir dir;
      const std::string path = (dir / (lang == Lang::hlsl ? "s.hlsl" : "s.comp")).string();
      ASSERT_TRUE(write_file(path, compute_harness(lang, ex.text, ex.entry + "(wi, wo)")).has_value());
      std::vector<std::string> args = {glslang_program(), "-V", "-S", "comp", "--auto-map-bindings", "-q", "-o",
                                       (dir / "s.spv").string()};
      if (lang == Lang::hlsl) args.insert(args.end(), {"-D", "-e", "main"});
      args.push_back(path);
      auto run = run_process(args, 120.0);
      ASSERT_TRUE(run.has_value());
      ASSERT_EQ(run->exit_code, 0) << run->out;
      for (const auto& f : ex.uniform_layout) {
        const std::regex line(ex.entry + "_params\\." + f.name + ": offset (\\d+)");
        std::smatch match;
        ASSERT_TRUE(std::regex_search(run->out, match, line)) << f.name << "\n" << run->out;
        EXPECT_EQ(std::stoul(match[1]), f.offset) << f.name;
      }
      const std::regex block(ex.block_name + ": offset -1, type ffffffff, size (\\d+), index \\d+, binding (\\d+)");
      std::smatch match;
      ASSERT_TRUE(std::regex_search(run->out, match, block)) << run->out;
      EXPECT_EQ(std::stoul(match[1]), ex.uniform_data.size());
      EXPECT_EQ(match[2], "0");  // the verifier binds the parameters at binding 0
    }
  }
}

}  // namespace
}  // namespace shadelab::shaders
