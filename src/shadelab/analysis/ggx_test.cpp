// The GGX family's proofs beyond the all-models suite (issue 10 section 2): chi-square of every sampler over
// 48 (alpha, theta) configurations up to 89.9 degrees, the pdf's integral, the white furnace with Kulla-Conty
// compensation (and the loss without it), reciprocity with multiple scattering, the variance ordering of the
// samplers (by quadrature of the weight's second moment, and measured), and a stress test at alpha = 1e-4.
// Costs (2 cores, Release): docs/testing.md, "GGX family".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "shadelab/analysis/albedo.h"
#include "shadelab/analysis/chi_square.h"
#include "shadelab/analysis/test_brdfs.h"
#include "shadelab/brdf/ggx.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

using testing::make;
using testing::view;

constexpr const char* samplers[] = {"ndf", "vndf", "vndf-caps", "vndf-bounded"};
constexpr double alphas[] = {0.002, 0.01, 0.04, 0.1, 0.25, 0.5, 0.75, 1.0};
constexpr double thetas[] = {0.0, 30.0, 60.0, 80.0, 89.0, 89.9};
constexpr int configurations = static_cast<int>(std::size(alphas) * std::size(thetas));  // 48 per sampler

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

BrdfPtr specular(const std::string& sampler, double alpha, const ParamAssignments& extra = {}) {
  ParamAssignments p = {{"kd", "0"}, {"f", "none"}, {"alpha", num(alpha)}, {"sampling", sampler}};
  p.insert(p.end(), extra.begin(), extra.end());
  return make("ggx", p);
}

// Every sampler, 48 configurations each: chi-square at a family-wise 0.01 (Sidak over all 4 x 48 + 8 tests).
TEST(GgxSamplers, ChiSquareOverFortyEightConfigurations) {
  const int tests = 4 * configurations + 8;
  const double level = sidak_significance(0.01, tests);
  ChiSquareOptions o;
  o.samples = 100'000;
  o.cos_theta_bins = 10;
  o.phi_bins = 20;
  int run = 0;
  for (const char* s : samplers) {
    for (double alpha : alphas) {
      const BrdfPtr f = specular(s, alpha);
      for (double t : thetas) {
        const ChiSquareResult r = chi_square_test(*f, view(t), o);
        ++run;
        EXPECT_GE(r.p_value, level) << s << " alpha " << alpha << " theta " << t << ": statistic " << r.statistic
                                    << ", dof " << r.degrees_of_freedom << ", unexpected " << r.unexpected_samples;
      }
    }
    // Anisotropic, two configurations per sampler.
    for (double t : {45.0, 85.0}) {
      const BrdfPtr f = make("ggx", {{"kd", "0"}, {"f", "none"}, {"alpha_x", "0.6"}, {"alpha_y", "0.05"}, {"sampling", s}});
      const ChiSquareResult r = chi_square_test(*f, view(t), o);
      ++run;
      EXPECT_GE(r.p_value, level) << s << " anisotropic theta " << t << ": statistic " << r.statistic;
    }
  }
  EXPECT_EQ(run, tests);
}

// The pdf integrates to 1: the upper hemisphere by quadrature plus the sampler's share below the horizon
// (chi_square.h: these densities jump below the horizon), within 4 standard errors (about 5e-4).
TEST(GgxSamplers, PdfIntegratesToOne) {
  for (const char* s : samplers) {
    for (double alpha : {0.01, 0.25, 1.0}) {
      const BrdfPtr f = specular(s, alpha);
      for (double t : {0.0, 60.0, 89.0}) {
        const QuadratureResult q = pdf_integral(*f, view(t));
        EXPECT_NEAR(q.value, 1.0, std::max(1e-6, 4.0 * q.error)) << s << " alpha " << alpha << " theta " << t;
      }
    }
  }
}

// The mean weight equals the albedo by quadrature for every sampler (an expected value computed without sample()).
TEST(GgxSamplers, MeanWeightIsTheAlbedo) {
  for (const char* s : samplers) {
    for (double alpha : {0.05, 0.6}) {
      const BrdfPtr f = make("ggx", {{"kd", "0.3"}, {"alpha", num(alpha)}, {"sampling", s}, {"ms", "kulla-conty"}});
      for (double t : {10.0, 75.0}) {
        const WeightMean m = weight_mean(*f, view(t), 200'000);
        EXPECT_LE(m.max_z, 5.0) << s << " alpha " << alpha << " theta " << t << ": " << m.mean.r << " vs " << m.albedo.r;
      }
    }
  }
}

double albedo_f1(const Brdf& f, double theta_deg) {
  AlbedoOptions o;
  o.quadrature.rel_tol = 1e-6;  // ample for the furnace bound of 1e-3
  return directional_albedo(f, deg_to_rad(theta_deg), o).albedo.r;
}

// White furnace (F = 1, kd = 0): with ms = kulla-conty the directional albedo is within 1e-3 of 1 for alpha in
// [0.01, 1] and theta in [0, 89] degrees, both Smith forms; without it the loss is reported and is > 0.
TEST(GgxFurnace, KullaContyRestoresTheLostEnergy) {
  double worst = 0.0;
  std::string where;
  for (const char* g : {"smith-correlated", "smith-separable"}) {
    std::printf("[ furnace  ] %s: 1 - albedo without ms (rows alpha, columns theta 0 30 60 80 89)\n", g);
    for (double alpha : {0.01, 0.03, 0.1, 0.25, 0.5, 0.75, 1.0}) {
      const BrdfPtr ms = make("ggx", {{"kd", "0"}, {"f", "none"}, {"alpha", num(alpha)}, {"g", g}, {"ms", "kulla-conty"}});
      const BrdfPtr ss = make("ggx", {{"kd", "0"}, {"f", "none"}, {"alpha", num(alpha)}, {"g", g}});
      std::string row;
      for (double t : {0.0, 30.0, 60.0, 80.0, 89.0}) row += " " + num(1.0 - albedo_f1(*ss, t));
      std::printf("[ furnace  ]   alpha %-5s%s\n", num(alpha).c_str(), row.c_str());
      for (double t : {0.0, 15.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0, 88.0, 89.0}) {
        const double e = std::abs(1.0 - albedo_f1(*ms, t));
        if (e > worst) {
          worst = e;
          where = std::string(g) + " alpha " + num(alpha) + " theta " + num(t);
        }
      }
    }
  }
  std::printf("[ furnace  ] with kulla-conty: max |1 - albedo| = %.3g (%s)\n", worst, where.c_str());
  EXPECT_LE(worst, 1e-3) << where;
  // Without compensation the rough lobe loses energy (E(1, alpha = 1) is about 0.31).
  const BrdfPtr rough = make("ggx", {{"kd", "0"}, {"f", "none"}, {"alpha", "1"}});
  EXPECT_GT(1.0 - albedo_f1(*rough, 0.0), 0.5);
  const BrdfPtr smooth = make("ggx", {{"kd", "0"}, {"f", "none"}, {"alpha", "0.01"}});
  EXPECT_LT(1.0 - albedo_f1(*smooth, 0.0), 1e-3);
}

// Kulla-Conty's lobe is symmetric, so the model stays reciprocal (to 1e-9, the bound; it is exact).
TEST(GgxFurnace, ReciprocalWithMultipleScattering) {
  for (const ParamAssignments& p :
       {ParamAssignments{{"alpha", "0.3"}, {"ms", "kulla-conty"}},
        ParamAssignments{{"alpha", "0.9"}, {"ms", "kulla-conty"}, {"g", "smith-separable"}, {"f", "conductor"}, {"ior", "0.2,0.9,1.1"}, {"k", "3.9,2.4,2.2"}},
        ParamAssignments{{"alpha_x", "0.05"}, {"alpha_y", "0.7"}, {"ms", "kulla-conty"}, {"f", "dielectric"}}}) {
    const BrdfPtr f = make("ggx", p);
    EXPECT_TRUE(f->is_reciprocal());
    EXPECT_LE(reciprocity_error(*f).max_relative_error, 1e-9);
  }
}

// The variance of the weight w = f cos / pdf at fixed wo, by quadrature: Var = integral (f cos)^2 / pdf - E^2
// over the upper hemisphere (weight 0 below). For the specular lobe alone (kd = 0, ms none) and each sampler.
double weight_variance_by_quadrature(const Ggx& f, const Vec3& wo) {
  QuadratureOptions o;
  o.rel_tol = 1e-9;
  o.initial_intervals = 4;
  const Vec3 mirror{-wo.x, -wo.y, wo.z};
  const VectorQuadratureResult r = integrate_directions(
      [&](const Vec3& wi, std::span<double> out) {
        const double fc = f.eval(wi, wo).r * wi.z;
        const double p = f.sampler_pdf(wi, wo);
        out[0] = fc;
        out[1] = p > 0.0 ? fc * fc / p : 0.0;
      },
      2, mirror.z > 1e-3 ? mirror : Vec3{mirror.x, mirror.y, 1e-3}, SphereRegion::upper, o);
  return r.value[1] - r.value[0] * r.value[0];
}

TEST(GgxVariance, BoundedVndfNeverWorseThanCapsNeverWorseThanNdf) {
  std::printf("[ variance ] alpha theta: ndf vndf vndf-caps vndf-bounded (by quadrature)\n");
  for (double alpha : {0.05, 0.2, 0.5, 1.0}) {
    for (double t : {0.0, 30.0, 60.0, 80.0, 89.0}) {
      double v[4];
      for (int k = 0; k < 4; ++k) {
        const BrdfPtr f = specular(samplers[k], alpha);
        v[k] = weight_variance_by_quadrature(dynamic_cast<const Ggx&>(*f), view(t));
      }
      std::printf("[ variance ] %-5s %-4s: %.6g %.6g %.6g %.6g\n", num(alpha).c_str(), num(t).c_str(), v[0], v[1], v[2], v[3]);
      const double tol = 1e-7 + 1e-6 * v[0];  // the quadrature's accuracy
      EXPECT_NEAR(v[1], v[2], tol) << "vndf and vndf-caps share a density, alpha " << alpha << " theta " << t;
      EXPECT_LE(v[3], v[2] + tol) << "bounded vs caps, alpha " << alpha << " theta " << t;
      EXPECT_LE(v[2], v[0] + tol) << "caps vs ndf, alpha " << alpha << " theta " << t;
    }
  }
}

// The measured variance of the sampled weights agrees with the quadrature (the samplers draw what pdf says).
TEST(GgxVariance, MeasuredVarianceAgreesWithQuadrature) {
  for (int k = 0; k < 4; ++k) {
    const BrdfPtr f = specular(samplers[k], 0.4);
    const Vec3 wo = view(70.0);
    const double expected = weight_variance_by_quadrature(dynamic_cast<const Ggx&>(*f), wo);
    Pcg32 rng(11, static_cast<std::uint64_t>(k));
    const int n = 400'000;
    double s1 = 0.0;
    double s2 = 0.0;
    double s4 = 0.0;
    for (int i = 0; i < n; ++i) {
      const double w = f->sample(wo, {rng.next_double(), rng.next_double()}, rng.next_double()).weight.r;
      s1 += w;
      s2 += w * w;
      s4 += w * w * w * w;
    }
    const double mean = s1 / n;
    const double var = s2 / n - mean * mean;
    // Standard error of the variance estimate ~ sqrt((E[w^4] - var^2) / n).
    const double se = std::sqrt(std::max(0.0, s4 / n - var * var) / n);
    EXPECT_NEAR(var, expected, 5.0 * se + 1e-9) << samplers[k];
  }
}

// No NaN/Inf/negative values down to alpha = 1e-4 with grazing directions (|z| < 1e-4) for every sampler, and
// for the family's other GGX users at the same alpha: filament (alpha = perceptual_roughness^2 = 1e-4, its
// bounded VNDF sampler) and cook-torrance d=ggx (its own NDF sampler and pdf).
TEST(GgxStress, FiniteAtTinyAlphaAndGrazingAngles) {
  std::vector<std::pair<std::string, ParamAssignments>> models;
  for (const char* s : samplers) {
    for (const char* ms : {"none", "kulla-conty"}) {
      if (std::string(ms) == "kulla-conty" && std::string(s) != "vndf-bounded") continue;
      models.push_back({"ggx", {{"kd", "0.1"}, {"alpha", "1e-4"}, {"sampling", s}, {"ms", ms}}});
    }
  }
  models.push_back({"filament", {{"perceptual_roughness", "0.01"}}});
  models.push_back({"filament", {{"perceptual_roughness", "0.01"}, {"metallic", "1"}, {"diffuse", "burley"}}});
  models.push_back({"cook-torrance", {{"kd", "0.1"}, {"d", "ggx"}, {"m", "1e-4"}}});
  for (const auto& [model, params] : models) {
    const BrdfPtr f = make(model, params);
    Pcg32 rng(0x5eed, 3);
    int bad = 0;
    for (int i = 0; i < 1'000'000; ++i) {
      const double phi_o = two_pi * rng.next_double();
      const double phi_i = two_pi * rng.next_double();
      const double zo = i % 2 == 0 ? 1e-4 * rng.next_double() : rng.next_double();
      const double zi = i % 3 == 0 ? 1e-4 * rng.next_double() : 2.0 * rng.next_double() - 1.0;
      const Vec3 wo = spherical_direction(std::sqrt(1.0 - zo * zo), zo, phi_o);
      const Vec3 wi = spherical_direction(std::sqrt(1.0 - zi * zi), zi, phi_i);
      const Rgb v = f->eval(wi, wo);
      const double p = f->pdf(wi, wo);
      const BrdfSample smp = f->sample(wo, {rng.next_double(), rng.next_double()}, rng.next_double());
      if (!is_finite(v) || v.r < 0.0 || !std::isfinite(p) || p < 0.0 || !is_finite(smp.weight) || smp.weight.r < 0.0 ||
          !std::isfinite(smp.pdf)) {
        ++bad;
      }
    }
    std::string text = model;
    for (const auto& [k, v] : params) text += " " + k + "=" + v;
    EXPECT_EQ(bad, 0) << text;
  }
}

}  // namespace
}  // namespace shadelab
