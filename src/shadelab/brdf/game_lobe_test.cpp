// brdf/game_lobe.h and the game-shading kernels it feeds (kernels/game_ambient.sl, the point-light and
// game-colour helpers of game_shading.sl, kernels/display.sl), each against an independent computation:
// the prefiltered level inverts envmap/prefilter.h's gloss mapping; the albedo lookup is exact at bin
// centres and linear between them; the mirror direction keeps the angle to the normal; the specular albedo
// table of a Phong lobe matches the closed-form albedo of the zoo at normal view; the display transform's
// sRGB codes match the published IEC 61966-2-1 values.
#include "shadelab/brdf/game_lobe.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/envmap/prefilter.h"
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
      const Vec3 d = kernel::game_split_sum_direction(n, r, alpha);
      EXPECT_NEAR(length(d), 1.0, 1e-12);
      EXPECT_NEAR(dot(cross(r, n), d), 0.0, 1e-12);  // in the plane of R and n
      const double t = alpha * alpha;
      const double want = std::atan2((1.0 - t) * std::sin(theta_r), t + (1.0 - t) * std::cos(theta_r));
      EXPECT_NEAR(std::acos(std::clamp(dot(d, n), -1.0, 1.0)), want, 1e-7) << "nv " << nv << " alpha " << alpha;
      EXPECT_LE(std::acos(std::clamp(dot(d, n), -1.0, 1.0)), last);  // toward n as alpha grows
      last = std::acos(std::clamp(dot(d, n), -1.0, 1.0)) + 1e-12;
    }
    const Vec3 mirror = kernel::game_split_sum_direction(n, r, 0.0);
    const Vec3 normal = kernel::game_split_sum_direction(n, r, 1.0);
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
  const ModelInfo* model = find_brdf_model("phong-modified");
  ASSERT_NE(model, nullptr);
  auto values = parse_params(model->name, model->params, {{"kd", "0"}, {"ks", "0.5"}, {"n", "50"}});
  ASSERT_TRUE(values.has_value()) << values.error().message;
  auto f = model->create(*values);
  ASSERT_TRUE(f.has_value());
  const GameLobe lobe = game_lobe(model->name, *values, **f);
  EXPECT_EQ(lobe.exponent, 50.0);
  EXPECT_FALSE(lobe.blinn_like);
  // The last bin is at cos theta_o = 1 - 1/64: the lobe of n = 50 is still all above the horizon there.
  const Rgb rho = lobe.specular_albedo.back();
  EXPECT_NEAR(rho.r, 0.5, 0.02);
  EXPECT_EQ(game_phong_exponent("blinn-phong", *values), 12.5);  // Blinn-Phong n / 4
  EXPECT_EQ(game_phong_exponent("lambert", *values), 0.0);
}

}  // namespace
}  // namespace shadelab
