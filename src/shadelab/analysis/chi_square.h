// shadelab sampler tests: Pearson's chi-square goodness of fit of a BRDF's sampler against its pdf, the
// consistency of the values sample() returns, and the integral of the pdf over the sphere.
//
// Contract:
// - chi_square_test(f, wo) draws N directions with f.sample(wo, u, u_lobe), u and u_lobe from Pcg32 with a
//   fixed seed, and bins them over the WHOLE sphere in (cos theta, phi): cos_theta_bins equal rows over
//   [-1, 1] (so the horizon is a row boundary) times phi_bins equal columns over [0, 2 pi). The expected
//   count of a cell is N times the integral of f.pdf(wi, wo) over it (d(omega) = d(cos theta) d(phi)), by
//   nested adaptive Gauss-Kronrod quadrature. Cells with expected count below min_expected are pooled (in
//   increasing order of expectation, into groups of at least min_expected). The statistic is
//   sum (O - E)^2 / E over the groups, with groups - 1 degrees of freedom; the p-value is Q(dof/2, stat/2).
//   A sample in a cell whose expected count is 0, or a non-finite sampled direction, makes the p-value 0.
// - regularized_gamma_p / _q are the regularized lower / upper incomplete gamma functions P(a, x), Q(a, x)
//   for a > 0, x >= 0 (series for x < a + 1, continued fraction otherwise), about 1e-14 relative for
//   small a and a few 1e-13 for a in the hundreds (the prefactor goes through lgamma(a)); NaN for a <= 0.
// - sidak_significance(alpha, k) = 1 - (1 - alpha)^(1/k): the per-test level that keeps the family-wise
//   false rejection rate of k independent tests at alpha.
// - sample_consistency(f, wo, M) draws M samples and reports the largest relative differences between
//   sample().pdf and f.pdf(wi, wo), and between sample().weight and f.eval(wi, wo) cos(theta_i) / f.pdf(wi, wo)
//   (per channel, relative to max(|expected|, |weight|, 1e-12)); samples below the horizon must have weight 0
//   and are counted, as are samples with pdf 0 (which are not compared).
// - pdf_integral(f, wo) integrates f.pdf(wi, wo) over the sphere by quadrature (integrate_sphere): the upper
//   half about the pdf's peak there, the lower half about -wo (where reflection samplers have an integrable
//   1 / |wo.h| singularity) or about a lobe that peaks below the horizon. It should be 1. For a model whose
//   pdf_smooth_below_horizon() is false (brdf.h: a density that jumps across a curve below the horizon), the
//   lower half is the sampler's share of pdf_integral_lower_samples_for(f) samples below the horizon instead, and the
//   result's error adds that share's binomial standard error.
// - For a tabulated model (Brdf::is_tabulated: a density piecewise constant on cells, with jumps adaptive quadrature
//   cannot finish over) pdf_integral is instead the midpoint sum on a 1024 x 1024 grid in (phi - phi_o, cos theta)
//   over the sphere, whose cells the measured model's (128 x 64 over the upper hemisphere) divide exactly, so its
//   table part is summed exactly and its cosine part to O(h^2); error: |the sum - the 512 x 512 sum|.
// - For such a model chi_square_test pools the whole lower hemisphere into one bin whose expected count is N
//   minus the upper cells' (lower_pooled): the sampler's mass below the horizon is tested, not its shape
//   there (those samples carry weight 0).
// - weight_mean(f, wo, M): the mean and standard error of M sample weights against the directional albedo by
//   quadrature (albedo.h): E[f cos / pdf] = albedo for an unbiased sampler, an expected value computed without
//   sample(). max_z = max over channels of |mean - albedo| / sqrt(se^2 + (1e-7 albedo)^2).
// Deterministic: the same inputs and seed give the same results. No printing.
#pragma once

#include <cstdint>
#include <vector>

#include "shadelab/numeric/quadrature.h"
#include "shadelab/brdf/brdf.h"

namespace shadelab {

double regularized_gamma_p(double a, double x);
double regularized_gamma_q(double a, double x);
// Upper tail of the chi-square distribution with dof degrees of freedom: Q(dof/2, statistic/2).
double chi_square_p_value(double statistic, double dof);
double sidak_significance(double alpha, int tests);

struct ChiSquareOptions {
  int cos_theta_bins = 20;
  int phi_bins = 40;
  std::uint64_t samples = 1'000'000;
  std::uint64_t seed = 0x5eed;
  double min_expected = 5.0;
  double cell_rel_tol = 1e-5;  // quadrature tolerance per cell (plus an absolute 0.01 counts)
};

struct ChiSquareResult {
  double statistic = 0.0;
  int degrees_of_freedom = 0;
  double p_value = 0.0;
  std::uint64_t samples = 0;
  std::uint64_t invalid_samples = 0;     // non-finite direction
  std::uint64_t unexpected_samples = 0;  // landed in a cell with expected count 0
  double expected_total = 0.0;           // sum of the expected counts (N times the integral of the pdf)
  bool lower_pooled = false;             // the lower hemisphere is one bin (pdf_smooth_below_horizon() false)
  double lower_expected = 0.0;           // its expected count then
  int pooled_cells = 0;                  // cells that went into pooled groups
  bool integration_converged = false;
  int rows = 0;
  int cols = 0;
  std::vector<double> observed;  // rows * cols, row 0 at cos theta = -1
  std::vector<double> expected;
};

ChiSquareResult chi_square_test(const Brdf& f, const Vec3& wo, const ChiSquareOptions& options = {});

struct SampleConsistency {
  std::uint64_t samples = 0;
  std::uint64_t zero_pdf = 0;                      // sample().pdf == 0
  std::uint64_t below_horizon = 0;                 // wi.z <= 0
  std::uint64_t nonzero_weight_below_horizon = 0;  // violations of the contract
  std::uint64_t non_finite = 0;                    // non-finite wi, pdf or weight
  double max_pdf_error = 0.0;
  double max_weight_error = 0.0;
  Vec3 worst_pdf_wi;
  Vec3 worst_weight_wi;
};

SampleConsistency sample_consistency(const Brdf& f, const Vec3& wo, std::uint64_t count, std::uint64_t seed = 0x5eed);

struct WeightMean {
  std::uint64_t samples = 0;
  Rgb mean;            // of sample().weight
  Rgb standard_error;  // of the mean
  Rgb albedo;          // directional albedo by quadrature
  double max_z = 0.0;
};

WeightMean weight_mean(const Brdf& f, const Vec3& wo, std::uint64_t count, std::uint64_t seed = 0x5eed);

// The share of count samples of f.sample(wo, ...) that fall on or below the horizon.
double sampled_share_below_horizon(const Brdf& f, const Vec3& wo, std::uint64_t count, std::uint64_t seed = 0x5eed);
constexpr std::uint64_t pdf_integral_lower_samples = 1'000'000;
// The count pdf_integral takes for f: a fifth for a stochastic model (Brdf::is_stochastic), whose every sample
// evaluates a Monte Carlo estimate for its weight (the tolerance, 4 standard errors, widens with it).
inline std::uint64_t pdf_integral_lower_samples_for(const Brdf& f) {
  return f.is_stochastic() ? pdf_integral_lower_samples / 5 : pdf_integral_lower_samples;
}

// rel_tol 1e-9 by default.
QuadratureResult pdf_integral(const Brdf& f, const Vec3& wo, const QuadratureOptions& options = [] {
  QuadratureOptions o;
  o.rel_tol = 1e-9;
  o.initial_intervals = 4;
  return o;
}());

}  // namespace shadelab
