// brdf/game_lobe.h and the game-shading kernels it feeds (kernels/game_ambient.sl, the point-light and
// game-colour helpers of game_shading.sl, kernels/display.sl), each against an independent computation:
// the prefiltered level inverts envmap/specular/prefilter.h's gloss mapping; the albedo lookup is exact at bin
// centres and linear between them; the mirror direction keeps the angle to the normal; the specular albedo
// table of a Phong lobe matches the closed-form albedo of the zoo at normal view; the display transform's
// sRGB codes match the published IEC 61966-2-1 values.
#include "shadelab/brdf/game_lobe.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/registry.h"
#include "shadelab/brdf/test_measured_file.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/envmap/specular/prefilter.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {
namespace {

TEST(GameKernels, PrefilteredLevelInvertsTheGlossMapping) {
  const PrefilterOptions po;
  for (int levels : {2, 5, 8}) {
    for (int i = 0; i < levels; ++i) {
      const double n = prefilter_exponent(i, levels, po.gloss_scale, po.gloss_bias);
      EXPECT_NEAR(kernel::game_prefiltered_level(n, levels, po.gloss_scale, po.gloss_bias), i, 1e-12) << levels << " " << i;
    }
    // Beyond the chain: clamped to its ends.
    EXPECT_EQ(kernel::game_prefiltered_level(1e9, levels, po.gloss_scale, po.gloss_bias), 0.0);
    EXPECT_EQ(kernel::game_prefiltered_level(0.0, levels, po.gloss_scale, po.gloss_bias), levels - 1.0);
  }
}

TEST(GameKernels, SpecularAlbedoIsLinearBetweenBinCentres) {
  kernel::GameSpecularAlbedo t;
  for (int b = 0; b < kernel::GAME_ALBEDO_BINS; ++b) t.bin[b] = Rgb{b * 1.0, b * b * 1.0, 7.0};
  const int bins = kernel::GAME_ALBEDO_BINS;
  for (int b = 0; b < bins; ++b) {
    const Rgb v = kernel::game_specular_albedo(t, (b + 0.5) / bins);
    EXPECT_NEAR(v.r, b, 1e-12);
    EXPECT_NEAR(v.g, b * b, 1e-12);
  }
  // A quarter of the way from centre 3 to centre 4: 3.25 on the line, 9 + 0.25 (16 - 9) on the parabola.
  const Rgb q = kernel::game_specular_albedo(t, (3.75) / bins);
  EXPECT_NEAR(q.r, 3.25, 1e-12);
  EXPECT_NEAR(q.g, 9.0 + 0.25 * 7.0, 1e-12);
  EXPECT_NEAR(q.b, 7.0, 1e-12);
  EXPECT_EQ(kernel::game_specular_albedo(t, 0.0).r, 0.0);           // below the first centre
  EXPECT_EQ(kernel::game_specular_albedo(t, 1.0).r, bins - 1.0);    // above the last
  EXPECT_EQ(kernel::game_specular_albedo(t, -3.0).r, 0.0);          // out of range: clamped
}

TEST(GameKernels, ReflectKeepsTheAngleToTheNormal) {
  const Vec3 n = normalize(Vec3{0.2, -0.3, 0.9});
  const Vec3 wo = normalize(Vec3{-0.5, 0.1, 0.7});
  const Vec3 r = kernel::game_reflect(wo, n);
  EXPECT_NEAR(length(r), 1.0, 1e-12);
  EXPECT_NEAR(dot(r, n), dot(wo, n), 1e-12);
  // r, wo and n are coplanar and wo + r is along n.
  const Vec3 s = wo + r;
  EXPECT_NEAR(length(cross(s, n)), 0.0, 1e-12);
}

TEST(GameKernels, SplitSumDirectionLeansFromTheMirrorToTheNormal) {
  // d = normalize(mix(R, n, alpha^2)): R for a mirror, n for alpha = 1, and in between on the great circle
  // from R to n at the angle from n that the plane's own trigonometry gives: with t = alpha^2 and theta_R
  // the angle of R from n, tan(theta_d) = (1 - t) sin(theta_R) / (t + (1 - t) cos(theta_R)).
  const Vec3 n = normalize(Vec3{0.1, 0.2, 0.95});
  for (const double nv : {0.05, 0.3, 0.7, 1.0}) {
    const Frame frame = Frame::from_normal(n);
    const Vec3 wo = frame.to_world({std::sqrt(1.0 - nv * nv), 0.0, nv});
    const Vec3 r = kernel::game_reflect(wo, n);
    const double theta_r = std::acos(std::clamp(dot(r, n), -1.0, 1.0));
    double last = theta_r + 1e-12;
    for (const double alpha : {0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0}) {
      const Vec3 d = kernel::game_split_sum_lookup(n, r, alpha);
      EXPECT_NEAR(length(d), 1.0, 1e-12);
      EXPECT_NEAR(dot(cross(r, n), d), 0.0, 1e-12);  // in the plane of R and n
      const double t = alpha * alpha;
      const double want = std::atan2((1.0 - t) * std::sin(theta_r), t + (1.0 - t) * std::cos(theta_r));
      EXPECT_NEAR(std::acos(std::clamp(dot(d, n), -1.0, 1.0)), want, 1e-7) << "nv " << nv << " alpha " << alpha;
      EXPECT_LE(std::acos(std::clamp(dot(d, n), -1.0, 1.0)), last);  // toward n as alpha grows
      last = std::acos(std::clamp(dot(d, n), -1.0, 1.0)) + 1e-12;
    }
    const Vec3 mirror = kernel::game_split_sum_lookup(n, r, 0.0);
    const Vec3 normal = kernel::game_split_sum_lookup(n, r, 1.0);
    EXPECT_NEAR(length(mirror - r), 0.0, 1e-12);
    EXPECT_NEAR(length(normal - n), 0.0, 1e-12);
  }
}

TEST(GameKernels, TheLobeDirectionTurnsTheNormalTowardRByTheAngle) {
  const Vec3 n = normalize(Vec3{0.3, -0.2, 0.9});
  for (const double nv : {0.05, 0.3, 0.7}) {
    // A view direction at N.V = nv, its mirror direction R.
    const Vec3 t = normalize(cross(n, Vec3{1.0, 0.0, 0.0}));
    const Vec3 wo = n * nv + t * std::sqrt(1.0 - nv * nv);
    const Vec3 r = kernel::game_reflect(wo, n);
    const double theta_r = std::acos(nv);
    for (const double angle : {-0.1, 0.0, 0.4, theta_r, 1.5}) {
      const Vec3 d = kernel::game_split_sum_lobe_direction(n, r, angle);
      EXPECT_NEAR(length(d), 1.0, 1e-12);
      EXPECT_NEAR(dot(cross(r, n), d), 0.0, 1e-12);  // in the plane of R and n
      // The angle from n, signed positive on R's side (written from the Rodrigues rotation about n x R).
      const Vec3 axis = normalize(cross(n, r));
      const double signed_angle = std::atan2(dot(cross(n, d), axis), dot(n, d));
      EXPECT_NEAR(signed_angle, angle, 1e-12) << "nv " << nv;
    }
    EXPECT_NEAR(length(Vec3(kernel::game_split_sum_lobe_direction(n, r, theta_r)) - r), 0.0, 1e-12);
  }
  // R along n (normal view): n whatever the angle.
  EXPECT_NEAR(length(Vec3(kernel::game_split_sum_lobe_direction(n, n, 0.7)) - n), 0.0, 1e-15);
  // The two-read split sum: f0 A L_A + f90 B L_B per channel.
  const Rgb s = kernel::game_split_sum_specular_lobes(Rgb{2.0, 4.0, 8.0}, Rgb{1.0, 3.0, 5.0}, Rgb{0.04, 0.5, 1.0},
                                                      Rgb{1.0, 1.0, 0.5}, 0.7, 0.2);
  EXPECT_NEAR(s.r, 2.0 * 0.04 * 0.7 + 1.0 * 1.0 * 0.2, 1e-15);
  EXPECT_NEAR(s.g, 4.0 * 0.5 * 0.7 + 3.0 * 1.0 * 0.2, 1e-15);
  EXPECT_NEAR(s.b, 8.0 * 1.0 * 0.7 + 5.0 * 0.5 * 0.2, 1e-15);
}

TEST(GameKernels, PointLightAndGameColour) {
  const Rgb e = kernel::point_light_irradiance(Rgb{4.0, 8.0, 2.0}, 4.0);  // I / d^2
  EXPECT_DOUBLE_EQ(e.r, 1.0);
  EXPECT_DOUBLE_EQ(e.g, 2.0);
  const Rgb c = kernel::game_colour_from_irradiance(Rgb{pi, 2.0 * pi, 0.0});  // E_perp = pi c
  EXPECT_NEAR(c.r, 1.0, 1e-15);
  EXPECT_NEAR(c.g, 2.0, 1e-15);
}

TEST(GameKernels, DisplayTransform) {
  // Published values: 0.18 linear (mid grey) encodes to 0.46135612950044165; 8-bit code 118.
  EXPECT_NEAR(kernel::linear_to_srgb(0.18), 0.46135612950044165, 1e-15);
  EXPECT_EQ(kernel::srgb8_code(0.18), 118.0);
  EXPECT_EQ(kernel::srgb8_code(0.5), 188.0);  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 rounds to 188
  EXPECT_EQ(kernel::srgb8_code(std::nan("")), 0.0);
  EXPECT_EQ(kernel::srgb8_code(2.0), 255.0);
  EXPECT_DOUBLE_EQ(kernel::exposure_scale(-2.0), 0.25);
  // Filmic: f(1) = 2.54 / 3.16 from the rational form, written out independently.
  EXPECT_NEAR(kernel::tone_filmic(1.0), (2.51 + 0.03) / (2.43 + 0.59 + 0.14), 1e-15);
  EXPECT_EQ(kernel::tone_filmic(-1.0), 0.0);
}

TEST(GameLobe, PhongSpecularAlbedoAtNormalViewIsTheZoosClosedForm) {
  // Modified Phong, f = ks (n + 2)/(2 pi) cos^n(alpha): at normal view the mirror direction is the normal
  // and the albedo is ks (n + 2)/(2 pi) int cos^(n+1) dw = ks (n + 2)/(2 pi) 2 pi/(n + 2) = ks.
  auto f = make_brdf("phong-modified", {{"kd", "0"}, {"ks", "0.5"}, {"n", "50"}});
  ASSERT_TRUE(f.has_value()) << f.error().message;
  const GameLobe lobe = game_lobe(**f);
  EXPECT_EQ(lobe.exponent, 50.0);
  EXPECT_FALSE(lobe.blinn_like);
  // The last bin is at cos theta_o = 1 - 1/64: the lobe of n = 50 is still all above the horizon there.
  const Rgb rho = lobe.specular_albedo.back();
  EXPECT_NEAR(rho.r, 0.5, 0.02);
}

// Each model answers for itself (brdf.h: game_phong_exponent, gloss_exponent_is_blinn_phong, game_wrap,
// split_sum_inputs); the expected values are the conversions written out here from the parameters: a Phong
// lobe keeps n, a Blinn-Phong (N.H)^n lobe is n/4, a Beckmann m (or Ward's alpha, GGX's alpha) is the
// Blinn-Phong n = 2/m^2 - 2, perceptual roughness r is alpha = r^2.
TEST(GameLobe, EachModelAnswersItsChainExponentGlossKindWrapAndSplitSum) {
  struct Case {
    const char* model;
    ParamAssignments params;
    double exponent;
    bool blinn_like;
    double wrap;
    bool split_sum;
  };
  auto blinn_of_m = [](double m) { return (2.0 / (m * m) - 2.0) / 4.0; };
  const std::vector<Case> cases = {
      {"lambert", {}, 0.0, false, 0.0, false},
      {"phong", {{"n", "40"}}, 40.0, false, 0.0, false},
      {"phong-modified", {{"n", "50"}}, 50.0, false, 0.0, false},
      {"blinn-phong", {{"n", "50"}}, 12.5, true, 0.0, false},
      {"blinn-phong-modified", {{"n", "300"}}, 75.0, true, 0.0, false},
      {"minimalist-cook-torrance", {{"n", "64"}}, 16.0, true, 0.0, false},
      {"cook-torrance", {{"m", "0.2"}}, blinn_of_m(0.2), true, 0.0, false},
      {"cook-torrance", {{"n", "100"}}, 25.0, true, 0.0, false},
      {"ward", {{"alpha", "0.2"}}, blinn_of_m(0.2), false, 0.0, false},
      {"ward-anisotropic", {{"alpha_x", "0.1"}, {"alpha_y", "0.3"}}, blinn_of_m(0.2), false, 0.0, false},
      {"lafortune", {{"lobes", "-1,-1,1,30"}}, 30.0, false, 0.0, false},
      {"wrapped-diffuse", {{"w", "0.4"}}, 0.0, false, 0.4, false},
      {"burley", {}, 0.0, false, 0.0, false},
      {"ggx", {{"roughness", "0.5"}}, blinn_of_m(0.25), false, 0.0, true},
      {"ggx", {{"alpha_x", "0.1"}, {"alpha_y", "0.4"}}, blinn_of_m(0.2), false, 0.0, true},
      {"filament", {{"perceptual_roughness", "0.5"}}, blinn_of_m(0.25), false, 0.0, true},
  };
  for (const Case& c : cases) {
    auto f = make_brdf(c.model, c.params);
    ASSERT_TRUE(f.has_value()) << c.model << ": " << f.error().message;
    EXPECT_NEAR((*f)->game_phong_exponent(), c.exponent, 1e-12 * (1.0 + c.exponent)) << c.model;
    EXPECT_EQ((*f)->gloss_exponent_is_blinn_phong(), c.blinn_like) << c.model;
    EXPECT_EQ((*f)->game_wrap(), c.wrap) << c.model;
    EXPECT_EQ((*f)->split_sum_inputs().has_value(), c.split_sum) << c.model;
  }
  // The split sum's inputs: roughness sqrt(alpha) (the geometric mean of an anisotropic pair), f0 and f90.
  const auto g = (*make_brdf("ggx", {{"alpha_x", "0.1"}, {"alpha_y", "0.4"}, {"f", "schlick"}, {"f0", "0.04"}, {"ks", "0.5"}, {"kd", "0.25"}}))
                     ->split_sum_inputs();
  ASSERT_TRUE(g.has_value());
  EXPECT_NEAR(g->roughness(), std::sqrt(0.2), 1e-15);
  EXPECT_NEAR(g->f0().g, 0.02, 1e-15);  // ks f0
  EXPECT_EQ(g->f90().g, 0.5);           // ks
  EXPECT_EQ(g->material.ms_albedo.g, 0.0);  // no Kulla-Conty lobe
  EXPECT_EQ(g->material.compensation.g, 0.0);
  EXPECT_EQ(g->material.diffuse.g, 0.25);  // kd
  const auto m = (*make_brdf("filament", {{"perceptual_roughness", "0.3"}, {"metallic", "1"}, {"base_color", "0.9,0.6,0.3"}}))
                     ->split_sum_inputs();
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->roughness(), 0.3, 1e-15);
  EXPECT_NEAR(m->f0().b, 0.3, 1e-15);  // a metal's f0 is its base colour
  EXPECT_EQ(m->f90().r, 1.0);
  EXPECT_NEAR(m->material.compensation.b, 0.3, 1e-15);  // energy compensation is on by default: c = f0
  EXPECT_EQ(m->material.diffuse.r, 0.0);  // a metal has no diffuse
}

// The registry's split-sum sweep (ibl-error's rows) is declared by exactly the models whose BRDFs answer
// split_sum_inputs(), and its roughness parameter is a parameter of the model that moves the answer.
TEST(GameLobe, TheSplitSumSweepIsDeclaredByTheModelsThatTakeTheSplitSum) {
  int declared = 0;
  for (const ModelInfo& info : brdf_models()) {
    auto f = make_brdf(info.name, testing::registry_params(info));  // measured: this binary's test file
    ASSERT_TRUE(f.has_value()) << info.name;
    EXPECT_EQ(info.split_sum_sweep.has_value(), (*f)->split_sum_inputs().has_value()) << info.name;
    if (!info.split_sum_sweep) continue;
    ++declared;
    const SplitSumSweep& s = *info.split_sum_sweep;
    auto rough = make_brdf(info.name, {{s.roughness_param, "0.7"}});
    ASSERT_TRUE(rough.has_value()) << info.name << " " << s.roughness_param;
    EXPECT_NEAR((*rough)->split_sum_inputs()->roughness(), 0.7, 1e-15) << info.name;
    auto alone = make_brdf(info.name, {{s.specular_only_param, s.specular_only_value}});
    ASSERT_TRUE(alone.has_value()) << info.name << " " << s.specular_only_param;
    EXPECT_EQ((*alone)->diffuse_albedo().max_component(), 0.0) << info.name << ": the specular lobe alone";
  }
  EXPECT_GE(declared, 2);
  EXPECT_EQ(split_sum_model_names(), "ggx, filament");
}

}  // namespace
}  // namespace shadelab
