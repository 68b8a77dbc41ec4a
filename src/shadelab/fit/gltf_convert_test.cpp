// The spec-gloss -> metallic-roughness conversion (fit/gltf_convert.h): exact where metallic-roughness can represent
// the material, a reported difference where it cannot, never worse than PR #1719's analytic start.
#include "shadelab/fit/gltf_convert.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "shadelab/analysis/albedo.h"
#include "shadelab/core/constants.h"

namespace shadelab {
namespace {

void print(const char* name, const GltfMaterialConversion& c) {
  std::printf("%s: PR #1719 max %.3g rms %.3g -> fitted max %.3g rms %.3g (metallic %.4f roughness %.4f specular %.4f, "
              "%lld evaluations)\n",
              name, c.start_difference.max, c.start_difference.rms, c.difference.max, c.difference.rms,
              c.result.metallic, c.result.roughness, c.result.specular, static_cast<long long>(c.evaluations));
}

// A black diffuse: spec-gloss is F(specular) D V alone, which both the metal branch (baseColor = specular) and the
// dielectric with f0 = specular represent exactly.
TEST(GltfConvert, ARepresentableMaterialConvertsExactly) {
  SpecGloss::Params sg;
  sg.diffuse = Rgb{0.0, 0.0, 0.0};
  sg.specular = Rgb{0.9, 0.6, 0.3};
  sg.glossiness = 0.7;
  const GltfMaterialConversion c = convert_spec_gloss(sg);
  print("black diffuse", c);
  EXPECT_LT(c.difference.max, 1e-4);
  // The fast rule finds it too (its albedo by quadrature, not by its tables).
  const FastConversion fast = convert_spec_gloss_fast(sg);
  EXPECT_LT(albedo_difference(sg, fast.result).max, 1e-4);
  // PR #1719's f0 = 0.996 specular leaves a difference the fit removes.
  EXPECT_GT(c.start_difference.max, 1e-4);
}

// A coloured diffuse under a 4% specular: glTF weighs the diffuse by 1 - F(V.H), spec-gloss by the constant 0.96,
// so no factors match at every angle; the fit trades the angles against each other (its RMS below the start's).
TEST(GltfConvert, ADiffuseMaterialIsReportedAndTheFitBeatsTheStart) {
  SpecGloss::Params sg;
  sg.diffuse = Rgb{0.6, 0.4, 0.2};
  sg.specular = Rgb{0.04, 0.04, 0.04};
  sg.glossiness = 0.5;
  const GltfMaterialConversion c = convert_spec_gloss(sg);
  print("diffuse", c);
  EXPECT_LE(c.difference.rms, c.start_difference.rms);
  EXPECT_LT(c.difference.rms, 0.5 * c.start_difference.rms);
  EXPECT_GT(c.start_difference.max, 1e-3);
  // The reported difference is the one albedo_difference measures for the result.
  EXPECT_DOUBLE_EQ(albedo_difference(sg, c.result).max, c.difference.max);
  // The fast per-texel rule (tables + Levenberg-Marquardt) against this exact fit, both measured by quadrature:
  // its max difference within kFastExcess of the fit's, its RMS below PR #1719's.
  const FastConversion fast = convert_spec_gloss_fast(sg);
  const AlbedoDifference d = albedo_difference(sg, fast.result);
  std::printf("fast rule: max %.3g rms %.3g (exact fit max %.3g rms %.3g), %d steps; roughness %.4f specular %.4f\n", d.max,
              d.rms, c.difference.max, c.difference.rms, fast.iterations, fast.result.roughness, fast.result.specular);
  constexpr double kFastExcess = 2e-4;  // docs/conversions.md, "The fast rule"
  EXPECT_LT(d.max, c.difference.max + kFastExcess);
  EXPECT_LT(d.rms, 0.5 * c.start_difference.rms);
}

// The directional albedos from the tables against adaptive quadrature of the two models themselves (SpecGloss and
// the gltf model), between the tables' roughness nodes (where the interpolation error is largest), for a spec-gloss
// and a metallic-roughness material with every term non-zero.
TEST(GltfConvert, TheTablesMatchTheQuadratureBetweenNodes) {
  const auto start = std::chrono::steady_clock::now();
  (void)gltf_albedo_tables();
  std::printf("tables built in %.2f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  const int nodes = gltf_albedo_tables().nodes;
  double worst = 0.0;
  int worst_j = -1, worst_k = -1;
  for (const int j : {0, 3, 20, 40, 63}) {
    const double r = (j + 0.5) / (nodes - 1);
    SpecGloss::Params sg;
    sg.diffuse = Rgb{0.5, 0.3, 0.1};
    sg.specular = Rgb{0.3, 0.05, 0.1};
    sg.glossiness = 1.0 - r;
    MetalRoughFactors m;
    m.base_color = Rgb{0.5, 0.3, 0.1};
    m.metallic = 0.3;
    m.roughness = r;
    m.ior = 1.5;
    m.specular = 0.7;
    m.specular_color = Rgb{1.0, 0.5, 2.0};  // f0 = (0.04, 0.02, 0.08): the max3 channel is blue
    const GridAlbedo a_sg = table_albedo(sg), a_m = table_albedo(m);
    for (int k = 0; k < GltfAlbedoTables::angles; ++k) {
      const double t = deg_to_rad(10.0 * k);
      AlbedoOptions o;
      o.quadrature.rel_tol = 1e-9;
      o.quadrature.abs_tol = 1e-12;
      o.axis = Vec3{-std::sin(t), 0.0, std::cos(t)};
      const Vec3 wo{std::sin(t), 0.0, std::cos(t)};
      const Rgb q_sg = directional_albedo(SpecGloss(sg), wo, o).albedo;
      const Rgb q_m = directional_albedo(Gltf(gltf_params(m)), wo, o).albedo;
      for (int c = 0; c < 3; ++c) {
        const double e = std::max(std::abs(a_sg[static_cast<std::size_t>(k)][c] - q_sg[c]), std::abs(a_m[static_cast<std::size_t>(k)][c] - q_m[c]));
        if (e > worst) {
          worst = e;
          worst_j = j;
          worst_k = k;
        }
      }
    }
  }
  std::printf("tables against quadrature: max |difference| %.3g (between nodes %d and %d, theta_o %d deg)\n", worst, worst_j,
              worst_j + 1, 10 * worst_k);
  EXPECT_LT(worst, 2e-5);  // docs/conversions.md, "The fast rule"
}

// Speed: unique texel values per second through the rule (one thread), for the docs.
TEST(GltfConvert, TheFastRuleIsFast) {
  (void)gltf_albedo_tables();
  const auto start = std::chrono::steady_clock::now();
  int n = 0;
  double sum = 0.0;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      for (int g = 0; g < 8; ++g, ++n) {
        SpecGloss::Params sg;
        sg.diffuse = Rgb{i / 7.0, j / 7.0, 0.5 * i / 7.0};
        sg.specular = Rgb{0.02 + 0.1 * j / 7.0, 0.04, 0.04 + 0.2 * i / 7.0};
        sg.glossiness = g / 7.0;
        sum += convert_spec_gloss_fast(sg).result.roughness;
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("fast rule: %d materials in %.3f s, %.0f per second (one thread)\n", n, seconds, n / seconds);
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
}  // namespace shadelab
