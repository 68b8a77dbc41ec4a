#include "shadelab/brdf/rough_dielectric.h"

#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace shadelab
