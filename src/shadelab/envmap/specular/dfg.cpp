// shadelab DFG table (dfg.h): the split-sum scale A and bias B of the height-correlated Smith GGX model.
#include "shadelab/envmap/specular/dfg.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "shadelab/core/constants.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/numeric/quadrature.h"
#include "shadelab/sampling/sobol.h"

namespace shadelab {
namespace {

struct Integrand {
  Vec3 v;
  double mu = 1.0;
  double alpha = 1.0;

  // The half vector at GGX sampling variable xi and azimuth phi: tan(theta_h) = alpha sqrt(xi / (1 - xi))
  // (Walter et al. 2007 eq. 35, solved for theta_h), so that D cos(theta_h) d(omega_h) = d(xi) d(phi)/(2 pi).
  Vec3 half_vector(double xi, double phi) const { return half_vector_tan(alpha * std::sqrt(xi / (1.0 - xi)), phi); }
  Vec3 half_vector_tan(double t, double phi) const {
    const double c = 1.0 / std::sqrt(1.0 + t * t);
    const double s = t * c;
    return {s * std::cos(phi), s * std::sin(phi), c};
  }

  // The horizon of l = reflect(-v, h) for h at azimuth phi: l.z > 0 <=> theta_h < (delta + pi/2) / 2 with
  // delta = atan2(sin(theta_v) cos(phi), cos(theta_v)) (l.z = 2 (V.H) N.H - N.V = R cos(2 theta_h - delta)),
  // as u = -ln(1 - xi) = ln(1 + tan^2 / alpha^2) (the quadratures' variable).
  double u_max(double phi) const {
    const double theta = 0.5 * (std::atan2(v.x * std::cos(phi), mu) + 0.5 * pi);
    const double t = std::tan(theta) / alpha;
    return std::log1p(t * t);
  }

  // G2 (V.H) / (N.V N.H) times (1 - Fc, Fc): the integrand of A and B in the (xi, phi) measure (Karis 2013
  // eq. 8 written for the height-correlated G2). Zero where the mirrored l is below the horizon.
  void eval(const Vec3& h, double& a, double& b) const {
    const double vh = dot(v, h);
    const Vec3 l = 2.0 * vh * h - v;  // reflect(-v, h)
    a = 0.0;
    b = 0.0;
    if (l.z <= 0.0 || vh <= 0.0) return;
    const double g = kernel::G2_ggx_correlated(v, l, alpha, alpha) * vh / (mu * h.z);
    const double fc = kernel::F_schlick(vh, 0.0);  // Schlick 1994: F = F0 + (1 - F0) (1 - V.H)^5 at F0 = 0 (fresnel.sl)
    a = (1.0 - fc) * g;
    b = fc * g;
  }
};

Integrand make_integrand(double mu, double alpha) {
  Integrand f;
  f.mu = mu;
  f.alpha = alpha;
  f.v = {std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu};
  return f;
}

}  // namespace

DfgValue dfg_quadrature(double mu, double alpha, double tolerance) {
  const Integrand f = make_integrand(mu, alpha);
  const auto u_max = [&](double phi) { return f.u_max(phi); };
  QuadratureOptions options;
  options.rel_tol = 0.0;
  options.abs_tol = 0.5 * tolerance;
  options.initial_intervals = 4;
  options.max_subdivisions = 4000;
  // Each inner integral (over xi at one phi, already divided by pi) adds at most its error times the
  // outer length pi / pi = 1 to the total: a quarter of the tolerance each leaves room for the outer rule.
  QuadratureOptions inner;
  inner.rel_tol = 0.0;
  inner.abs_tol = 0.25 * tolerance;
  inner.max_subdivisions = 4000;
  // phi over [0, pi]: the integrand is even in phi (v lies in the XZ plane), so d(phi)/(2 pi) over the full
  // circle is d(phi)/pi over half of it.
  const VectorQuadratureResult r = integrate_2d_vector(
      [&](double phi, double u, std::span<double> out) {
        // xi = 1 - exp(-u), d(xi) = exp(-u) du: where the lobe is thin (small alpha) all of its shape sits
        // in xi within alpha^2 of 1; in u it is spread over [0, 2 ln(1/alpha)] and smooth.
        // tan(theta_h) = alpha sqrt(xi / (1 - xi)) = alpha sqrt(e^u - 1).
        double a = 0.0;
        double b = 0.0;
        f.eval(f.half_vector_tan(alpha * std::sqrt(std::expm1(u)), phi), a, b);
        const double w = std::exp(-u) * inv_pi;
        out[0] = a * w;
        out[1] = b * w;
      },
      2, 0.0, pi, [](double) { return 0.0; }, u_max, options, inner);
  DfgValue value;
  value.a = r.value[0];
  value.b = r.value[1];
  value.error = std::max(r.error[0], r.error[1]);
  value.evaluations = r.evaluations;
  return value;
}

DfgLobeMoments dfg_lobe_moments(double mu, double alpha, double rel_tol) {
  const Integrand f = make_integrand(mu, alpha);
  // The same variables and horizon bound as dfg_quadrature: (phi, u) over [0, pi] (every integrand below is
  // even in phi: l.x and l.z are, l.y is odd and its integral vanishes), u = ln(1 + tan^2(theta_h) / alpha^2).
  const auto u_max = [&](double phi) { return f.u_max(phi); };
  QuadratureOptions options;
  options.rel_tol = rel_tol;
  options.abs_tol = 1e-10;
  options.initial_intervals = 4;
  options.max_subdivisions = 4000;
  QuadratureOptions inner = options;
  inner.initial_intervals = 1;
  // The weight of (a, b) at (phi, u) in the measure dl, and l itself.
  const auto at = [&](double phi, double u, double& a, double& b, Vec3& l) {
    const Vec3 h = f.half_vector_tan(alpha * std::sqrt(std::expm1(u)), phi);
    f.eval(h, a, b);
    const double w = std::exp(-u) * inv_pi;
    a *= w;
    b *= w;
    l = 2.0 * dot(f.v, h) * h - f.v;
  };
  const VectorQuadratureResult first = integrate_2d_vector(
      [&](double phi, double u, std::span<double> out) {
        double a = 0.0, b = 0.0;
        Vec3 l;
        at(phi, u, a, b, l);
        out[0] = a;
        out[1] = b;
        out[2] = a * l.x;
        out[3] = a * l.z;
        out[4] = b * l.x;
        out[5] = b * l.z;
      },
      6, 0.0, pi, [](double) { return 0.0; }, u_max, options, inner);
  DfgLobeMoments m;
  Vec3 d[2];
  for (int k = 0; k < 2; ++k) {
    const double w = first.value[static_cast<std::size_t>(k)];
    m.weight[k] = w;
    const double mx = w > 0.0 ? first.value[static_cast<std::size_t>(2 + 2 * k)] / w : 0.0;
    const double mz = w > 0.0 ? first.value[static_cast<std::size_t>(3 + 2 * k)] / w : 1.0;
    m.angle[k] = std::atan2(-mx, mz);  // R lies at -x
    d[k] = normalize(Vec3{mx, 0.0, mz});
  }
  const VectorQuadratureResult second = integrate_2d_vector(
      [&](double phi, double u, std::span<double> out) {
        double a = 0.0, b = 0.0;
        Vec3 l;
        at(phi, u, a, b, l);
        const Vec3 ea = l - d[0], eb = l - d[1];
        out[0] = a * 0.5 * dot(ea, ea);
        out[1] = b * 0.5 * dot(eb, eb);
      },
      2, 0.0, pi, [](double) { return 0.0; }, u_max, options, inner);
  for (int k = 0; k < 2; ++k)
    m.spread[k] = m.weight[k] > 0.0 ? second.value[static_cast<std::size_t>(k)] / m.weight[k] : 0.0;
  return m;
}

DfgValue dfg_sampled(double mu, double alpha, int samples) {
  const Integrand f = make_integrand(mu, alpha);
  double a_sum = 0.0;
  double b_sum = 0.0;
  for (int i = 0; i < samples; ++i) {
    // Hammersley point (i + 1/2)/N, radical_inverse(i) (Karis 2013, "Hammersley"), mapped through the GGX
    // sampling of D cos(theta_h).
    const double xi = (static_cast<double>(i) + 0.5) / static_cast<double>(samples);
    const double phi = two_pi * radical_inverse(static_cast<std::uint32_t>(i));
    double a = 0.0;
    double b = 0.0;
    f.eval(f.half_vector(xi, phi), a, b);
    a_sum += a;
    b_sum += b;
  }
  DfgValue value;
  value.a = a_sum / static_cast<double>(samples);
  value.b = b_sum / static_cast<double>(samples);
  value.evaluations = samples;
  return value;
}

DfgTable bake_dfg(const DfgOptions& options) {
  if (options.size < 1 || options.size > 4096)
    throw std::invalid_argument("--size must be in [1, 4096], got " + std::to_string(options.size));
  if (options.samples < 0 || options.samples > (1 << 24))
    throw std::invalid_argument("--samples must be in [0, 16777216], got " + std::to_string(options.samples));
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    throw std::invalid_argument("the DFG tolerance must be a positive number");
  DfgTable table;
  table.size = options.size;
  table.multiscatter = options.multiscatter;
  const auto n = static_cast<std::size_t>(options.size);
  table.texels.assign(n * n * 3, 0.0);
  std::vector<double> errors(n * n, 0.0);
  std::vector<std::int64_t> evaluations(n * n, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, options.size * options.size), [&](const tbb::blocked_range<int>& r) {
    for (int k = r.begin(); k != r.end(); ++k) {
      const int i = k % options.size;  // column: N.V
      const int j = k / options.size;  // row: perceptual roughness
      const double mu = (i + 0.5) / options.size;
      const double rough = (j + 0.5) / options.size;
      const double alpha = rough * rough;  // alpha = perceptual roughness squared (Burley 2012; Karis 2013)
      const DfgValue v = options.samples > 0 ? dfg_sampled(mu, alpha, options.samples)
                                             : dfg_quadrature(mu, alpha, options.tolerance);
      double* t = &table.texels[static_cast<std::size_t>(k) * 3];
      t[0] = v.a;
      t[1] = v.b;
      t[2] = options.multiscatter ? v.a + v.b : 0.0;
      errors[static_cast<std::size_t>(k)] = v.error;
      evaluations[static_cast<std::size_t>(k)] = v.evaluations;
    }
  });
  for (std::size_t k = 0; k < n * n; ++k) {
    table.max_error_estimate = std::max(table.max_error_estimate, errors[k]);
    table.evaluations += evaluations[k];
  }
  return table;
}

TexelLerp texel_lerp(double x, int n) {
  // Texel i's centre is at (i + 0.5) / n: the continuous texel coordinate is x n - 0.5, clamped to the edges.
  const double p = std::clamp((std::isfinite(x) ? x : 0.0) * n - 0.5, 0.0, static_cast<double>(n - 1));
  TexelLerp out;
  out.i0 = std::min(static_cast<int>(p), n - 1);
  out.i1 = std::min(out.i0 + 1, n - 1);
  out.t = p - out.i0;
  return out;
}

DfgAb dfg_lookup(const DfgTable& table, double mu, double roughness) {
  if (table.size < 1) return {};
  const kernel::IblTexels texels{nullptr, 0, table.texels.data(), table.size};
  const kernel::IblBinding bind(texels);
  const kernel::DfgScaleBias ab = kernel::dfg_read(std::isfinite(mu) ? mu : 0.0, std::isfinite(roughness) ? roughness : 0.0, table.size);
  return {ab.a, ab.b};
}

}  // namespace shadelab
