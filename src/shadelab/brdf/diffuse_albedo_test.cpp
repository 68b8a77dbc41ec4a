// diffuse_albedo() of every model with a constant diffuse term: pi times that term, the directional albedo
// of the diffuse part alone (the game renderer's SH ambient multiplies it, render/game_renderer.cpp). The
// independent value is pi x eval with the specular lobe switched off (ks = 0), which goes through the
// model's kernel (kernels/*.sl), not through the LobeMixtureBrdf constructor that stores diffuse_albedo().
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>

#include "shadelab/brdf/registry.h"
#include "shadelab/brdf/test_util.h"
#include "shadelab/core/constants.h"

namespace shadelab {
namespace {

bool has_param(const ModelInfo& m, const std::string& name) {
  return std::any_of(m.params.begin(), m.params.end(), [&](const ParamSpec& p) { return p.name == name; });
}

TEST(DiffuseAlbedo, IsPiTimesTheDiffuseEvalForEveryModelWithKdAndKs) {
  int checked = 0;
  for (const ModelInfo& m : brdf_models()) {
    if (!has_param(m, "kd") || (!has_param(m, "ks") && m.name != "lambert")) continue;
    std::vector<std::string> normalizations{""};
    for (const ParamSpec& p : m.params)
      if (p.name == "normalization") normalizations = p.choices;
    for (const std::string& norm : normalizations) {
      ParamAssignments params{{"kd", "0.2,0.5,0.8"}};
      if (has_param(m, "ks")) params.emplace_back("ks", "0");
      if (!norm.empty()) params.emplace_back("normalization", norm);
      const BrdfPtr f = testing::make(m.name, params);
      ASSERT_TRUE(f) << m.name;
      for (const auto& [ti, pi_deg, to, po] : {std::array{0.0, 0.0, 0.0, 0.0}, std::array{30.0, 10.0, 60.0, 200.0},
                                              std::array{75.0, 90.0, 20.0, 300.0}}) {
        const Rgb expected = f->eval(testing::dir(ti, pi_deg), testing::dir(to, po)) * pi;
        testing::expect_rgb_near(f->diffuse_albedo(), expected, 1e-12);
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 10);  // lambert, the Phong family in every normalization, cook-torrance, ward, ...
}

}  // namespace
}  // namespace shadelab
