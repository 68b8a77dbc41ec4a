#include "shadelab/analysis/albedo.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/analysis/test_brdfs.h"
#include "shadelab/brdf/blinn_phong.h"
#include "shadelab/brdf/phong.h"

namespace shadelab {
namespace {

using testing::Broken;
using testing::make;
using testing::view;

double max_rel(const Rgb& a, const Rgb& b) {
  double e = 0.0;
  for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(a[c] - b[c]) / std::max(std::abs(b[c]), 1e-300));
  return e;
}

TEST(Albedo, LambertIsKdAtEveryAngle) {
  const auto f = make("lambert", {{"kd", "0.8,0.5,0.2"}});
  for (double t : {0.0, 30.0, 60.0, 85.0, 89.0, 89.99}) {
    const AlbedoResult a = directional_albedo(*f, deg_to_rad(t));
    EXPECT_TRUE(a.converged) << t;
    EXPECT_LE(max_rel(a.albedo, {0.8, 0.5, 0.2}), 1e-12) << "theta " << t;
    EXPECT_LE(a.error.max_component(), 1e-9) << t;
  }
}

// Every model with normalization = exact, kd = 0, ks = 1: the albedo at normal incidence is 1.
TEST(Albedo, ExactNormalizationGivesOneAtNormalIncidence) {
  for (const char* model : {"phong", "phong-modified", "blinn-phong", "blinn-phong-modified"}) {
    for (const char* n : {"0", "0.5", "2", "10", "100", "1000", "10000"}) {
      const auto f = make(model, {{"kd", "0"}, {"ks", "1"}, {"n", n}, {"normalization", "exact"}});
      const AlbedoResult a = directional_albedo(*f, 0.0);
      EXPECT_TRUE(a.converged) << model << " n=" << n;
      EXPECT_LE(max_rel(a.albedo, Rgb::gray(1.0)), 1e-9) << model << " n=" << n << " albedo " << a.albedo.r;
    }
  }
}

// The unnormalized forms (and the zoo's bounds) do not give 1; their albedo is the inverse of the zoo's
// closed form, or the bound divided by it.
TEST(Albedo, UnnormalizedFormsDoNotGiveOne) {
  for (double n : {0.5, 10.0, 1000.0}) {
    const std::string ns = std::to_string(n);
    for (bool modified : {false, true}) {
      const auto phong = make(modified ? "phong-modified" : "phong",
                              {{"kd", "0"}, {"ks", "1"}, {"n", ns}, {"normalization", "none"}});
      const double a = directional_albedo(*phong, 0.0).albedo.r;
      const double expected = 1.0 / Phong::normalization_factor(n, Phong::Normalization::exact, modified);
      EXPECT_NEAR(a, expected, 1e-9 * expected) << "phong modified=" << modified << " n=" << n;
      EXPECT_GT(std::abs(a - 1.0), 1e-3);

      const std::string bp = modified ? "blinn-phong-modified" : "blinn-phong";
      const double exact = BlinnPhong::normalization_factor(n, BlinnPhong::Normalization::exact, modified);
      for (auto [word, kind] : {std::pair{"none", BlinnPhong::Normalization::none},
                                std::pair{"lower", BlinnPhong::Normalization::lower},
                                std::pair{"upper", BlinnPhong::Normalization::upper}}) {
        const auto f = make(bp, {{"kd", "0"}, {"ks", "1"}, {"n", ns}, {"normalization", word}});
        const double value = directional_albedo(*f, 0.0).albedo.r;
        const double want = BlinnPhong::normalization_factor(n, kind, modified) / exact;
        EXPECT_NEAR(value, want, 1e-9 * want) << bp << " " << word << " n=" << n;
        // (The lower bounds approach the exact value as n grows: blinn-phong's equals it at n = 1000.)
        if (kind != BlinnPhong::Normalization::lower) {
          EXPECT_GT(std::abs(value - 1.0), 1e-3) << bp << " " << word << " n=" << n;
        }
      }
    }
  }
}

// Off normal incidence, against closed forms: a sharp normalized Phong lobe that lies wholly above the
// horizon reflects ks (the original form); blinn-phong-modified with n = 0 is Lambertian, ks/pi; wrapped
// diffuse reflects kd (1 + 2w) / (1 + w)^2 at every angle.
TEST(Albedo, ClosedFormsOffNormalIncidence) {
  const auto phong = make("phong", {{"kd", "0"}, {"ks", "1"}, {"n", "10000"}});
  const auto lambertian = make("blinn-phong-modified", {{"kd", "0"}, {"ks", "0.7"}, {"n", "0"}});
  const auto wrapped = make("wrapped-diffuse", {{"kd", "0.9"}, {"w", "0.5"}});
  for (double t : {15.0, 30.0, 60.0, 80.0}) {
    EXPECT_NEAR(directional_albedo(*phong, deg_to_rad(t)).albedo.r, 1.0, 1e-9) << t;
    EXPECT_NEAR(directional_albedo(*lambertian, deg_to_rad(t)).albedo.r, 0.7, 1e-9) << t;
    EXPECT_NEAR(directional_albedo(*wrapped, deg_to_rad(t)).albedo.r, 0.9 * 2.0 / 2.25, 1e-9) << t;
  }
}

// The modified Phong lobe's albedo off the normal is cos(theta_o) while the lobe lies above the horizon:
// the integral of (R.L)^n L.z over the whole sphere is R.z 2 pi / (n + 2) exactly (L.z = (R.L) R.z plus a
// part perpendicular to R that integrates to 0), and (n + 2)/(2 pi) normalizes it.
TEST(Albedo, ModifiedPhongOffNormalMatchesTheSphereIntegral) {
  const auto f = make("phong-modified", {{"kd", "0"}, {"ks", "1"}, {"n", "10000"}});
  for (double t : {30.0, 60.0}) {
    // Lobe entirely above the horizon: the integral over the hemisphere equals the one over the sphere.
    EXPECT_NEAR(directional_albedo(*f, deg_to_rad(t)).albedo.r, std::cos(deg_to_rad(t)), 1e-9) << t;
  }
}

TEST(Albedo, ExplicitAxisGivesTheSameValue) {
  const auto f = make("blinn-phong", {{"kd", "0.3"}, {"ks", "0.6"}, {"n", "40"}});
  AlbedoOptions about_normal;
  about_normal.axis = Vec3{0.0, 0.0, 1.0};
  const double automatic = directional_albedo(*f, deg_to_rad(40.0)).albedo.g;
  const double normal = directional_albedo(*f, deg_to_rad(40.0), about_normal).albedo.g;
  EXPECT_NEAR(automatic, normal, 1e-9);
}

TEST(Albedo, LobePeakFindsTheMirrorAndOffSpecularLobes) {
  const auto phong = make("phong", {{"kd", "0.5"}, {"ks", "0.5"}, {"n", "1000"}});
  const Vec3 wo = view(35.0);
  const Vec3 peak = lobe_peak(*phong, wo, LobeQuantity::reflected);
  EXPECT_GT(dot(peak, Vec3{-wo.x, -wo.y, wo.z}), std::cos(1e-4));
  // A retro-reflective Lafortune lobe peaks towards the viewer, not at the mirror direction.
  const auto retro = make("lafortune", {{"kd", "0"}, {"ks", "1"}, {"lobes", "1,1,1,500"}});
  const Vec3 retro_peak = lobe_peak(*retro, wo, LobeQuantity::reflected);
  EXPECT_GT(dot(retro_peak, wo), std::cos(0.05));
  EXPECT_NEAR(directional_albedo(*retro, wo).albedo.r,
              directional_albedo(*retro, wo, AlbedoOptions{albedo_quadrature(), wo}).albedo.r, 1e-9);
}

TEST(Albedo, MaxOverTheta) {
  const auto lambert = make("lambert", {{"kd", "0.6"}});
  const AlbedoMax l = max_albedo(*lambert);
  EXPECT_NEAR(l.value, 0.6, 1e-8);
  EXPECT_TRUE(l.converged);
  // The minimalist model's 1/(L.H)^3 makes its albedo grow without bound towards grazing.
  const auto minimalist = make("minimalist-cook-torrance", {{"kd", "0"}, {"ks", "1"}, {"n", "100"}});
  const AlbedoMax m = max_albedo(*minimalist);
  EXPECT_GT(m.value, 1.5);
  EXPECT_NEAR(m.theta_deg, 89.0, 1e-3);
  // An interior maximum between scan points (0, 3, ..., 87, 89 degrees), found by the refinement.
  const testing::ViewDependentLambert hill(0.9, 50.5, 0.4);
  const AlbedoMax c = max_albedo(hill);
  EXPECT_NEAR(c.theta_deg, 50.5, 2e-3);
  EXPECT_NEAR(c.theta_rad, deg_to_rad(c.theta_deg), 1e-15);
  EXPECT_NEAR(c.value, 0.9, 1e-8);
  EXPECT_NEAR(c.value, hill.albedo(c.theta_rad), 1e-8);
}

TEST(Albedo, Reciprocity) {
  EXPECT_EQ(reciprocity_error(*make("lambert")).max_relative_error, 0.0);
  const ReciprocityResult modified = reciprocity_error(*make("phong-modified", {{"n", "1000"}}));
  EXPECT_LE(modified.max_relative_error, 1e-12);
  EXPECT_GT(modified.pairs, 3000);
  // The original Phong divides by N.L: f(a, b) != f(b, a).
  EXPECT_GT(reciprocity_error(*make("phong")).max_relative_error, 0.1);
  EXPECT_GT(reciprocity_error(*make("wrapped-diffuse", {{"w", "0.5"}})).max_relative_error, 0.1);
  const auto asymmetric = testing::broken("lambert", {}, Broken::Fault::non_reciprocal);
  const ReciprocityResult r = reciprocity_error(*asymmetric);
  EXPECT_GT(r.max_relative_error, 0.1);
  EXPECT_NE(r.f_ab.r, r.f_ba.r);
}

}  // namespace
}  // namespace shadelab
