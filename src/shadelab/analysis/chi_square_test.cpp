#include "shadelab/analysis/chi_square.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>

#include "shadelab/analysis/test_brdfs.h"

namespace shadelab {
namespace {

using testing::Broken;
using testing::broken;
using testing::make;
using testing::view;

// Q(a, x) for integer a: e^-x sum_{k < a} x^k / k! (the Poisson tail; A&S 6.5.13).
double poisson_q(int a, double x) {
  double term = 1.0;
  double sum = 0.0;
  for (int k = 0; k < a; ++k) {
    if (k > 0) term *= x / k;
    sum += term;
  }
  return std::exp(-x) * sum;
}

TEST(IncompleteGamma, IntegerOrderAgainstThePoissonSum) {
  for (int a : {1, 2, 5, 20, 50, 200}) {
    for (double x : {0.01, 0.5, 1.0, 3.0, 10.0, 49.0, 50.0, 51.0, 150.0, 190.0, 210.0, 300.0}) {
      const double q = poisson_q(a, x);
      // The prefactor x^a e^-x / Gamma(a) goes through lgamma(a), ~860 for a = 200: a few 1e-13 relative.
      const double rel = a >= 100 ? 5e-13 : 1e-13;
      EXPECT_NEAR(regularized_gamma_q(a, x), q, rel * q + 1e-300) << "a=" << a << " x=" << x;
      EXPECT_NEAR(regularized_gamma_p(a, x), 1.0 - q, rel) << "a=" << a << " x=" << x;
    }
  }
}

TEST(IncompleteGamma, HalfIntegerOrderAgainstErf) {
  for (double x : {1e-6, 0.1, 0.5, 1.0, 1.5, 2.0, 5.0, 20.0}) {
    // P(1/2, x) = erf(sqrt(x)) (A&S 6.5.17); Q(3/2, x) = erfc(sqrt(x)) + 2 sqrt(x / pi) e^-x.
    EXPECT_NEAR(regularized_gamma_p(0.5, x), std::erf(std::sqrt(x)), 1e-14) << x;
    const double q32 = std::erfc(std::sqrt(x)) + 2.0 * std::sqrt(x / pi) * std::exp(-x);
    EXPECT_NEAR(regularized_gamma_q(1.5, x), q32, 1e-14 * std::max(1.0, q32)) << x;
  }
}

TEST(IncompleteGamma, ChiSquareCriticalValues) {
  // Upper 5% and 1% points of the chi-square distribution (checked against erfc and the Poisson sum).
  EXPECT_NEAR(chi_square_p_value(3.841458820694124, 1), 0.05, 1e-13);
  EXPECT_NEAR(chi_square_p_value(6.6348966010212145, 1), 0.01, 1e-13);
  EXPECT_NEAR(chi_square_p_value(18.307038053275146, 10), 0.05, 1e-13);
  EXPECT_NEAR(chi_square_p_value(124.34211340400407, 100), 0.05, 1e-13);
  EXPECT_NEAR(chi_square_p_value(135.80672317102676, 100), 0.01, 1e-13);
  EXPECT_EQ(chi_square_p_value(0.0, 10), 1.0);
  EXPECT_EQ(chi_square_p_value(5.0, 0), 1.0);
}

TEST(IncompleteGamma, EdgesAndSymmetry) {
  EXPECT_EQ(regularized_gamma_p(3.0, 0.0), 0.0);
  EXPECT_EQ(regularized_gamma_q(3.0, 0.0), 1.0);
  EXPECT_EQ(regularized_gamma_q(3.0, std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_TRUE(std::isnan(regularized_gamma_p(0.0, 1.0)));
  EXPECT_TRUE(std::isnan(regularized_gamma_q(-1.0, 1.0)));
  for (double a : {0.3, 2.5, 17.5, 399.5}) {
    for (double x : {0.2, a * 0.9, a, a + 1.0, a * 1.2, a * 3.0}) {
      EXPECT_NEAR(regularized_gamma_p(a, x) + regularized_gamma_q(a, x), 1.0, 1e-14) << a << " " << x;
    }
  }
}

TEST(ChiSquare, SidakSignificance) {
  EXPECT_DOUBLE_EQ(sidak_significance(0.05, 1), 0.05);
  EXPECT_NEAR(sidak_significance(0.01, 4), 1.0 - std::pow(0.99, 0.25), 1e-16);
  EXPECT_NEAR(sidak_significance(0.01, 4), 0.002509430066318874, 1e-15);
  // k tests at the corrected level keep the family-wise rate at alpha.
  const double level = sidak_significance(0.01, 132);
  EXPECT_NEAR(1.0 - std::pow(1.0 - level, 132), 0.01, 1e-14);
}

TEST(ChiSquare, CorrectSamplersPass) {
  const double level = sidak_significance(0.01, 12);
  ChiSquareOptions o;
  o.samples = 300'000;
  for (const auto& [model, params] : std::vector<std::pair<std::string, ParamAssignments>>{
           {"lambert", {}}, {"phong", {{"n", "20"}}}, {"blinn-phong-modified", {{"n", "5"}, {"kd", "0.1"}}},
           {"cook-torrance", {{"m", "0.6"}}}}) {
    const auto f = make(model, params);
    for (double t : {0.0, 45.0, 80.0}) {
      const ChiSquareResult r = chi_square_test(*f, view(t), o);
      EXPECT_GE(r.p_value, level) << model << " theta " << t << " statistic " << r.statistic << " dof "
                                  << r.degrees_of_freedom;
      EXPECT_NEAR(r.expected_total, 300'000.0, 0.5) << model << " theta " << t;
      EXPECT_EQ(r.invalid_samples, 0u);
      EXPECT_EQ(r.unexpected_samples, 0u);
      EXPECT_GT(r.degrees_of_freedom, 100) << model;
      EXPECT_NEAR(std::accumulate(r.observed.begin(), r.observed.end(), 0.0), 300'000.0, 0.0);
    }
  }
}

TEST(ChiSquare, WrongPdfsAreRejected) {
  ChiSquareOptions o;
  o.samples = 200'000;
  // Cosine-weighted samples tested against a uniform pdf.
  EXPECT_LT(chi_square_test(*broken("lambert", {}, Broken::Fault::uniform_pdf), view(30.0), o).p_value, 1e-12);
  // A pdf that integrates to 0.9.
  EXPECT_LT(chi_square_test(*broken("phong", {{"n", "20"}}, Broken::Fault::scaled_pdf), view(30.0), o).p_value, 1e-12);
  // Samples where the pdf is 0.
  const ChiSquareResult below = chi_square_test(*broken("lambert", {}, Broken::Fault::samples_below), view(0.0), o);
  EXPECT_GT(below.unexpected_samples, 0u);
  EXPECT_EQ(below.p_value, 0.0);
  // A subtle one: the pdf of a Phong lobe of exponent 20 against the sampler of exponent 22.
  class Mismatch final : public Brdf {
   public:
    Rgb eval(const Vec3& wi, const Vec3& wo) const override { return m_pdf->eval(wi, wo); }
    double pdf(const Vec3& wi, const Vec3& wo) const override { return m_pdf->pdf(wi, wo); }
    BrdfSample sample(const Vec3& wo, Vec2 u, double ul) const override { return m_sampler->sample(wo, u, ul); }

   private:
    BrdfPtr m_pdf = make("phong", {{"kd", "0"}, {"n", "20"}});
    BrdfPtr m_sampler = make("phong", {{"kd", "0"}, {"n", "22"}});
  };
  EXPECT_LT(chi_square_test(Mismatch(), view(30.0), o).p_value, 1e-6);
}

TEST(ChiSquare, SampleConsistency) {
  const auto lambert = make("lambert");
  const SampleConsistency good = sample_consistency(*lambert, view(30.0), 20'000);
  EXPECT_LE(good.max_pdf_error, 1e-15);
  EXPECT_LE(good.max_weight_error, 1e-15);
  EXPECT_EQ(good.samples, 20'000u);
  EXPECT_EQ(good.below_horizon + good.zero_pdf + good.non_finite, 0u);

  // A glossy lobe at grazing incidence samples below the horizon; those must have weight 0, and they do.
  const SampleConsistency grazing = sample_consistency(*make("phong", {{"n", "5"}}), view(80.0), 20'000);
  EXPECT_GT(grazing.below_horizon, 100u);
  EXPECT_EQ(grazing.nonzero_weight_below_horizon, 0u);
  EXPECT_LE(grazing.max_weight_error, 1e-12);

  EXPECT_NEAR(sample_consistency(*broken("lambert", {}, Broken::Fault::wrong_weight), view(30.0), 1000).max_weight_error,
              0.01 / 1.01, 1e-12);
  EXPECT_NEAR(
      sample_consistency(*broken("lambert", {}, Broken::Fault::wrong_sample_pdf), view(30.0), 1000).max_pdf_error,
      0.5 / 1.5, 1e-12);
  EXPECT_GT(sample_consistency(*broken("phong", {{"n", "5"}}, Broken::Fault::weight_below_horizon), view(80.0), 5000)
                .nonzero_weight_below_horizon,
            10u);
}

TEST(ChiSquare, PdfIntegral) {
  EXPECT_NEAR(pdf_integral(*make("lambert"), view(20.0)).value, 1.0, 1e-12);
  EXPECT_NEAR(pdf_integral(*broken("phong", {{"n", "20"}}, Broken::Fault::scaled_pdf), view(40.0)).value, 0.9, 1e-9);
  for (double t : {0.0, 60.0, 89.0}) {
    // A sharp lobe, and a broad microfacet one with the 1 / |wo.h| singularity of the reflection Jacobian.
    const QuadratureResult sharp = pdf_integral(*make("phong", {{"n", "10000"}, {"kd", "0"}}), view(t));
    EXPECT_NEAR(sharp.value, 1.0, 1e-9) << t;
    const QuadratureResult broad = pdf_integral(*make("blinn-phong", {{"n", "0"}, {"kd", "0"}}), view(t));
    EXPECT_NEAR(broad.value, 1.0, 1e-8) << t;
  }
}

}  // namespace
}  // namespace shadelab
