// The openpbr model's statistical proofs beyond the all-models suite (issue 37 section 2): the white furnace of
// every configuration OpenPBR's specification lists (white metal; white diffuse dielectric with specular; + white
// coat; + white fuzz; mixes) within 1e-3 of 1 in the view form (the specification's, where the claim holds) for
// roughness in [0, 1] and theta in [0, 85] deg, the reciprocal form's furnace measured; chi-square of its lobe
// mixture over 48 (material, theta) configurations with a Sidak correction; the pdf's integral; the sample weights
// against f cos / pdf and their mean against the albedo by quadrature (independent of sample()).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "shadelab/analysis/albedo.h"
#include "shadelab/analysis/chi_square.h"
#include "shadelab/analysis/test_brdfs.h"

namespace shadelab {
namespace {

using testing::make;
using testing::view;

std::string describe(const ParamAssignments& p) {
  std::string s = "openpbr";
  for (const auto& [k, v] : p) s += " " + k + "=" + v;
  return s;
}

// The specification's furnace list ("Glossy-diffuse", "Coat", "Fuzz": a white C passes the furnace test), each at
// roughness r for the specular, coat and fuzz lobes alike; the diffuse roughness at 0 and 1.
struct FurnaceConfig {
  std::string name;
  ParamAssignments params;
};
std::vector<FurnaceConfig> furnace_configs() {
  const ParamAssignments white_metal = {{"base_metalness", "1"}, {"base_color", "1"}, {"specular_color", "1"}};
  const ParamAssignments white_dielectric = {{"base_metalness", "0"}, {"base_color", "1"}};
  std::vector<FurnaceConfig> c;
  c.push_back({"white metal", white_metal});
  c.push_back({"white dielectric", white_dielectric});
  ParamAssignments rough = white_dielectric;
  rough.emplace_back("base_diffuse_roughness", "1");
  c.push_back({"white dielectric, EON 1", rough});
  ParamAssignments coat = white_dielectric;
  coat.insert(coat.end(), {{"coat_weight", "1"}, {"coat_color", "1"}});
  c.push_back({"+ white coat", coat});
  ParamAssignments metal_coat = white_metal;
  metal_coat.insert(metal_coat.end(), {{"coat_weight", "1"}, {"coat_color", "1"}, {"coat_ior", "2"}});
  c.push_back({"white metal + coat", metal_coat});
  ParamAssignments fuzz = coat;
  fuzz.insert(fuzz.end(), {{"fuzz_weight", "1"}, {"fuzz_color", "1"}});
  c.push_back({"+ white fuzz", fuzz});
  c.push_back({"mix", {{"base_color", "1"}, {"base_metalness", "0.5"}, {"base_diffuse_roughness", "0.5"}, {"specular_ior", "1.8"},
                       {"specular_roughness_anisotropy", "0"}, {"coat_weight", "0.5"}, {"coat_ior", "1.4"},
                       {"fuzz_weight", "0.5"}, {"coat_darkening", "0.3"}}});
  return c;
}

double furnace_albedo(const Brdf& f, double theta_deg) {
  // 1e-5: a hundredth of the claim's 1e-3 (1e-7 cost twice the time for digits the claim does not use).
  AlbedoOptions o;
  o.quadrature.rel_tol = 1e-5;
  return directional_albedo(f, deg_to_rad(theta_deg), o).albedo.g;
}

TEST(OpenpbrFurnace, ViewFormHoldsToOneThousandth) {
  double worst = 0.0;
  for (const auto& cfg : furnace_configs()) {
    for (double r : {0.0, 0.1, 0.3, 0.6, 1.0}) {
      ParamAssignments p = cfg.params;
      p.insert(p.end(), {{"specular_roughness", std::to_string(r)}, {"coat_roughness", std::to_string(r)},
                         {"fuzz_roughness", std::to_string(r)}});
      const BrdfPtr f = make("openpbr", p);
      double lo = 1e9, hi = -1e9;
      for (double t : {0.0, 30.0, 60.0, 75.0, 85.0}) {
        const double a = furnace_albedo(*f, t);
        lo = std::min(lo, a);
        hi = std::max(hi, a);
        EXPECT_NEAR(a, 1.0, 1e-3) << cfg.name << " roughness " << r << " theta " << t;
      }
      worst = std::max({worst, std::abs(lo - 1.0), std::abs(hi - 1.0)});
      std::printf("[ openpbr  ] furnace view %-24s r %.1f: albedo %.6f .. %.6f over theta 0..85\n", cfg.name.c_str(), r, lo, hi);
    }
  }
  std::printf("[ openpbr  ] furnace view: max |albedo - 1| = %.2e\n", worst);
}

// The reciprocal form: exact for the glossy-diffuse slab with the Lambertian base (the Kelemen normalization),
// energy conserving (<= 1) and darker under a coat or fuzz (symmetric attenuation); with a rough EON base the
// normalization is not exact (the specification leaves it to the implementation). Measured and printed.
TEST(OpenpbrFurnace, ReciprocalFormMeasured) {
  for (const auto& cfg : furnace_configs()) {
    for (double r : {0.1, 0.6}) {
      ParamAssignments p = cfg.params;
      p.insert(p.end(), {{"specular_roughness", std::to_string(r)}, {"coat_roughness", std::to_string(r)},
                         {"fuzz_roughness", std::to_string(r)}, {"layering", "reciprocal"}});
      const BrdfPtr f = make("openpbr", p);
      double lo = 1e9, hi = -1e9;
      for (double t : {0.0, 60.0, 85.0}) {
        const double a = furnace_albedo(*f, t);
        lo = std::min(lo, a);
        hi = std::max(hi, a);
      }
      std::printf("[ openpbr  ] furnace reciprocal %-24s r %.1f: albedo %.6f .. %.6f\n", cfg.name.c_str(), r, lo, hi);
      if (cfg.name == "white dielectric" || cfg.name == "white metal") {
        EXPECT_NEAR(lo, 1.0, 1e-3) << cfg.name;
        EXPECT_NEAR(hi, 1.0, 1e-3) << cfg.name;
      }
      // Conserving where the diffuse is Lambertian (the Kelemen normalization is exact only there; with EON's
      // sigma > 0 the reciprocal form's albedo moves both ways, printed above).
      const bool lambertian = std::none_of(cfg.params.begin(), cfg.params.end(),
                                           [](const auto& kv) { return kv.first == "base_diffuse_roughness"; });
      if (lambertian) {
        EXPECT_LE(hi, 1.0 + 1e-3) << cfg.name;
      }
    }
  }
}

// Twelve materials: every lobe alone and in combination, both forms, anisotropy, sharp and rough.
const std::vector<ParamAssignments>& materials() {
  static const std::vector<ParamAssignments> m = {
      {},  // OpenPBR's defaults
      {{"specular_roughness", "0.05"}},
      {{"base_color", "0.2,0.5,0.8"}, {"base_diffuse_roughness", "1"}, {"specular_roughness", "0.6"}},
      {{"base_metalness", "1"}, {"specular_roughness", "0.3"}, {"specular_roughness_anisotropy", "0.9"}},
      {{"base_metalness", "1"}, {"base_color", "0.9,0.6,0.3"}, {"specular_color", "0.5,0.7,1"}, {"specular_roughness", "1"}},
      {{"coat_weight", "1"}, {"coat_roughness", "0.03"}, {"specular_roughness", "0.5"}},
      {{"coat_weight", "0.6"}, {"coat_roughness", "0.4"}, {"coat_color", "0.8,0.5,0.2"}, {"base_metalness", "0.5"}},
      {{"fuzz_weight", "1"}, {"fuzz_roughness", "0.1"}, {"base_color", "0.1"}},
      {{"fuzz_weight", "0.7"}, {"fuzz_roughness", "0.9"}, {"fuzz_color", "0.9,0.6,0.4"}, {"specular_roughness", "0.2"}},
      {{"coat_weight", "1"}, {"coat_roughness", "0.1"}, {"fuzz_weight", "0.5"}, {"fuzz_roughness", "0.4"}, {"layering", "reciprocal"}},
      {{"specular_ior", "2.4"}, {"specular_roughness", "0.15"}, {"specular_roughness_anisotropy", "1"}, {"layering", "reciprocal"}},
      {{"base_weight", "0"}, {"specular_weight", "0"}, {"fuzz_weight", "0.3"}, {"fuzz_roughness", "1"}},
  };
  return m;
}

constexpr double thetas[] = {0.0, 35.0, 65.0, 85.0};

TEST(OpenpbrSamplers, ChiSquareOverFortyEightConfigurations) {
  const int tests = static_cast<int>(materials().size() * std::size(thetas));
  ASSERT_GE(tests, 48);
  const double level = sidak_significance(0.01, tests);
  ChiSquareOptions o;
  o.samples = 100'000;
  o.cos_theta_bins = 10;
  o.phi_bins = 20;
  double lowest = 1.0;
  for (const auto& p : materials()) {
    const BrdfPtr f = make("openpbr", p);
    for (double t : thetas) {
      const ChiSquareResult r = chi_square_test(*f, view(t), o);
      lowest = std::min(lowest, r.p_value);
      EXPECT_GE(r.p_value, level) << describe(p) << " theta " << t << ": statistic " << r.statistic << ", dof "
                                  << r.degrees_of_freedom << ", unexpected " << r.unexpected_samples;
    }
  }
  std::printf("[ openpbr  ] chi-square: %d configurations, lowest p %.3g (Sidak level %.3g)\n", tests, lowest, level);
}

TEST(OpenpbrSamplers, PdfIntegratesToOneAndWeightsAreFCosOverPdf) {
  double worst = 0.0;
  for (std::size_t k = 0; k < materials().size(); ++k) {
    const ParamAssignments& p = materials()[k];
    const BrdfPtr f = make("openpbr", p);
    for (double t : {0.0, 70.0}) {
      // The quadrature (0.4-1.8 s per integral, its evaluation budget) at 70 degrees for every material and at
      // normal incidence for every third; the sampled pdf and weights at both.
      if (t == 0.0 && k % 3 != 0) {
        const SampleConsistency c = sample_consistency(*f, view(t), 20'000);
        EXPECT_LE(c.max_pdf_error, 1e-6) << describe(p);
        EXPECT_LE(c.max_weight_error, 1e-6) << describe(p);
        EXPECT_EQ(c.non_finite, 0u) << describe(p);
        continue;
      }
      QuadratureOptions qo;  // 1e-6, not the default 1e-9: the bounded VNDF's cut at the horizon stalls it there
      qo.rel_tol = 1e-6;
      qo.initial_intervals = 4;
      const QuadratureResult q = pdf_integral(*f, view(t), qo);
      worst = std::max(worst, std::abs(q.value - 1.0));
      EXPECT_NEAR(q.value, 1.0, std::max(1e-6, 4.0 * q.error)) << describe(p) << " theta " << t;
      const SampleConsistency c = sample_consistency(*f, view(t), 20'000);
      EXPECT_LE(c.max_pdf_error, 1e-6) << describe(p);
      EXPECT_LE(c.max_weight_error, 1e-6) << describe(p);
      EXPECT_EQ(c.non_finite, 0u) << describe(p);
    }
  }
  std::printf("[ openpbr  ] pdf integral: max |integral - 1| = %.2e\n", worst);
}

// Independent of sample(): the mean weight equals the albedo by quadrature within 5 standard errors.
TEST(OpenpbrSamplers, MeanWeightIsTheAlbedo) {
  for (std::size_t k : {2u, 6u, 8u, 9u}) {
    const BrdfPtr f = make("openpbr", materials()[k]);
    for (double t : {20.0, 75.0}) {
      const WeightMean m = weight_mean(*f, view(t), 100'000);
      EXPECT_LE(m.max_z, 5.0) << describe(materials()[k]) << " theta " << t << ": " << m.mean.r << " vs " << m.albedo.r;
    }
  }
}

}  // namespace
}  // namespace shadelab
