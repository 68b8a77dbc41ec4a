#include "shadelab/brdf/layered.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "shadelab/brdf/test_util.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/numeric/quadrature.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

struct Mean {
  double mean = 0.0;
  double standard_error = 0.0;
};

// The directional albedo at wo, channel g, by the model's own sampler: the mean of the sample weights
// (eval cos / pdf), with its standard error.
Mean albedo_by_sampling(const Brdf& f, const Vec3& wo, int n, std::uint64_t seed) {
  Pcg32 rng(seed, 11);
  double sum = 0.0;
  double sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec2 u{rng.next_double(), rng.next_double()};
    const BrdfSample s = f.sample(wo, u, rng.next_double());
    sum += s.weight.g;
    sum2 += s.weight.g * s.weight.g;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1.0))};
}

// The smooth-coat oracle. A smooth dielectric (relative index eta) over a Lambertian base of albedo rho, with a
// clear slab between: light from mu is reflected with F(mu); the rest, 1 - F(mu), enters and reaches the base,
// which returns rho of it as a Lambertian distribution; of Lambertian light inside, the interface returns the
// internal diffuse reflectance r_i and lets 1 - r_i out. Summing the bounces,
//   A(mu) = F(mu) + (1 - F(mu)) rho (1 - r_i) / (1 - rho r_i).
// By reciprocity (the cosine-weighted throughput of the interface is the same from each side once radiance is
// divided by n^2), the Lambertian light let out from inside is (1 - r_e) / eta^2 of it, with r_e = 2
// integral_0^1 F(mu) mu dmu the outside hemispherical reflectance: 1 - r_i = (1 - r_e) / eta^2.
double smooth_coat_albedo(double mu, double eta, double rho) {
  const auto r_e = integrate([&](double m) { return 2.0 * m * kernel::F_dielectric(m, eta); }, 0.0, 1.0);
  const double escape = (1.0 - r_e.value) / (eta * eta);  // 1 - r_i
  const double f = kernel::F_dielectric(mu, eta);
  return f + (1.0 - f) * rho * escape / (1.0 - rho * (1.0 - escape));
}

TEST(Layered, SmoothCoatOverLambertMeetsTheOracle) {
  // >= 1e5 walks per configuration (one per sample), within 3 standard errors; the default coat (multiple
  // scattering) at every configuration, the single-scattering coat at the first.
  const int n = 100000;
  for (const auto& [eta, rho, scattering] :
       {std::tuple{1.5, 0.8, "multiple"}, std::tuple{1.5, 1.0, "multiple"}, std::tuple{1.33, 0.3, "multiple"},
        std::tuple{2.0, 0.6, "multiple"}, std::tuple{1.5, 0.8, "single"}}) {
    const BrdfPtr f = testing::make("layered", {{"coat_roughness", "0"}, {"coat_ior", std::to_string(eta)},
                                                {"base_color", std::to_string(rho)}, {"walk_samples", "1"},
                                                {"coat_scattering", scattering}});
    for (double theta : {0.0, 45.0, 75.0}) {
      const Mean a = albedo_by_sampling(*f, testing::dir(theta, 20.0), n, 1);
      const double expected = smooth_coat_albedo(std::cos(theta * pi / 180.0), eta, rho);
      EXPECT_NEAR(a.mean, expected, 3.0 * a.standard_error)
          << "eta " << eta << " rho " << rho << " theta " << theta << " " << scattering << " (se " << a.standard_error
          << ")";
    }
  }
}

// Breaking the oracle's physics must fail it: a base of half the albedo is many standard errors away.
TEST(Layered, TheOracleTellsADifferentBaseApart) {
  const BrdfPtr f = testing::make("layered", {{"coat_roughness", "0"}, {"base_color", "0.4"}, {"walk_samples", "1"}});
  const Mean a = albedo_by_sampling(*f, testing::dir(30.0, 0.0), 100000, 2);
  EXPECT_GT(std::abs(a.mean - smooth_coat_albedo(std::cos(pi / 6.0), 1.5, 0.8)), 30.0 * a.standard_error);
}

// coat_ior = 1 is no interface: the base seen through the slab twice, T = coat_color^(thickness / |cos|).
TEST(Layered, NoInterfaceIsTheBaseThroughTheSlab) {
  const BrdfPtr f = testing::make("layered", {{"coat_ior", "1"}, {"coat_color", "0.9,0.5,0.2"}, {"coat_thickness", "2"},
                                              {"base_color", "0.7"}});
  const Vec3 wi = testing::dir(30.0, 10.0);
  const Vec3 wo = testing::dir(60.0, 200.0);
  const double c[3] = {0.9, 0.5, 0.2};
  const Rgb got = f->eval(wi, wo);
  for (int k = 0; k < 3; ++k) {
    const double t = std::exp(2.0 * std::log(c[k]) / wi.z) * std::exp(2.0 * std::log(c[k]) / wo.z);
    EXPECT_NEAR(got[k], t * 0.7 / pi, 1e-14) << k;
  }
}

// eval is a function of (wi, wo, seed): the same bits on every call; another seed, another estimate.
TEST(Layered, EvalIsDeterministicPerPairAndSeed) {
  const BrdfPtr a = testing::make("layered", {{"coat_roughness", "0.3"}});
  const BrdfPtr b = testing::make("layered", {{"coat_roughness", "0.3"}, {"seed", "5"}});
  const Vec3 wi = testing::dir(35.0, 0.0);
  const Vec3 wo = testing::dir(50.0, 160.0);
  const Rgb x = a->eval(wi, wo);
  EXPECT_EQ(x.g, a->eval(wi, wo).g);
  EXPECT_NE(x.g, b->eval(wi, wo).g);
  EXPECT_GT(x.g, 0.0);
}

// Reciprocal in expectation: f(wi, wo) and f(wo, wi) agree within their standard errors, for a rough coat over
// each base and an absorbing slab; the largest relative defect is printed (docs/models/layered.md).
TEST(Layered, IsReciprocalInExpectation) {
  double worst = 0.0;
  for (const char* base : {"lambert", "conductor", "ggx"}) {
    const BrdfPtr f = testing::make("layered", {{"coat_roughness", "0.4"}, {"base", base}, {"coat_color", "0.8,0.6,0.9"},
                                                {"base_roughness", "0.5"}});
    const auto& l = static_cast<const LayeredSlab&>(*f);
    for (const auto& [ti, pi_, to, po] : {std::array{20.0, 0.0, 60.0, 150.0}, std::array{70.0, 30.0, 10.0, 200.0}}) {
      const Vec3 wi = testing::dir(ti, pi_);
      const Vec3 wo = testing::dir(to, po);
      const auto x = l.eval_estimate(wi, wo, 40000, 1);
      const auto y = l.eval_estimate(wo, wi, 40000, 2);
      const double sigma = std::hypot(x.standard_error.g, y.standard_error.g);
      EXPECT_NEAR(x.mean.g, y.mean.g, 4.0 * sigma) << base << " " << ti << " " << to;
      worst = std::max(worst, std::abs(x.mean.g - y.mean.g) / x.mean.g);
    }
  }
  std::printf("layered: largest relative reciprocity defect %.2e (40000 walks each way)\n", worst);
}

// The standard error of eval_estimate is the walks' spread: it falls as 1 / sqrt(walks), and the means of
// two independent streams differ by about it.
TEST(Layered, StandardErrorFallsAsOneOverRootWalks) {
  const BrdfPtr f = testing::make("layered", {{"coat_roughness", "0.2"}, {"base", "conductor"}});
  const auto& l = static_cast<const LayeredSlab&>(*f);
  const Vec3 wi = testing::dir(40.0, 0.0);
  const Vec3 wo = testing::dir(40.0, 180.0);
  const auto small = l.eval_estimate(wi, wo, 2000, 1);
  const auto large = l.eval_estimate(wi, wo, 32000, 2);
  EXPECT_NEAR(small.standard_error.g / large.standard_error.g, 4.0, 1.0);
  EXPECT_NEAR(small.mean.g, large.mean.g, 4.0 * std::hypot(small.standard_error.g, large.standard_error.g));
}

// eval states the standard error of its own estimate: the spread of its walk_samples walks, about 10 times that
// of a 100-times longer independent estimate; none from a single walk; 0 where eval is exact.
TEST(Layered, EvalStatesItsStandardError) {
  const BrdfPtr f = testing::make("layered", {{"coat_roughness", "0.3"}, {"walk_samples", "64"}});
  const auto& l = static_cast<const LayeredSlab&>(*f);
  const Vec3 wi = testing::dir(25.0, 0.0);
  const Vec3 wo = testing::dir(55.0, 170.0);
  const auto se = f->eval_standard_error(wi, wo);
  ASSERT_TRUE(se.has_value());
  const auto reference = l.eval_estimate(wi, wo, 6400, 3);
  EXPECT_GT(se->g / reference.standard_error.g, 10.0 * 0.6);
  EXPECT_LT(se->g / reference.standard_error.g, 10.0 * 1.6);
  EXPECT_NEAR(f->eval(wi, wo).g, reference.mean.g, 4.0 * std::hypot(se->g, reference.standard_error.g));
  EXPECT_FALSE(testing::make("layered", {{"walk_samples", "1"}})->eval_standard_error(wi, wo).has_value());
  EXPECT_EQ(testing::make("layered", {{"coat_ior", "1"}})->eval_standard_error(wi, wo)->g, 0.0);
  EXPECT_FALSE(testing::make("lambert")->eval_standard_error(wi, wo).has_value());
}

TEST(Layered, WalkSamplesAndSeedMustBeWholeNumbers) {
  auto r = make_brdf("layered", {{"walk_samples", "2.5"}});
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().message, "brdf layered: parameter 'walk_samples' = 2.5 is not a whole number");
}

// No NaN, infinity or negative value over many pairs, grazing ones included, for every base and extreme
// parameters (the coat at its floor roughness, an opaque slab, a white conductor).
TEST(Layered, FiniteAndNonNegativeEverywhere) {
  Pcg32 rng(9);
  for (const ParamAssignments& p : {ParamAssignments{{"coat_roughness", "0"}, {"base_color", "1"}},
                                    ParamAssignments{{"coat_roughness", "1"}, {"base", "conductor"}, {"base_roughness", "0"}},
                                    ParamAssignments{{"coat_color", "0"}, {"base", "ggx"}},
                                    ParamAssignments{{"coat_ior", "4"}, {"base", "conductor"}, {"base_color", "1"}}}) {
    ParamAssignments q = p;
    q.emplace_back("walk_samples", "1");
    const BrdfPtr f = testing::make("layered", q);
    for (int i = 0; i < 20000; ++i) {
      const double grazing = (i % 4 == 0) ? 1e-9 : 0.0;
      Vec3 wi = testing::dir(90.0 * rng.next_double(), 360.0 * rng.next_double());
      const Vec3 wo = testing::dir(90.0 * rng.next_double(), 360.0 * rng.next_double());
      if (grazing > 0.0) wi = normalize(Vec3{wi.x, wi.y, grazing});
      const Rgb v = f->eval(wi, wo);
      ASSERT_TRUE(is_finite(v) && v.r >= 0.0 && v.g >= 0.0 && v.b >= 0.0) << i;
      const BrdfSample s = f->sample(wo, Vec2{rng.next_double(), rng.next_double()}, rng.next_double());
      ASSERT_TRUE(is_finite(s.weight) && s.weight.g >= 0.0 && std::isfinite(s.pdf)) << i;
    }
  }
}

// The white furnace of the ground truth: a clear coat (coat_color 1) over a white Lambertian base reflects all
// the light (nothing absorbs), within 3 standard errors, once the coat scatters multiply on its microsurface
// (the default); with coat_scattering = single it loses energy at rough coats (0.93, 0.65, 0.32 at 0 degrees).
TEST(Layered, ClearCoatOverWhiteLambertIsAWhiteFurnace) {
  for (const char* r : {"0.3", "0.6", "1"}) {
    const BrdfPtr f = testing::make("layered", {{"coat_roughness", r}, {"base_color", "1"}, {"walk_samples", "1"}});
    for (double theta : {0.0, 60.0}) {
      const Mean a = albedo_by_sampling(*f, testing::dir(theta, 20.0), 150000, 3);
      EXPECT_NEAR(a.mean, 1.0, 3.0 * a.standard_error) << "coat_roughness " << r << " theta " << theta;
      std::printf("layered white furnace, coat_roughness %s, %2.0f deg: %.4f +- %.4f\n", r, theta, a.mean, a.standard_error);
    }
  }
  const BrdfPtr single = testing::make("layered", {{"coat_roughness", "0.6"}, {"base_color", "1"}, {"walk_samples", "1"},
                                                   {"coat_scattering", "single"}});
  const Mean a = albedo_by_sampling(*single, testing::dir(0.0, 20.0), 20000, 3);
  EXPECT_LT(a.mean, 1.0 - 10.0 * a.standard_error);
  std::printf("layered white furnace, single scattering, coat_roughness 0.6: %.4f +- %.4f\n", a.mean, a.standard_error);
}

}  // namespace
}  // namespace shadelab
