#include "shadelab/brdf/rough_dielectric.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <vector>

#include "shadelab/brdf/test_util.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/numeric/quadrature.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

using Transport = RoughDielectric::Transport;
using Lobes = RoughDielectric::Lobes;

Vec3 below(double theta_deg, double phi_deg) {
  Vec3 w = testing::dir(theta_deg, phi_deg);
  w.z = -w.z;
  return w;
}

// The quadrature of the density and albedo integrals below: 1e-7 relative, room for the narrow lobes.
QuadratureOptions fine_quadrature() {
  QuadratureOptions o;
  o.rel_tol = 1e-7;
  o.max_subdivisions = 20000;
  return o;
}

// Its reflection is the registry's ggx with the exact dielectric Fresnel, no diffuse, height-correlated G2:
// the kernel ggx.sl, an independent text.
TEST(RoughDielectric, ReflectionIsTheGgxModelWithTheDielectricFresnel) {
  for (double alpha : {0.05, 0.3, 0.8}) {
    for (double eta : {1.33, 1.5, 2.4}) {
      const RoughDielectric coat(eta, alpha);
      const BrdfPtr ggx = testing::make("ggx", {{"kd", "0"}, {"alpha", std::to_string(alpha)}, {"f", "dielectric"},
                                                {"ior", std::to_string(eta)}});
      for (const auto& [ti, pi_, to, po] : {std::array{10.0, 0.0, 30.0, 180.0}, std::array{60.0, 40.0, 70.0, 250.0},
                                            std::array{85.0, 0.0, 5.0, 90.0}, std::array{45.0, 0.0, 45.0, 180.0}}) {
        const Vec3 wi = testing::dir(ti, pi_);
        const Vec3 wo = testing::dir(to, po);
        const double expected = ggx->eval(wi, wo).g;
        EXPECT_NEAR(coat.eval(wo, wi, Transport::radiance), expected, 1e-12 * expected) << alpha << " " << eta;
        EXPECT_NEAR(coat.eval(wi, wo, Transport::importance), expected, 1e-12 * expected);
      }
    }
  }
}

// Generalized reciprocity of the transmission (Veach 1997, eq. 5.14): f(a, b) / eta_b^2 = f(b, a) / eta_a^2 in
// the radiance form, a above (index 1), b below (index eta); and the importance form is the radiance form of
// the reversed pair.
TEST(RoughDielectric, TransmissionObeysGeneralizedReciprocity) {
  for (double eta : {1.2, 1.5, 2.0}) {
    const RoughDielectric coat(eta, 0.4);
    for (const auto& [ta, pa, tb, pb] : {std::array{20.0, 0.0, 30.0, 170.0}, std::array{70.0, 10.0, 50.0, 190.0},
                                         std::array{5.0, 0.0, 10.0, 90.0}}) {
      const Vec3 a = testing::dir(ta, pa);
      const Vec3 b = below(tb, pb);
      const double ab = coat.eval(a, b, Transport::radiance);
      const double ba = coat.eval(b, a, Transport::radiance);
      ASSERT_GT(ab, 0.0) << eta << " " << ta << " " << tb;
      EXPECT_NEAR(ab * eta * eta, ba, 1e-12 * ba);
      EXPECT_NEAR(coat.eval(a, b, Transport::importance), ba, 1e-12 * ba);
    }
  }
}

// The density integrates to the share of samples the sampler returns (a visible normal can reflect wo below the
// surface, or refract it back above: single scattering's loss, about 2% at alpha 0.5 from outside and 20%
// from inside), from above and from below, where total internal reflection turns transmission into reflection.
TEST(RoughDielectric, PdfIntegratesToTheShareOfSamplesReturned) {
  const QuadratureOptions o = fine_quadrature();
  for (double alpha : {0.1, 0.5}) {
    for (double eta : {1.5, 1.0 / 1.5}) {
      const RoughDielectric coat(eta, alpha);
      for (double theta : {0.0, 40.0, 80.0}) {
        const Vec3 wo = testing::dir(theta, 30.0);
        const Vec3 mirror{-wo.x, -wo.y, wo.z};
        auto r = integrate_sphere([&](const Vec3& w, std::span<double> out) { out[0] = coat.pdf(wo, w, Lobes::both); },
                                  1, mirror, Vec3{-wo.x, -wo.y, -wo.z}, o);
        Pcg32 rng(1, static_cast<std::uint64_t>(theta));
        const int n = 200000;
        int returned = 0;
        for (int i = 0; i < n; ++i) {
          const double ul = rng.next_double();
          if (coat.sample(wo, ul, Vec2{rng.next_double(), rng.next_double()}, Transport::radiance, Lobes::both)) ++returned;
        }
        const double share = static_cast<double>(returned) / n;
        EXPECT_NEAR(r.value[0], share, 4.0 * std::sqrt(share * (1.0 - share) / n) + 1e-5)
            << "alpha " << alpha << " eta " << eta << " theta " << theta;
        EXPECT_LE(r.value[0], 1.0 + 1e-6);
        if (alpha == 0.1 && eta > 1.0 && theta < 45.0) {
          EXPECT_GT(r.value[0], 0.998);
        }
      }
    }
  }
}

// The sampler draws what pdf says: the share of reflections among samples matches the integral of the
// density over the upper hemisphere, and the mean sample weight (f |cos| / pdf) matches the quadrature of
// f |cos| (the interface's albedo), for both transports.
TEST(RoughDielectric, SamplesMatchTheirDensityAndTheirWeights) {
  const QuadratureOptions o = fine_quadrature();
  for (double theta : {20.0, 70.0}) {
    for (double eta : {1.5, 1.0 / 1.5}) {
      const RoughDielectric coat(eta, 0.35);
      const Vec3 wo = testing::dir(theta, 0.0);
      const Vec3 mirror{-wo.x, -wo.y, wo.z};
      auto upper = integrate_directions([&](const Vec3& w, std::span<double> out) { out[0] = coat.pdf(wo, w, Lobes::both); },
                                        1, mirror, SphereRegion::upper, o);
      Pcg32 rng(7, static_cast<std::uint64_t>(theta));
      const int n = 200000;
      int reflected = 0;
      double sum = 0.0;
      double sum2 = 0.0;
      for (int i = 0; i < n; ++i) {
        const double ul = rng.next_double();
        const Vec2 u{rng.next_double(), rng.next_double()};
        const auto s = coat.sample(wo, ul, u, Transport::importance, Lobes::both);
        if (!s) continue;
        if (s->wi.z > 0.0) ++reflected;
        sum += s->weight;
        sum2 += s->weight * s->weight;
      }
      const double share = static_cast<double>(reflected) / n;
      EXPECT_NEAR(share, upper.value[0], 4.0 * std::sqrt(upper.value[0] * (1.0 - upper.value[0]) / n)) << theta << " " << eta;
      auto albedo = integrate_sphere(
          [&](const Vec3& w, std::span<double> out) { out[0] = coat.eval(wo, w, Transport::importance) * std::abs(w.z); }, 1,
          mirror, Vec3{-wo.x, -wo.y, -wo.z}, o);
      const double mean = sum / n;
      const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
      EXPECT_NEAR(mean, albedo.value[0], 4.0 * se + 1e-6) << theta << " " << eta;
      EXPECT_LE(albedo.value[0], 1.0 + 1e-6);  // single scattering: energy is lost, never made
    }
  }
}

// Near the smooth limit the interface is Fresnel's: the transmitted direction is Snell's, the reflected share
// is F(theta) and the radiance transmitted in is (1 - F) / eta^2 per sample (the radiance form's weight).
TEST(RoughDielectric, NearlySmoothIsFresnelAndSnell) {
  const double eta = 1.5;
  const RoughDielectric coat(eta, 0.0);  // floored at min_alpha
  EXPECT_EQ(coat.alpha(), RoughDielectric::min_alpha);
  for (double theta : {0.0, 30.0, 60.0, 80.0}) {
    const Vec3 wo = testing::dir(theta, 0.0);
    const double f = kernel::F_dielectric(wo.z, eta);
    const double sin_t = std::sin(theta * pi / 180.0) / eta;
    Pcg32 rng(3);
    double weight = 0.0;
    const int n = 1000;
    for (int i = 0; i < n; ++i) {
      const auto s = coat.sample(wo, 0.5, Vec2{rng.next_double(), rng.next_double()}, Transport::radiance, Lobes::transmission);
      ASSERT_TRUE(s.has_value());
      EXPECT_NEAR(std::hypot(s->wi.x, s->wi.y), sin_t, 3e-3);
      EXPECT_LT(s->wi.x, 1e-3);  // refracted to the far side of the normal
      weight += s->weight;
    }
    EXPECT_NEAR(weight / n, (1.0 - f) / (eta * eta), 2e-3) << theta;
    int reflected = 0;
    for (int i = 0; i < 20000; ++i) {
      const auto s = coat.sample(wo, rng.next_double(), Vec2{rng.next_double(), rng.next_double()}, Transport::radiance,
                                 Lobes::both);
      if (s && s->wi.z > 0.0) ++reflected;
    }
    EXPECT_NEAR(reflected / 20000.0, f, 4.0 * std::sqrt(f * (1.0 - f) / 20000.0) + 1e-3) << theta;
  }
}

// From inside beyond the critical angle everything is reflected: a transmission-only sample fails.
TEST(RoughDielectric, TotalInternalReflectionFailsTransmission) {
  const RoughDielectric coat(1.5, 0.0);
  const Vec3 wo = below(60.0, 0.0);  // beyond asin(1/1.5) = 41.8 degrees
  Pcg32 rng(5);
  for (int i = 0; i < 100; ++i) {
    const Vec2 u{rng.next_double(), rng.next_double()};
    EXPECT_FALSE(coat.sample(wo, 0.5, u, Transport::radiance, Lobes::transmission).has_value());
    const auto r = coat.sample(wo, 0.99, u, Transport::radiance, Lobes::both);
    ASSERT_TRUE(r.has_value());
    EXPECT_LT(r->wi.z, 0.0);
  }
}

// ---- Multiple scattering (Heitz et al. 2016): the walk on the microsurface ----

using Scattering = RoughDielectric::Scattering;

struct Integral {
  double value = 0.0;
  double standard_error = 0.0;
  double max_events = 0.0;
};

// integral over the sphere of eval_walk(wo, w, importance) |w.z|: the interface's reflected + transmitted power.
// Directions from a mixture of the single-scattering sampler and the uniform sphere (density q), one walk per
// direction; the mean of f |w.z| / q with its standard error.
Integral walked_power(const RoughDielectric& coat, const Vec3& wo, int n, std::uint64_t seed) {
  const RoughDielectric single(coat.eta(), coat.alpha());
  Pcg32 rng(seed, 3);
  double sum = 0.0;
  double sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    Vec3 w;
    const double pick = rng.next_double();
    const double ul = rng.next_double();
    const Vec2 u{rng.next_double(), rng.next_double()};
    if (pick < 0.5) {
      // The single-scattering sampler's density integrates to the share it returns: a failed draw adds 0.
      const auto s = single.sample(wo, ul, u, Transport::importance, Lobes::both);
      if (!s) continue;
      w = s->wi;
    } else {
      const double z = 1.0 - 2.0 * u.x;
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      w = Vec3{r * std::cos(two_pi * u.y), r * std::sin(two_pi * u.y), z};
    }
    const double q = 0.5 * single.pdf(wo, w, Lobes::both) + 0.5 / (4.0 * pi);
    const double x = coat.eval_walk(wo, w, Transport::importance, rng) * std::abs(w.z) / q;
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1.0)), 0.0};
}

// Energy: a non-absorbing interface that scatters until the light leaves reflects and transmits all of it. The
// walks all leave (none is cut at max_walk_events), and the eval estimator integrates to 1 over the sphere
// (within 3 standard errors or 1e-3), for roughness 0 to 1 (perceptual; alpha = r^2), from above and below,
// 0 to 85 degrees. The single-scattering interface fails it at roughness 1 (measured, far below 1).
TEST(RoughDielectricMultiple, ConservesEnergy) {
  double worst = 0.0;
  int most_events = 0;
  for (double r : {0.0, 0.3, 0.6, 1.0}) {
    for (double eta : {1.5, 1.0 / 1.5}) {
      const RoughDielectric coat(eta, r * r, Scattering::multiple);
      for (double theta : {0.0, 45.0, 85.0}) {
        const Vec3 wo = testing::dir(theta, 10.0);
        Pcg32 rng(11, static_cast<std::uint64_t>(theta));
        const int walks = 20000;
        int left = 0;
        for (int i = 0; i < walks; ++i) {
          int events = 0;
          if (coat.random_walk(wo, rng, nullptr, nullptr, &events)) ++left;
          most_events = std::max(most_events, events);
        }
        EXPECT_EQ(left, walks) << r << " " << eta << " " << theta;
        const Integral e = walked_power(coat, wo, 20000, 5 + static_cast<std::uint64_t>(theta));
        EXPECT_NEAR(e.value, 1.0, std::max(3.0 * e.standard_error, 1e-3))
            << "roughness " << r << " eta " << eta << " theta " << theta << " se " << e.standard_error;
        worst = std::max(worst, std::abs(e.value - 1.0) / e.standard_error);
      }
    }
  }
  const RoughDielectric single(1.5, 1.0);
  const Integral lost = walked_power(single, testing::dir(45.0, 10.0), 20000, 1);
  EXPECT_LT(lost.value, 1.0 - 10.0 * lost.standard_error);
  std::printf("multiple scattering: power within %.2f standard errors of 1; longest walk %d hits; single "
              "scattering at roughness 1, 45 deg: %.4f +- %.4f\n",
              worst, most_events, lost.value, lost.standard_error);
}

// The eval estimator is the density of the walk: the histogram of 2e5 walks over 80 equal-area bins of the
// sphere (10 in z, 8 in phi: both hemispheres) against the integral of eval_walk over each bin (1024 jittered
// directions, one walk each). Pearson's statistic over the bins expected to hold >= 20 walks, with the variance
// of both estimates, stays under the chi-square quantile at p = 1e-3 (Wilson-Hilferty); and the single-scattering
// eval, against the same walks, is far over it.
TEST(RoughDielectricMultiple, EvalMatchesTheWalkHistogram) {
  const int nz = 10;
  const int nphi = 8;
  const double cell = (2.0 / nz) * (two_pi / nphi);
  for (const auto& [alpha, eta, theta] : {std::tuple{0.36, 1.5, 30.0}, std::tuple{1.0, 1.5, 70.0},
                                          std::tuple{1.0, 1.0 / 1.5, 20.0}, std::tuple{0.5, 2.0, 60.0}}) {
    const RoughDielectric coat(eta, alpha, Scattering::multiple);
    const RoughDielectric single(eta, alpha);
    const Vec3 wo = testing::dir(theta, 0.0);
    Pcg32 rng(21, static_cast<std::uint64_t>(theta));
    auto bin_of = [&](const Vec3& w) {
      const int iz = std::clamp(static_cast<int>((w.z + 1.0) * 0.5 * nz), 0, nz - 1);
      double phi = std::atan2(w.y, w.x);
      if (phi < 0.0) phi += two_pi;
      const int ip = std::clamp(static_cast<int>(phi / two_pi * nphi), 0, nphi - 1);
      return iz * nphi + ip;
    };
    const int n = 200000;
    std::vector<double> counts(nz * nphi, 0.0);
    for (int i = 0; i < n; ++i) {
      const auto w = coat.random_walk(wo, rng, nullptr, nullptr, nullptr);
      ASSERT_TRUE(w.has_value());
      counts[bin_of(*w)] += 1.0;
    }
    double chi2 = 0.0;
    double chi2_single = 0.0;
    int dof = 0;
    const int m = 1024;  // 32 x 32 jittered; the estimator is skewed (rare large next-event terms), so not fewer
    for (int iz = 0; iz < nz; ++iz) {
      for (int ip = 0; ip < nphi; ++ip) {
        double sum = 0.0;
        double sum2 = 0.0;
        double sum_single = 0.0;
        for (int j = 0; j < m; ++j) {
          const double z = -1.0 + (iz + (j % 32 + rng.next_double()) / 32.0) * (2.0 / nz);
          const double phi = (ip + (j / 32 + rng.next_double()) / 32.0) * (two_pi / nphi);
          const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
          const Vec3 w{s * std::cos(phi), s * std::sin(phi), z};
          const double x = coat.eval_walk(wo, w, Transport::importance, rng) * std::abs(z);
          sum += x;
          sum2 += x * x;
          sum_single += single.eval(wo, w, Transport::importance) * std::abs(z);
        }
        const double mean = sum / m;
        const double p = cell * mean;                                                   // the bin's probability
        const double var_p = cell * cell * std::max(0.0, sum2 / m - mean * mean) / (m - 1.0);  // of that estimate
        const double expected = n * p;
        if (expected < 20.0) continue;
        const double o = counts[iz * nphi + ip];
        chi2 += (o - expected) * (o - expected) / (expected * (1.0 - p) + static_cast<double>(n) * n * var_p);
        const double es = n * cell * sum_single / m;
        chi2_single += (o - es) * (o - es) / (expected * (1.0 - p) + static_cast<double>(n) * n * var_p);
        ++dof;
      }
    }
    ASSERT_GT(dof, 20);
    // chi^2_{dof} quantile at 1 - 1e-3 (Wilson & Hilferty 1931): dof (1 - 2/(9 dof) + z sqrt(2/(9 dof)))^3, z = 3.09.
    const double k = 2.0 / (9.0 * dof);
    const double limit = dof * std::pow(1.0 - k + 3.09 * std::sqrt(k), 3.0);
    EXPECT_LT(chi2, limit) << "alpha " << alpha << " eta " << eta << " theta " << theta << " dof " << dof;
    EXPECT_GT(chi2_single, (alpha >= 1.0 ? 3.0 : 1.0) * limit) << alpha << " " << eta << " " << theta;
    std::printf("walk histogram alpha %.2f eta %.3f theta %.0f: chi2 %.1f over %d bins (limit %.1f); single scattering %.0f\n",
                alpha, eta, theta, chi2, dof, limit, chi2_single);
  }
}

// Near the smooth limit, multiple scattering adds nothing measurable: eval_walk's mean over 4000 walks equals the
// single-scattering value within 3 standard errors (and 1e-3 relative) at reflected and refracted pairs near the
// lobes' peaks, and the walks almost never hit twice.
TEST(RoughDielectricMultiple, NearlySmoothIsSingleScattering) {
  for (double alpha : {1e-4, 1e-3, 1e-2}) {
    const RoughDielectric coat(1.5, alpha, Scattering::multiple);
    const RoughDielectric single(1.5, alpha);
    Pcg32 rng(31);
    for (double theta : {10.0, 50.0}) {
      const Vec3 wo = testing::dir(theta, 0.0);
      // Near the mirror direction and near Snell's, offset by about alpha.
      const double sin_t = std::sin(theta * pi / 180.0) / 1.5;
      const Vec3 mirror = normalize(Vec3{-wo.x + 0.5 * alpha, 0.3 * alpha, wo.z});
      const Vec3 snell = normalize(Vec3{-sin_t + 0.5 * alpha, 0.3 * alpha, -std::sqrt(1.0 - sin_t * sin_t)});
      for (const Vec3& wi : {mirror, snell}) {
        double sum = 0.0;
        double sum2 = 0.0;
        const int n = 4000;
        for (int i = 0; i < n; ++i) {
          const double x = coat.eval_walk(wo, wi, Transport::radiance, rng);
          sum += x;
          sum2 += x * x;
        }
        const double mean = sum / n;
        const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1.0));
        const double expected = single.eval(wo, wi, Transport::radiance);
        ASSERT_GT(expected, 0.0);
        EXPECT_NEAR(mean, expected, std::max(3.0 * se, 1e-3 * expected)) << alpha << " " << theta << " se " << se;
      }
      int twice = 0;
      for (int i = 0; i < 20000; ++i) {
        int events = 0;
        coat.random_walk(wo, rng, nullptr, nullptr, &events);
        if (events > 1) ++twice;
      }
      EXPECT_LE(twice, 20000 * 10.0 * alpha + 5.0) << alpha << " " << theta;
    }
  }
}

// Reciprocity in expectation: the reflection (radiance form) f(a, b) and f(b, a) agree within 4 standard errors
// on both sides of the interface; and the transmission obeys generalized reciprocity f(a, b) eta^2 = f(b, a)
// (a above). 20000 walks per value.
TEST(RoughDielectricMultiple, IsReciprocalInExpectation) {
  auto mean_of = [](const RoughDielectric& c, const Vec3& wo, const Vec3& wi, std::uint64_t seed) {
    Pcg32 rng(seed, 7);
    double sum = 0.0;
    double sum2 = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double x = c.eval_walk(wo, wi, Transport::radiance, rng);
      sum += x;
      sum2 += x * x;
    }
    const double mean = sum / n;
    return std::pair{mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1.0))};
  };
  double worst = 0.0;
  for (double alpha : {0.36, 1.0}) {
    const RoughDielectric coat(1.5, alpha, Scattering::multiple);
    for (const auto& [ta, pa, tb, pb] : {std::array{20.0, 0.0, 60.0, 150.0}, std::array{75.0, 30.0, 10.0, 200.0}}) {
      for (bool above : {true, false}) {
        const Vec3 a = above ? testing::dir(ta, pa) : below(ta, pa);
        const Vec3 b = above ? testing::dir(tb, pb) : below(tb, pb);
        const auto [ab, se_ab] = mean_of(coat, a, b, 1);
        const auto [ba, se_ba] = mean_of(coat, b, a, 2);
        const double sigma = std::hypot(se_ab, se_ba);
        EXPECT_NEAR(ab, ba, 4.0 * sigma) << alpha << " " << ta << " " << tb << " above " << above;
        worst = std::max(worst, std::abs(ab - ba) / sigma);
      }
      const Vec3 a = testing::dir(ta, pa);
      const Vec3 b = below(tb, pb);
      const auto [ab, se_ab] = mean_of(coat, a, b, 3);
      const auto [ba, se_ba] = mean_of(coat, b, a, 4);
      EXPECT_NEAR(ab * 1.5 * 1.5, ba, 4.0 * std::hypot(1.5 * 1.5 * se_ab, se_ba)) << alpha << " " << ta << " " << tb;
    }
  }
  std::printf("multiple scattering: largest reflection reciprocity defect %.2f standard errors\n", worst);
}

// The walk sample's weight is the form asked for: 1 for importance, 1 / eta_i^2 for a transmission in radiance;
// and Scattering::single makes sample_walk and eval_walk the single-scattering sample and eval.
TEST(RoughDielectricMultiple, WalkSampleWeightsAndTheSingleFallback) {
  const RoughDielectric coat(1.5, 0.3, Scattering::multiple);
  Pcg32 rng(41);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 wo = i % 2 ? testing::dir(40.0, 0.0) : below(30.0, 0.0);
    const auto s = coat.sample_walk(wo, rng, Transport::radiance);
    ASSERT_TRUE(s.has_value());
    const bool across = s->wi.z * wo.z < 0.0;
    const double etap = wo.z > 0.0 ? 1.5 : 1.0 / 1.5;
    EXPECT_DOUBLE_EQ(s->weight, across ? 1.0 / (etap * etap) : 1.0);
    EXPECT_EQ(coat.sample_walk(wo, rng, Transport::importance)->weight, 1.0);
  }
  const RoughDielectric single(1.5, 0.3);
  Pcg32 a(5);
  const Vec3 wo = testing::dir(30.0, 0.0);
  const Vec3 wi = below(20.0, 180.0);
  EXPECT_EQ(single.eval_walk(wo, wi, Transport::radiance, a), single.eval(wo, wi, Transport::radiance));
  const auto s = single.sample_walk(wo, a, Transport::radiance);
  Pcg32 b(5);
  const double ul = b.next_double();
  const double u1 = b.next_double();
  const double u2 = b.next_double();
  const auto t = single.sample(wo, ul, Vec2{u1, u2}, Transport::radiance, Lobes::both);
  ASSERT_EQ(s.has_value(), t.has_value());
  if (s) {
    EXPECT_EQ(s->weight, t->weight);
  }
}

}  // namespace
}  // namespace shadelab
