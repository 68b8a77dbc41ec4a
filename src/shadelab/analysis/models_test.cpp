// The statistical suite over EVERY model in the registry (brdf_models()), with 2-4 parameter sets each (5 for
// cook-torrance, whose d=ggx set runs its own GGX sampler):
// defaults, plus sharp / rough variants chosen from the parameters a model declares (n, alpha, alpha_x/y, m,
// w, lobes), so a model added to the registry is covered without touching this file. Per set: finite,
// non-negative values over 1e6 random direction pairs (grazing and below-horizon ones included), reciprocity,
// energy (asserted for the sets known to conserve energy, measured and recorded for the others), chi-square
// of the sampler against the pdf, sample weight == f cos / pdf, and the pdf's integral over the sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "shadelab/analysis/albedo.h"
#include "shadelab/analysis/chi_square.h"
#include "shadelab/analysis/test_brdfs.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

using testing::view;

struct ParamSet {
  std::string model;
  std::string label;  // defaults | sharp | rough | extra
  ParamAssignments params;
  bool conserves_energy = false;  // asserted: max albedo <= 1 + 1e-6
};

bool has(const ModelInfo& m, std::string_view name) {
  return std::any_of(m.params.begin(), m.params.end(), [&](const ParamSpec& p) { return p.name == name; });
}

std::string value_of(const ParamSet& s, const ModelInfo& m, std::string_view name) {
  for (const auto& [k, v] : s.params) {
    if (k == name) return v;
  }
  for (const auto& p : m.params) {
    if (p.name == name) return p.default_value;
  }
  return {};
}

// Which of the sets may be asserted to conserve energy, from what is known about the models (the zoo's
// normalized forms with kd + ks <= 1, Lambert and wrapped diffuse with kd <= 1, microfacet Cook-Torrance
// with a physical masking term and kd = 0). Everything else is measured and recorded, not asserted.
bool known_to_conserve(const ParamSet& s, const ModelInfo& m) {
  const auto number = [&](std::string_view name) {
    auto v = parse_numbers(value_of(s, m, name));
    return v && !v->empty() ? *std::max_element(v->begin(), v->end()) : 0.0;
  };
  if (s.model == "lambert" || s.model == "wrapped-diffuse") return number("kd") <= 1.0;
  if (s.model == "phong" || s.model == "phong-modified" || s.model == "blinn-phong" ||
      s.model == "blinn-phong-modified") {
    return value_of(s, m, "normalization") == "exact" && number("kd") + number("ks") <= 1.0;
  }
  if (s.model == "cook-torrance") {
    return number("kd") == 0.0 && number("ks") <= 1.0 && value_of(s, m, "form") == "microfacet" &&
           value_of(s, m, "g") != "kelemen";
  }
  // Single-scattering GGX with F <= 1 and no diffuse base (with ms = kulla-conty the albedo may exceed 1 by the
  // tables' interpolation error, below 3e-4: asserted by the furnace tests, not here).
  if (s.model == "ggx") return number("kd") == 0.0 && value_of(s, m, "ms") == "none";
  return false;
}

std::vector<ParamSet> param_sets() {
  std::vector<ParamSet> sets;
  for (const ModelInfo& m : brdf_models()) {
    // measured needs a file: its samplers are tested on measured tables by analysis/measured_test.cpp.
    if (needs_input_file(m)) continue;
    std::vector<ParamSet> mine;
    mine.push_back({m.name, "defaults", {}, false});
    ParamAssignments sharp;
    ParamAssignments rough;
    ParamAssignments extra;
    if (has(m, "kd")) sharp.emplace_back("kd", "0");
    if (has(m, "ks")) sharp.emplace_back("ks", "1");
    if (has(m, "n")) {
      sharp.emplace_back("n", "2000");
      rough.emplace_back("n", "2");
    } else if (has(m, "m")) {
      sharp.emplace_back("m", "0.05");
      rough.emplace_back("m", "0.8");
    }
    if (has(m, "alpha")) {
      sharp.emplace_back("alpha", "0.03");
      rough.emplace_back("alpha", "0.6");
    }
    if (has(m, "alpha_x") && has(m, "alpha_y") && !has(m, "alpha")) {
      sharp.emplace_back("alpha_x", "0.3");
      sharp.emplace_back("alpha_y", "0.02");
      rough.emplace_back("alpha_x", "0.05");
      rough.emplace_back("alpha_y", "0.7");
    }
    if (has(m, "roughness") && !has(m, "alpha")) {  // burley
      sharp.emplace_back("roughness", "0");
      rough.emplace_back("roughness", "1");
    }
    if (has(m, "perceptual_roughness")) {  // filament
      sharp.emplace_back("metallic", "1");
      sharp.emplace_back("perceptual_roughness", "0.1");
      rough.emplace_back("perceptual_roughness", "1");
    }
    if (has(m, "w")) {
      sharp.emplace_back("w", "0");
      rough.emplace_back("w", "1");
    }
    if (has(m, "lobes")) {
      sharp.emplace_back("lobes", "-1,-1,1,2000");
      rough.emplace_back("lobes", "0.8,0.8,0.9,10;-1,-1,1,200");
      extra = {{"lobes", "-0.6,-1.1,1,40;-1,-1,-0.5,8"}};  // anisotropic, and a lobe pointing below
    }
    // Model-specific extras: the unnormalized zoo forms, and Cook-Torrance's other terms.
    if (has(m, "normalization")) extra = {{"normalization", "none"}, {"n", "30"}};
    if (m.name == "cook-torrance") {
      extra = {{"kd", "0"}, {"d", "blinn-phong"}, {"g", "cook-torrance"}, {"f", "dielectric"}, {"n", "100"}};
    }
    if (m.name == "lambert") extra = {{"kd", "1"}};
    // GGX: anisotropic, with multiple scattering and a conductor; Filament: Burley diffuse, no compensation.
    if (m.name == "ggx") {
      extra = {{"kd", "0.1"}, {"alpha_x", "0.5"}, {"alpha_y", "0.05"}, {"f", "conductor"}, {"ior", "0.2,0.9,1.1"},
               {"k", "3.9,2.4,2.2"}, {"ms", "kulla-conty"}, {"g", "smith-separable"}};
    }
    // glTF: a sharp anisotropic dielectric with the ashikhmin sheen; a rough coloured metal under a clearcoat with the
    // charlie sheen; a specular-coloured dielectric (KHR_materials_specular, _ior).
    if (m.name == "gltf") {
      sharp = {{"metallic", "0"}, {"roughness", "0.2"}, {"anisotropy_strength", "0.8"}, {"anisotropy_rotation", "0.7"},
               {"sheen_color", "0.9,0.6,0.3"}, {"sheen_roughness", "0.3"}, {"sheen_visibility", "ashikhmin"}};
      rough = {{"base_color", "0.9,0.6,0.2"}, {"roughness", "0.8"}, {"clearcoat", "1"}, {"clearcoat_roughness", "0.1"},
               {"sheen_color", "0.5,0.5,0.5"}, {"sheen_roughness", "0.8"}};
      extra = {{"metallic", "0"}, {"base_color", "0.7,0.2,0.2"}, {"roughness", "0.5"}, {"ior", "1.33"},
               {"specular", "0.6"}, {"specular_color", "2,1,0.5"}};
    }
    // OpenPBR: a sharp anisotropic F82 metal (reciprocal); every layer on and rough in the view form (an absorbing
    // coat, fuzz); the reciprocal form over a metal-dielectric mix. EON's roughness (sigma > 0: its s/t kink along
    // phi = +-90 deg and mu_i = mu_o) and the coat in the reciprocal form make each albedo quadrature 3-10 times
    // slower; they are proved in analysis/openpbr_test.cpp and brdf/openpbr_test.cpp instead (docs/testing.md).
    if (m.name == "openpbr") {
      sharp = {{"base_metalness", "1"}, {"base_color", "0.9,0.6,0.3"}, {"specular_color", "0.8,0.9,1"},
               {"specular_roughness", "0.3"}, {"specular_roughness_anisotropy", "0.6"}};
      rough = {{"specular_roughness", "1"}, {"coat_weight", "1"}, {"coat_roughness", "0.4"}, {"coat_color", "0.6,0.8,0.9"},
               {"fuzz_weight", "0.6"}, {"fuzz_color", "0.9,0.5,0.3"}, {"fuzz_roughness", "0.8"}};
      extra = {{"layering", "reciprocal"}, {"base_metalness", "0.3"}, {"specular_ior", "2"}, {"specular_roughness", "0.5"}};
    }
    if (m.name == "filament") extra = {{"diffuse", "burley"}, {"energy_compensation", "off"}, {"metallic", "0.5"}};
    // The layered ground truth: a near-smooth coat over a sharp conductor, a rough coat over the ggx base through
    // an absorbing slab (one walk per eval: each eval is a Monte Carlo estimate, and the suite evaluates millions).
    if (m.name == "layered") {
      sharp = {{"coat_roughness", "0"}, {"base", "conductor"}, {"base_roughness", "0.2"}, {"base_f82", "0.8,0.9,1"}};
      rough = {{"coat_roughness", "1"}, {"base", "ggx"}, {"base_roughness", "1"}, {"coat_color", "0.5,0.7,0.9"},
               {"coat_ior", "2.5"}};
    }
    // Blender's Principled (reflection): a sharp anisotropic metal under a sharp GTR1 coat; every lobe at 1 and rough;
    // specular 0 (eta = 1) with a rotated anisotropic lobe and sheen.
    if (m.name == "principled-v1") {
      sharp = {{"metallic", "1"}, {"base_color", "0.95,0.64,0.54"}, {"roughness", "0.05"}, {"anisotropic", "0.8"},
               {"anisotropic_rotation", "0.125"}, {"clearcoat", "1"}};
      rough = {{"base_color", "0.9,0.5,0.2"}, {"roughness", "1"}, {"specular", "1"}, {"specular_tint", "1"}, {"sheen", "1"},
               {"sheen_tint", "1"}, {"clearcoat", "1"}, {"clearcoat_roughness", "1"}};
      extra = {{"specular", "0"}, {"metallic", "0.3"}, {"roughness", "0.3"}, {"anisotropic", "1"},
               {"anisotropic_rotation", "0.3"}, {"sheen", "0.5"}};
    }
    if (!sharp.empty()) mine.push_back({m.name, "sharp", sharp, false});
    if (!rough.empty()) mine.push_back({m.name, "rough", rough, false});
    if (!extra.empty()) mine.push_back({m.name, "extra", extra, false});
    // Cook-Torrance with GGX's D: its own NDF sampler and pdf (cook_torrance.cpp), and GGX's Smith G.
    if (m.name == "cook-torrance") mine.push_back({m.name, "ggx", {{"kd", "0"}, {"d", "ggx"}, {"m", "0.05"}}, false});
    for (auto& s : mine) s.conserves_energy = known_to_conserve(s, m);
    if (m.name == "layered") {
      for (auto& s : mine) s.params.emplace_back("walk_samples", "1");
    }
    sets.insert(sets.end(), mine.begin(), mine.end());
  }
  return sets;
}

const std::vector<ParamSet>& all_sets() {
  static const std::vector<ParamSet> sets = param_sets();
  return sets;
}

std::string describe(const ParamSet& s) {
  std::string text = s.model;
  for (const auto& [k, v] : s.params) text += " " + k + "=" + v;
  return text;
}

// How GoogleTest prints a parameter (test listings, CTest names, failures): the model and its parameters,
// not "96-byte object <90-FB ...>".
void PrintTo(const ParamSet& s, std::ostream* os) { *os << describe(s) << " (" << s.label << ")"; }

constexpr double chi_square_angles[] = {0.0, 30.0, 60.0, 80.0};
constexpr double check_angles[] = {0.0, 30.0, 60.0, 80.0, 89.0};

class Models : public ::testing::TestWithParam<ParamSet> {
 protected:
  void SetUp() override {
    auto f = make_brdf(GetParam().model, GetParam().params);
    ASSERT_TRUE(f) << f.error().message;
    m_brdf = std::move(f).value();
  }
  const Brdf& brdf() const { return *m_brdf; }
  std::string name() const { return describe(GetParam()); }

 private:
  BrdfPtr m_brdf;
};

// A direction for the stress test: uniform over the sphere, grazing (|z| < 1e-4, sometimes exactly 0), or
// one of a few special ones relative to the other direction.
Vec3 stress_direction(Pcg32& rng, int kind) {
  const double phi = two_pi * rng.next_double();
  double z = 0.0;
  switch (kind) {
    case 0: z = 1.0 - 2.0 * rng.next_double(); break;                   // sphere
    case 1: z = (2.0 * rng.next_double() - 1.0) * 1e-4; break;          // grazing, either side
    case 2: z = rng.next_double() < 0.5 ? 0.0 : 1e-12; break;          // on / just above the horizon
    default: z = rng.next_double() < 0.5 ? 1.0 : -1.0; break;           // the poles
  }
  return spherical_direction(std::sqrt(std::max(0.0, 1.0 - z * z)), z, phi);
}

TEST_P(Models, FiniteAndNonNegativeEverywhere) {
  Pcg32 rng(0x57e55, 11);
  int failures = 0;
  std::string first;
  const auto fail = [&](const std::string& what, const Vec3& wi, const Vec3& wo) {
    if (failures++ == 0) {
      std::ostringstream os;
      os.precision(17);
      os << what << " at wi (" << wi.x << ", " << wi.y << ", " << wi.z << "), wo (" << wo.x << ", " << wo.y << ", "
         << wo.z << ")";
      first = os.str();
    }
  };
  const auto finite_non_negative = [](const Rgb& c) { return is_finite(c) && c.r >= 0.0 && c.g >= 0.0 && c.b >= 0.0; };
  for (int i = 0; i < 1'000'000; ++i) {
    // Kinds: 60% both uniform, then grazing / horizon / pole mixes on either side, and special pairs.
    const int mix = i % 10;
    Vec3 wo = stress_direction(rng, mix < 6 ? 0 : (mix == 6 ? 1 : (mix == 7 ? 0 : (mix == 8 ? 2 : 3))));
    Vec3 wi = stress_direction(rng, mix < 6 ? 0 : (mix == 6 ? 0 : (mix == 7 ? 1 : (mix == 8 ? 1 : 2))));
    if (i % 1000 == 1) wi = wo;
    if (i % 1000 == 2) wi = -wo;
    if (i % 1000 == 3) wi = {-wo.x, -wo.y, wo.z};  // the mirror direction
    const Rgb f = brdf().eval(wi, wo);
    if (!finite_non_negative(f)) fail("eval not finite / negative", wi, wo);
    if ((wi.z <= 0.0 || wo.z <= 0.0) && !f.is_black()) fail("eval non-zero below the horizon", wi, wo);
    const double p = brdf().pdf(wi, wo);
    if (!std::isfinite(p) || p < 0.0) fail("pdf not finite / negative", wi, wo);
    // Sampling, with the extremes of u included.
    const double ux = i % 97 == 0 ? 0.0 : (i % 89 == 0 ? 0x1.fffffffffffffp-1 : rng.next_double());
    const double uy = rng.next_double();
    const double ul = i % 83 == 0 ? 0x1.fffffffffffffp-1 : rng.next_double();
    const BrdfSample s = brdf().sample(wo, {ux, uy}, ul);
    if (!std::isfinite(s.pdf) || s.pdf < 0.0 || !finite_non_negative(s.weight)) fail("sample pdf/weight bad", s.wi, wo);
    if (s.pdf > 0.0 && (!is_finite(s.wi) || std::abs(length(s.wi) - 1.0) > 1e-9)) fail("sample wi not unit", s.wi, wo);
    if (wo.z <= 0.0 && (s.pdf != 0.0 || !s.weight.is_black())) fail("sample with wo below the horizon", s.wi, wo);
    if (s.wi.z <= 0.0 && !s.weight.is_black()) fail("sample weight non-zero below the horizon", s.wi, wo);
  }
  EXPECT_EQ(failures, 0) << name() << ": first: " << first;
}

TEST_P(Models, Reciprocity) {
  const ReciprocityResult r = reciprocity_error(brdf());
  ::testing::Test::RecordProperty("reciprocity_error", std::to_string(r.max_relative_error));
  if (brdf().is_reciprocal()) {
    EXPECT_LE(r.max_relative_error, 1e-12) << name();
  } else {
    EXPECT_GT(r.max_relative_error, 1e-6) << name() << " says it is not reciprocal, but is to 1e-6";
  }
}

TEST_P(Models, Energy) {
  const AlbedoMax m = max_albedo(brdf());
  EXPECT_TRUE(m.converged) << name();
  std::ostringstream os;
  os.precision(10);
  os << m.value << " at theta_o = " << m.theta_deg << " deg";
  ::testing::Test::RecordProperty("max_albedo", os.str());
  if (GetParam().conserves_energy) {
    EXPECT_LE(m.value, 1.0 + 1e-6) << name() << ": max albedo " << os.str();
  } else {
    std::printf("[ energy   ] %-70s max albedo %s%s\n", name().c_str(), os.str().c_str(),
                m.value > 1.0 + 1e-6 ? "  (exceeds 1)" : "");
  }
}

int chi_square_test_count() {
  return static_cast<int>(all_sets().size() * std::size(chi_square_angles));
}

TEST_P(Models, ChiSquare) {
  // Sidak over every chi-square test of this suite, so that a correct suite fails with probability 0.01.
  const double level = sidak_significance(0.01, chi_square_test_count());
  ChiSquareOptions o;
  o.samples = 500'000;
  for (double t : chi_square_angles) {
    const ChiSquareResult r = chi_square_test(brdf(), view(t), o);
    ::testing::Test::RecordProperty("p_value_theta_" + std::to_string(static_cast<int>(t)), std::to_string(r.p_value));
    EXPECT_GE(r.p_value, level) << name() << " theta_o " << t << ": statistic " << r.statistic << ", dof "
                                << r.degrees_of_freedom << ", invalid " << r.invalid_samples << ", unexpected "
                                << r.unexpected_samples;
    EXPECT_NEAR(r.expected_total, static_cast<double>(o.samples), 1e-4 * static_cast<double>(o.samples)) << name();
  }
}

TEST_P(Models, SampleWeightIsFCosOverPdf) {
  for (double t : check_angles) {
    // Independent of sample(): the mean weight is the directional albedo by quadrature (5 standard errors).
    // (A stochastic model's albedo is its sampler's mean, albedo.h: nothing independent to compare with; its
    // albedo is proved against closed forms in its own tests, brdf/layered_test.cpp.)
    const WeightMean m = brdf().is_stochastic() ? WeightMean{} : weight_mean(brdf(), view(t), 100'000);
    EXPECT_LE(m.max_z, 5.0) << name() << " theta_o " << t << ": mean weight " << m.mean.r << ", " << m.mean.g << ", "
                            << m.mean.b << " vs albedo " << m.albedo.r << ", " << m.albedo.g << ", " << m.albedo.b;
    const SampleConsistency c = sample_consistency(brdf(), view(t), 100'000);
    EXPECT_LE(c.max_pdf_error, 1e-6) << name() << " theta_o " << t;
    EXPECT_LE(c.max_weight_error, 1e-6) << name() << " theta_o " << t;
    EXPECT_EQ(c.nonzero_weight_below_horizon, 0u) << name() << " theta_o " << t;
    EXPECT_EQ(c.non_finite, 0u) << name() << " theta_o " << t;
    EXPECT_EQ(c.zero_pdf, 0u) << name() << " theta_o " << t;
  }
}

TEST_P(Models, PdfIntegratesToOne) {
  for (double t : check_angles) {
    const QuadratureResult q = pdf_integral(brdf(), view(t));
    // With the mass below the horizon sampled (pdf_smooth_below_horizon() false), 4 standard errors.
    EXPECT_NEAR(q.value, 1.0, std::max(1e-6, 4.0 * q.error)) << name() << " theta_o " << t;
  }
}

// CTest lists parameterized tests with GoogleTest's print of the parameter: it must read as the model and
// its parameters (issue 16, 7), not as the object's bytes.
TEST(ModelsSuite, ParametersPrintReadably) {
  const ParamSet p{"cook-torrance", "extra", {{"kd", "0"}, {"n", "100"}}, false};
  EXPECT_EQ(::testing::PrintToString(p), "cook-torrance kd=0 n=100 (extra)");
}

TEST(ModelsSuite, CoversEveryRegisteredModel) {
  for (const ModelInfo& m : brdf_models()) {
    if (needs_input_file(m)) continue;  // measured: analysis/measured_test.cpp
    const auto n = std::count_if(all_sets().begin(), all_sets().end(), [&](const ParamSet& s) { return s.model == m.name; });
    EXPECT_GE(n, 2) << m.name;
    EXPECT_LE(n, m.name == "cook-torrance" ? 5 : 4) << m.name;  // cook-torrance: one set per D (d=ggx the fifth)
  }
  // Cook-Torrance's GGX distribution is in the suite, and asserted to conserve energy (kd = 0, microfacet form).
  const auto ct_ggx = std::find_if(all_sets().begin(), all_sets().end(), [](const ParamSet& s) {
    const std::pair<std::string, std::string> d_ggx{"d", "ggx"};
    return s.model == "cook-torrance" && std::find(s.params.begin(), s.params.end(), d_ggx) != s.params.end();
  });
  ASSERT_NE(ct_ggx, all_sets().end());
  EXPECT_TRUE(ct_ggx->conserves_energy);
  // The energy assertion is not vacuous: the zoo models' normalized sets are asserted.
  const auto asserted = std::count_if(all_sets().begin(), all_sets().end(), [](const ParamSet& s) { return s.conserves_energy; });
  EXPECT_GE(asserted, 10);
}

std::string test_name(const ::testing::TestParamInfo<ParamSet>& info) {
  std::string n = info.param.model + "_" + info.param.label;
  std::replace(n.begin(), n.end(), '-', '_');
  return n;
}

INSTANTIATE_TEST_SUITE_P(Registry, Models, ::testing::ValuesIn(all_sets()), test_name);

}  // namespace
}  // namespace shadelab
