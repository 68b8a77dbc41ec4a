#include "shadelab/analysis/chi_square.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "shadelab/analysis/albedo.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

namespace {

constexpr double tiny = 1e-300;
constexpr double epsilon = std::numeric_limits<double>::epsilon();

// log of x^a e^(-x) / Gamma(a), the common factor of the series and the continued fraction.
double log_gamma_prefactor(double a, double x) { return a * std::log(x) - x - std::lgamma(a); }

// P(a, x) = x^a e^-x / Gamma(a) * sum_k x^k / (a (a+1) ... (a+k)) (Abramowitz & Stegun 6.5.29).
double gamma_p_series(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  double ap = a;
  for (int k = 0; k < 100000; ++k) {
    ap += 1.0;
    term *= x / ap;
    sum += term;
    if (std::abs(term) < std::abs(sum) * 0.5 * epsilon) break;
  }
  return sum * std::exp(log_gamma_prefactor(a, x));
}

// Q(a, x) = x^a e^-x / Gamma(a) * 1/(x+1-a- 1(1-a)/(x+3-a- 2(2-a)/(x+5-a- ...))) (A&S 6.5.31 in its even
// form), evaluated with the modified Lentz method (Lentz 1976; Thompson & Barnett 1986).
double gamma_q_fraction(double a, double x) {
  double b = x + 1.0 - a;
  double c = 1.0 / tiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < epsilon) break;
  }
  return std::exp(log_gamma_prefactor(a, x)) * h;
}

Vec3 cell_direction(double z, double phi) {
  return spherical_direction(std::sqrt(std::max(0.0, 1.0 - z * z)), z, phi);
}


struct Rect {
  double z0, z1, phi0, phi1;
};
struct CellIntegral {
  double value = 0.0;
  bool converged = true;
};

double pdf_at(const Brdf& f, const Vec3& wo, double z, double phi) { return f.pdf(cell_direction(z, phi), wo); }

// The integral of the pdf over a rectangle in (z, phi) with the singular point at its corner (zc, pc); the
// opposite corner is (zf, pf). Each of the two triangles on either side of the diagonal is mapped to the
// unit square by Duffy's transformation (Duffy, "Quadrature over a pyramid or cube of integrands with a
// singularity at a vertex", SIAM J. Numer. Anal. 1982): (s, t) -> corner + s (A, B t) with Jacobian |A B| s,
// which cancels a 1/r singularity at the corner, whatever its dependence on the direction of approach.
CellIntegral corner_singular(const Brdf& f, const Vec3& wo, double zc, double pc, double zf, double pf,
                             const QuadratureOptions& q) {
  const double a = zf - zc;
  const double b = pf - pc;
  const double jacobian = std::abs(a * b);
  const auto unit = [](double) { return 0.0; };
  const auto one = [](double) { return 1.0; };
  QuadratureOptions o = q;
  o.abs_tol = 0.5 * q.abs_tol;
  const QuadratureResult t1 = integrate_2d(
      [&](double s, double t) { return jacobian * s * pdf_at(f, wo, zc + a * s, pc + b * s * t); }, 0.0, 1.0, unit,
      one, o);
  const QuadratureResult t2 = integrate_2d(
      [&](double s, double t) { return jacobian * s * pdf_at(f, wo, zc + a * s * t, pc + b * s); }, 0.0, 1.0, unit,
      one, o);
  return {t1.value + t2.value, t1.converged && t2.converged};
}

// The integral of the pdf over one cell. Reflection samplers have an integrable singularity at wi = -wo (the
// Jacobian 1 / (4 |wo.h|) as wo.h -> 0, with a strength that depends on the direction of approach); a cell
// that holds it is cut there into pieces that each have it at a corner, and those are integrated by
// corner_singular. At the poles (z = -1 or 1 for wo on the normal) the singularity is a cell edge, which
// nested Gauss-Kronrod handles as it is.
CellIntegral cell_integral(const Brdf& f, const Vec3& wo, const Rect& cell, Vec2 singular, const QuadratureOptions& q) {
  constexpr double snap = 1e-12;
  const double zs = singular.x;
  const double ps = singular.y;
  const bool at_pole = std::abs(zs) > 1.0 - 1e-9;
  const bool z_in = zs >= cell.z0 - snap && zs <= cell.z1 + snap;
  const bool phi_in = ps >= cell.phi0 - snap && ps <= cell.phi1 + snap;
  if (at_pole || !z_in || !phi_in) {
    QuadratureOptions inner = q;
    inner.rel_tol = 0.1 * q.rel_tol;
    inner.abs_tol = 0.1 * q.abs_tol / (cell.z1 - cell.z0);
    const QuadratureResult p = integrate_2d(
        [&](double z, double phi) { return pdf_at(f, wo, z, phi); }, cell.z0, cell.z1,
        [&](double) { return cell.phi0; }, [&](double) { return cell.phi1; }, q, inner);
    return {p.value, p.converged};
  }
  const double zc = std::clamp(zs, cell.z0, cell.z1);
  const double pc = std::clamp(ps, cell.phi0, cell.phi1);
  CellIntegral total;
  for (double zf : {cell.z0, cell.z1}) {
    for (double pf : {cell.phi0, cell.phi1}) {
      if (std::abs(zf - zc) <= snap || std::abs(pf - pc) <= snap) continue;  // an empty piece
      const CellIntegral piece = corner_singular(f, wo, zc, pc, zf, pf, q);
      total.value += piece.value;
      total.converged = total.converged && piece.converged;
    }
  }
  return total;
}

}  // namespace

double regularized_gamma_p(double a, double x) {
  if (!(a > 0.0) || std::isnan(x)) return std::numeric_limits<double>::quiet_NaN();
  if (x <= 0.0) return 0.0;
  if (std::isinf(x)) return 1.0;
  return x < a + 1.0 ? gamma_p_series(a, x) : 1.0 - gamma_q_fraction(a, x);
}

double regularized_gamma_q(double a, double x) {
  if (!(a > 0.0) || std::isnan(x)) return std::numeric_limits<double>::quiet_NaN();
  if (x <= 0.0) return 1.0;
  if (std::isinf(x)) return 0.0;
  return x < a + 1.0 ? 1.0 - gamma_p_series(a, x) : gamma_q_fraction(a, x);
}

double chi_square_p_value(double statistic, double dof) {
  if (!(dof > 0.0)) return 1.0;  // nothing to test
  return regularized_gamma_q(0.5 * dof, 0.5 * statistic);  // upper tail of chi^2_dof
}

double sidak_significance(double alpha, int tests) {
  if (tests <= 1) return alpha;
  return -std::expm1(std::log1p(-alpha) / tests);  // 1 - (1 - alpha)^(1/k) (Sidak 1967)
}

ChiSquareResult chi_square_test(const Brdf& f, const Vec3& wo, const ChiSquareOptions& options) {
  ChiSquareResult r;
  r.rows = std::max(2, options.cos_theta_bins);
  r.lower_pooled = !f.pdf_smooth_below_horizon();
  if (r.lower_pooled) r.rows += r.rows % 2;  // the horizon must be a row boundary
  r.cols = std::max(1, options.phi_bins);
  const std::size_t cells = static_cast<std::size_t>(r.rows) * static_cast<std::size_t>(r.cols);
  r.observed.assign(cells, 0.0);
  r.expected.assign(cells, 0.0);
  r.samples = options.samples;

  // Observed counts.
  Pcg32 rng(options.seed, 0x6368693273717561ULL);
  for (std::uint64_t i = 0; i < options.samples; ++i) {
    const Vec2 u{rng.next_double(), rng.next_double()};
    const double u_lobe = rng.next_double();
    const Vec3 wi = f.sample(wo, u, u_lobe).wi;
    if (!is_finite(wi)) {
      ++r.invalid_samples;
      continue;
    }
    const double z = std::clamp(wi.z, -1.0, 1.0);
    const int row = std::min(r.rows - 1, static_cast<int>((z + 1.0) * 0.5 * r.rows));
    const int col = std::min(r.cols - 1, static_cast<int>(azimuth(wi) * inv_two_pi * r.cols));
    r.observed[static_cast<std::size_t>(row) * r.cols + col] += 1.0;
  }

  // Expected counts: N times the integral of the pdf over each cell, d(omega) = dz dphi. With the lower
  // hemisphere pooled, its cells are not integrated: together they expect N minus the upper cells' total.
  const double n = static_cast<double>(options.samples);
  QuadratureOptions q;
  q.rel_tol = options.cell_rel_tol;
  q.abs_tol = n > 0.0 ? 1e-2 / n : 0.0;  // 0.01 counts per cell
  q.initial_intervals = 2;
  q.max_subdivisions = 200;
  r.integration_converged = true;
  const double z_s = -wo.z;
  const double phi_s = azimuth(-wo);
  const int first_row = r.lower_pooled ? r.rows / 2 : 0;
  for (int row = first_row; row < r.rows; ++row) {
    const double z0 = -1.0 + 2.0 * row / r.rows;
    const double z1 = -1.0 + 2.0 * (row + 1) / r.rows;
    for (int col = 0; col < r.cols; ++col) {
      const double phi0 = two_pi * col / r.cols;
      const double phi1 = two_pi * (col + 1) / r.cols;
      const CellIntegral c = cell_integral(f, wo, {z0, z1, phi0, phi1}, {z_s, phi_s}, q);
      r.integration_converged = r.integration_converged && c.converged;
      r.expected[static_cast<std::size_t>(row) * r.cols + col] = n * c.value;
    }
  }
  r.expected_total = std::accumulate(r.expected.begin(), r.expected.end(), 0.0);

  // The bins of the test: every cell, or the upper cells and one bin for the whole lower hemisphere.
  std::vector<std::pair<double, double>> bins;  // (observed, expected)
  if (r.lower_pooled) {
    const std::size_t lower_cells = static_cast<std::size_t>(first_row) * static_cast<std::size_t>(r.cols);
    const double lower_observed = std::accumulate(r.observed.begin(), r.observed.begin() + static_cast<std::ptrdiff_t>(lower_cells), 0.0);
    r.lower_expected = std::max(0.0, n - r.expected_total);
    bins.emplace_back(lower_observed, r.lower_expected);
    for (std::size_t k = lower_cells; k < cells; ++k) bins.emplace_back(r.observed[k], r.expected[k]);
    r.expected_total += r.lower_expected;
  } else {
    for (std::size_t k = 0; k < cells; ++k) bins.emplace_back(r.observed[k], r.expected[k]);
  }

  // Pool bins in increasing order of expectation into groups of at least min_expected.
  std::vector<std::size_t> order(bins.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return bins[a].second < bins[b].second; });
  std::vector<std::pair<double, double>> groups;  // (observed, expected)
  double acc_o = 0.0;
  double acc_e = 0.0;
  int acc_cells = 0;
  for (std::size_t idx : order) {
    const double e = bins[idx].second;
    const double o = bins[idx].first;
    if (e <= 0.0) {
      if (o > 0.0) r.unexpected_samples += static_cast<std::uint64_t>(o);
      continue;
    }
    acc_o += o;
    acc_e += e;
    ++acc_cells;
    if (acc_e >= options.min_expected) {
      if (acc_cells > 1) r.pooled_cells += acc_cells;
      groups.emplace_back(acc_o, acc_e);
      acc_o = acc_e = 0.0;
      acc_cells = 0;
    }
  }
  if (acc_cells > 0) {
    r.pooled_cells += acc_cells;
    if (groups.empty()) {
      groups.emplace_back(acc_o, acc_e);
    } else {
      groups.back().first += acc_o;
      groups.back().second += acc_e;
    }
  }
  for (const auto& [o, e] : groups) r.statistic += (o - e) * (o - e) / e;  // Pearson's statistic
  r.degrees_of_freedom = std::max(0, static_cast<int>(groups.size()) - 1);
  r.p_value = chi_square_p_value(r.statistic, r.degrees_of_freedom);
  if (r.invalid_samples > 0 || r.unexpected_samples > 0) r.p_value = 0.0;
  return r;
}

SampleConsistency sample_consistency(const Brdf& f, const Vec3& wo, std::uint64_t count, std::uint64_t seed) {
  SampleConsistency c;
  c.samples = count;
  Pcg32 rng(seed, 0x636f6e73697374ULL);
  constexpr double weight_floor = 1e-12;  // weights are O(albedo); below this a difference is immaterial
  for (std::uint64_t i = 0; i < count; ++i) {
    const Vec2 u{rng.next_double(), rng.next_double()};
    const double u_lobe = rng.next_double();
    const BrdfSample s = f.sample(wo, u, u_lobe);
    if (!is_finite(s.wi) || !std::isfinite(s.pdf) || !is_finite(s.weight)) {
      ++c.non_finite;
      continue;
    }
    if (s.pdf == 0.0) {
      ++c.zero_pdf;
      continue;
    }
    const double p = f.pdf(s.wi, wo);
    const double pdf_scale = std::max(std::abs(p), std::abs(s.pdf));
    const double pdf_err = std::abs(s.pdf - p) / pdf_scale;  // relative, pdf_scale > 0 here
    if (pdf_err > c.max_pdf_error) {
      c.max_pdf_error = pdf_err;
      c.worst_pdf_wi = s.wi;
    }
    if (s.wi.z <= 0.0) {
      ++c.below_horizon;
      if (!s.weight.is_black()) ++c.nonzero_weight_below_horizon;
      continue;
    }
    const Rgb expected = p > 0.0 ? f.eval(s.wi, wo) * (s.wi.z / p) : Rgb{};  // f cos / pdf
    for (int k = 0; k < 3; ++k) {
      const double scale = std::max({std::abs(expected[k]), std::abs(s.weight[k]), weight_floor});
      const double err = std::abs(s.weight[k] - expected[k]) / scale;
      if (!(err <= c.max_weight_error)) {
        c.max_weight_error = std::isnan(err) ? std::numeric_limits<double>::infinity() : err;
        c.worst_weight_wi = s.wi;
      }
    }
  }
  return c;
}

double sampled_share_below_horizon(const Brdf& f, const Vec3& wo, std::uint64_t count, std::uint64_t seed) {
  Pcg32 rng(seed, 0x62656c6f77ULL);
  std::uint64_t below = 0;
  for (std::uint64_t i = 0; i < count; ++i) {
    const Vec2 u{rng.next_double(), rng.next_double()};
    const double u_lobe = rng.next_double();
    if (f.sample(wo, u, u_lobe).wi.z <= 0.0) ++below;
  }
  return count > 0 ? static_cast<double>(below) / static_cast<double>(count) : 0.0;
}

WeightMean weight_mean(const Brdf& f, const Vec3& wo, std::uint64_t count, std::uint64_t seed) {
  WeightMean m;
  m.samples = count;
  m.albedo = directional_albedo(f, wo).albedo;
  Pcg32 rng(seed, 0x6d65616eULL);
  Rgb sum;
  Rgb sum2;
  for (std::uint64_t i = 0; i < count; ++i) {
    const Vec2 u{rng.next_double(), rng.next_double()};
    const double u_lobe = rng.next_double();
    const Rgb w = f.sample(wo, u, u_lobe).weight;
    if (!is_finite(w)) continue;  // counted by sample_consistency
    sum += w;
    sum2 += w * w;
  }
  const double n = static_cast<double>(std::max<std::uint64_t>(count, 1));
  m.mean = sum / n;
  double se_c[3];
  for (int c = 0; c < 3; ++c) {
    const double var = std::max(0.0, sum2[c] / n - m.mean[c] * m.mean[c]) * n / std::max(1.0, n - 1.0);
    const double se = std::sqrt(var / n);
    se_c[c] = se;
    // The albedo's quadrature is accurate to ~1e-8 relative (albedo.h); that floor keeps a zero-variance
    // weight (Lambert: every weight is kd) from turning rounding into a large z.
    const double scale = std::sqrt(se * se + std::pow(1e-7 * std::abs(m.albedo[c]), 2.0)) + 1e-300;
    m.max_z = std::max(m.max_z, std::abs(m.mean[c] - m.albedo[c]) / scale);
  }
  m.standard_error = {se_c[0], se_c[1], se_c[2]};
  return m;
}

namespace {

// The midpoint sum of f.pdf over the sphere on n x n cells in (phi - phi_o, z = cos theta), dw = dphi dz.
double pdf_midpoint_sum(const Brdf& f, const Vec3& wo, int n) {
  const double phi_o = std::atan2(wo.y, wo.x);
  double sum = 0.0;
  for (int j = 0; j < n; ++j) {
    const double z = -1.0 + 2.0 * (j + 0.5) / n;
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int i = 0; i < n; ++i) {
      const double phi = phi_o + 2.0 * pi * (i + 0.5) / n;
      sum += f.pdf({s * std::cos(phi), s * std::sin(phi), z}, wo);
    }
  }
  return sum * (2.0 / n) * (2.0 * pi / n);
}

}  // namespace

QuadratureResult pdf_integral(const Brdf& f, const Vec3& wo, const QuadratureOptions& options) {
  if (f.is_tabulated()) {
    const double fine = pdf_midpoint_sum(f, wo, 1024), coarse = pdf_midpoint_sum(f, wo, 512);
    return {fine, std::abs(fine - coarse), 1024 * 1024 + 512 * 512, 0, std::isfinite(fine)};
  }
  // The upper half about the pdf's peak there. The lower half about -wo, where every sampler that reflects
  // wo about a sampled half vector h has an integrable singularity (the Jacobian 1 / (4 |wo.h|) with wo.h -> 0),
  // which polar coordinates about it smooth out; unless a genuine lobe peaks below the horizon.
  const Vec3 upper = lobe_peak(f, wo, LobeQuantity::pdf_upper);
  const Vec3 lower_peak = lobe_peak(f, wo, LobeQuantity::pdf_lower);
  const Vec3 near_antipode = Frame::from_normal(-wo).to_world(spherical_direction(std::sin(1e-3), std::cos(1e-3), 0.0));
  // A peak search that climbed into the singularity stops near -wo but not on it; -wo itself is the centre.
  const bool genuine_lobe = f.pdf(lower_peak, wo) > 10.0 * f.pdf(near_antipode, wo) && dot(lower_peak, -wo) < std::cos(0.05);
  const Vec3 lower = genuine_lobe ? lower_peak : -wo;
  if (!f.pdf_smooth_below_horizon()) {
    // The upper half by quadrature; the mass below the horizon as the sampler's share of samples there, with
    // its binomial standard error in the result's error.
    const VectorQuadratureResult up = integrate_directions(
        [&](const Vec3& wi, std::span<double> out) { out[0] = f.pdf(wi, wo); }, 1, upper.z > 0.0 ? upper : Vec3{0, 0, 1},
        SphereRegion::upper, options);
    const std::uint64_t n = pdf_integral_lower_samples_for(f);
    const double share = sampled_share_below_horizon(f, wo, n);
    const double se = std::sqrt(share * (1.0 - share) / static_cast<double>(n));
    return {up.value[0] + share, up.error[0] + se, up.evaluations, up.subdivisions, up.converged};
  }
  const VectorQuadratureResult q = integrate_sphere(
      [&](const Vec3& wi, std::span<double> out) { out[0] = f.pdf(wi, wo); }, 1, upper.z > 0.0 ? upper : Vec3{0, 0, 1},
      lower, options);
  return {q.value[0], q.error[0], q.evaluations, q.subdivisions, q.converged};
}

}  // namespace shadelab
