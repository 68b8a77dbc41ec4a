// GLSL ES in headless Chromium's WebGL 2 (ANGLE on SwiftShader): every model's export, baked and with a uniform
// block, agrees with the C++ reference on the default direction pairs, all in one browser start; a shader that
// does not compile gives the browser compiler's first error line, naming the file and line.
#include "webgl.h"

#include <gtest/gtest.h>

#include "export.h"
#include "shadelab/brdf/registry.h"
#include "verify.h"

namespace shadelab::shaders {
namespace {

TEST(WebGL2, EveryModelBakedAndUniformAgreesWithTheReference) {
  std::vector<WebglProgram> programs;
  std::vector<std::string> labels;
  std::vector<BrdfPtr> refs;
  for (const auto& m : brdf_models()) {
    if (!m.no_shader.empty() || make_brdf(m.name).value()->is_stochastic()) continue;  // no shader: openpbr, measured (ModelInfo::no_shader; measured has no default file); the Monte Carlo ground truth
    for (bool uniforms : {false, true}) {
      if (uniforms && !(m.name == "lafortune" || m.name == "cook-torrance" || m.name == "phong")) continue;
      ExportOptions o;
      o.lang = Lang::essl;
      o.uniforms = uniforms;
      auto ex = export_model(m.name, {}, o);
      ASSERT_TRUE(ex.has_value()) << m.name;
      programs.push_back({ex->text, ex->entry + "(wi, wo)", uniforms ? ex->uniform_data : std::vector<std::uint8_t>{},
                          ex->block_name, m.name + ".essl", ex->tables_data, {}});
      labels.push_back(m.name + (uniforms ? " --uniforms" : ""));
      refs.push_back(std::move(make_brdf(m.name)).value());
    }
  }
  const std::vector<float> pairs = verification_pairs(100000, kDefaultSeed);
  auto batch = run_webgl_batch(programs, pairs);
  ASSERT_TRUE(batch.has_value()) << batch.error().message;
  ASSERT_EQ(batch->size(), programs.size());
  for (std::size_t i = 0; i < programs.size(); ++i) {
    SCOPED_TRACE(labels[i]);
    const auto& r = (*batch)[i];
    ASSERT_TRUE(r.has_value()) << r.error().message;
    EXPECT_NE(r->renderer.find("SwiftShader"), std::string::npos) << r->renderer;
    const Brdf& f = *refs[i];
    const DeviceReport d = compare_outputs(r->renderer, pairs, r->output, [&](const Vec3& wi, const Vec3& wo) { return f.eval(wi, wo); });
    EXPECT_EQ(d.nonfinite, 0u);
    EXPECT_LE(d.max_rel_error, kDefaultTolerance);
  }
}

TEST(WebGL2, ACompileErrorNamesTheFileAndLine) {
  const std::vector<float> pairs = verification_pairs(64, kDefaultSeed);
  const std::string good = "vec3 f(vec3 wi, vec3 wo) { return vec3(wi.z); }\n";
  const std::string bad = "vec3 f(vec3 wi, vec3 wo) {\n  return vec3(undeclared_name);\n}\n";
  auto batch = run_webgl_batch({{bad, "f(wi, wo)", {}, "", "bad.essl", {}, {}}, {good, "f(wi, wo)", {}, "", "good.essl", {}, {}}}, pairs);
  ASSERT_TRUE(batch.has_value()) << batch.error().message;
  ASSERT_EQ(batch->size(), 2u);
  ASSERT_FALSE((*batch)[0].has_value());
  const std::string& msg = (*batch)[0].error().message;
  EXPECT_EQ(msg.rfind("bad.essl:2: ", 0), 0u) << msg;
  EXPECT_NE(msg.find("undeclared_name"), std::string::npos) << msg;
  ASSERT_TRUE((*batch)[1].has_value()) << (*batch)[1].error().message;  // the next program still runs
  EXPECT_FLOAT_EQ((*batch)[1]->output[2], pairs[2]);  // vec3(wi.z) for case 0
}

}  // namespace
}  // namespace shadelab::shaders
