// shadelab DFG table (dfg.h): the split-sum scale A and bias B of the height-correlated Smith GGX model.
#include "shadelab/envmap/specular/dfg.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <span>
#include <vector>
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

// Smith's Lambda of the view direction v = (sqrt(1 - mu^2), 0, mu) (microfacet.sl lambda_ggx).
double lambda_of_view(double mu, double alpha) {
  return kernel::lambda_ggx(Vec3{std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu}, alpha, alpha);
}

// The fixed product rule of dfg_gauss (dfg.h): the same integrand in the same measure, d(xi) d(phi) / (2 pi) over
// the half vector, written in variables where it is smooth, each on panels whose ends are its features:
// - phi in [0, pi] (the integrand is even in phi): the view's azimuth plane is phi = 0. At grazing view the
//   integrand and the horizon bound change across cos(phi) = 0 on the scale eps = N.V / sin(theta_v) (v.h and
//   the horizon angle delta both depend on phi through sin(theta_v) cos(phi) / N.V), so the middle third,
//   x = cos(phi) in [-1/2, 1/2], is integrated in tau with x = eps sinh(tau) (tan(delta) = sinh(tau)), and
//   the outer thirds, phi in [0, pi/3] and [2 pi/3, pi], in phi.
// - along each phi, w = sqrt(u), u = -ln(1 - xi) = ln(1 + tan^2(theta_h) / alpha^2): d(xi) = 2 w e^(-w^2) dw,
//   smooth at w = 0 (in u the half vector moves as sqrt(u) there) and spreading a thin lobe over w in [0, 3].
//   Panels: [0, min(w_h, core_end)] (the lobe's core), [core_end, w_h] (its tail), [w_h, w_max] (the horizon
//   layer), w_max at l.z = 0 and w_h at l.z = horizon_layer alpha: near the horizon G2 falls to 0 over l.z of
//   order alpha (Lambda(l) = (sqrt(1 + alpha^2 (1 - l.z^2) / l.z^2) - 1) / 2), a feature of its own.
// visit(panel) is called once per w panel with its nodes: weight (the rule's weight times d(xi) d(phi) / pi, phi
// over [0, pi] standing for the whole circle, so that sum weight * integrand is the integral as dfg_quadrature
// defines it), the half vector h = (sz cphi, sz sphi, cz) through cz, sz (cphi, sphi per panel), v.h and l.z.
// A node whose l.z is not positive (only by rounding at w_max) has weight 0 and l.z 0. Returns the number of
// nodes. The arrays let the callers' per-node arithmetic vectorize.
constexpr int max_panel_nodes = 64;
struct GaussPanel {
  int n = 0;
  double cphi = 1.0, sphi = 0.0;
  double weight[max_panel_nodes];
  double cz[max_panel_nodes];
  double sz[max_panel_nodes];
  double vh[max_panel_nodes];
  double lz[max_panel_nodes];
};

// The height-correlated G2 of v and l from l.z alone: with l a unit vector Lambda(l) = (sqrt(l.z^2 + alpha^2 (1 -
// l.z^2)) / l.z - 1) / 2 (Heitz 2014 eq. 72 with tan^2 = (1 - l.z^2) / l.z^2), so G2 = 1 / (1 + Lambda(v) +
// Lambda(l)) = l.z / (l.z (1/2 + Lambda(v)) + sqrt(l.z^2 + alpha^2 (1 - l.z^2)) / 2) (Heitz 2014 eq. 99): one
// square root where the kernel takes two. l.z = 0 gives 0: the horizon.
inline double smith_g2_correlated_of_lz(double lz, double alpha, double lambda_v) {
  return lz / (lz * (0.5 + lambda_v) + 0.5 * std::sqrt(lz * lz + alpha * alpha * (1.0 - lz * lz)));
}

void check_gauss_rule(const DfgGaussRule& r) {
  for (const int n : {r.phi_outer, r.phi_middle, r.w_core, r.w_tail, r.w_horizon}) {
    if (n < 1 || n > max_panel_nodes) throw std::invalid_argument("DfgGaussRule: node counts must be in [1, 64]");
  }
  if (!(r.core_end > 0.0) || !(r.horizon_layer > 0.0) || !(r.phi_middle_per_tau >= 0.0)) {
    throw std::invalid_argument("DfgGaussRule: core_end, horizon_layer and phi_middle_per_tau must be positive");
  }
}

template <class Visit>
std::int64_t visit_gauss_nodes(double mu, double alpha, const DfgGaussRule& rule, Visit&& visit) {
  const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));  // sin(theta_v); v = (s, 0, mu)
  const double a2 = alpha * alpha;
  std::int64_t count = 0;
  const GaussLegendreRule& core_rule = gauss_legendre_rule(rule.w_core);
  const GaussLegendreRule& tail_rule = gauss_legendre_rule(rule.w_tail);
  const GaussLegendreRule& horizon_rule = gauss_legendre_rule(rule.w_horizon);
  GaussPanel p;
  double e[max_panel_nodes];
  double w[max_panel_nodes];
  // The w panel [w0, w1] of one phi line; line_weight is the phi rule's weight / pi.
  const auto panel = [&](const GaussLegendreRule& r, double w0, double w1, double sx, double line_weight) {
    if (!(w1 > w0)) return;
    const int n = static_cast<int>(r.nodes.size());
    const double half = 0.5 * (w1 - w0);
    for (int k = 0; k < n; ++k) {
      w[k] = w0 + half * (r.nodes[static_cast<std::size_t>(k)] + 1.0);
      e[k] = std::expm1(w[k] * w[k]);  // e^u - 1 = tan^2(theta_h) / alpha^2
    }
    for (int k = 0; k < n; ++k) {
      const double sec = std::sqrt(1.0 + a2 * e[k]);  // 1 / cos(theta_h) = sqrt(1 + tan^2)
      const double cz = 1.0 / sec;
      const double sz = std::sqrt(a2 * e[k]) * cz;  // sin(theta_h) = tan cos
      const double vh = sz * sx + mu * cz;           // v.h, v = (s, 0, mu), h = (sz cphi, sz sphi, cz)
      const double lz = 2.0 * vh * cz - mu;          // l = 2 (v.h) h - v
      const bool above = lz > 0.0 && vh > 0.0;
      // d(xi) = e^(-u) du = 2 w dw / (1 + e): the measure of the GGX sampling variable.
      p.weight[k] = above ? line_weight * half * r.weights[static_cast<std::size_t>(k)] * 2.0 * w[k] / (1.0 + e[k]) : 0.0;
      p.cz[k] = cz;
      p.sz[k] = sz;
      p.vh[k] = vh;
      p.lz[k] = above ? lz : 0.0;
    }
    p.n = n;
    count += n;
    visit(static_cast<const GaussPanel&>(p));
  };
  // One line of constant phi with the phi rule's weight dphi (already in the phi measure).
  const auto line = [&](double phi, double dphi) {
    const double cphi = std::cos(phi), sphi = std::sin(phi);
    const double sx = s * cphi;
    p.cphi = cphi;
    p.sphi = sphi;
    // l.z = R cos(2 theta_h - delta), R = sqrt(sx^2 + mu^2), tan(delta) = sx / mu (l.z = sx sin(2 theta_h) + mu
    // cos(2 theta_h)): the horizon at theta_h = (delta + pi/2) / 2, l.z = c at (delta + acos(c / R)) / 2.
    const double big_r = std::sqrt(sx * sx + mu * mu);
    const double delta = std::atan2(sx, mu);
    const auto w_at = [&](double theta) {  // w = sqrt(ln(1 + tan^2(theta_h) / alpha^2))
      const double t = std::tan(theta) / alpha;
      return std::sqrt(std::log1p(t * t));
    };
    const double w_max = w_at(0.5 * (delta + 0.5 * pi));
    const double c = rule.horizon_layer * alpha;
    const double theta_h = c < big_r ? 0.5 * (delta + std::acos(c / big_r)) : 0.0;
    // (A line whose l.z stays below c everywhere, theta_h <= 0, has no layer of its own: its core and tail
    // panels reach the horizon.)
    const double w_h = theta_h > 0.0 ? std::min(w_at(theta_h), w_max) : w_max;
    const double w_core = std::min(w_h, rule.core_end);
    const double line_weight = dphi * inv_pi;  // d(phi) / pi: phi over [0, pi] stands for the full circle
    panel(core_rule, 0.0, w_core, sx, line_weight);
    panel(tail_rule, w_core, w_h, sx, line_weight);
    panel(horizon_rule, w_h, w_max, sx, line_weight);
  };
  const GaussLegendreRule& outer = gauss_legendre_rule(rule.phi_outer);
  for (int i = 0; i < rule.phi_outer; ++i) {
    const double x = outer.nodes[static_cast<std::size_t>(i)], wt = outer.weights[static_cast<std::size_t>(i)];
    line(pi / 6.0 * (x + 1.0), pi / 6.0 * wt);                 // phi in [0, pi/3]
    line(2.0 * pi / 3.0 + pi / 6.0 * (x + 1.0), pi / 6.0 * wt);  // phi in [2 pi/3, pi]
  }
  // cos(phi) = x = eps sinh(tau) over x in [-1/2, 1/2]: d(phi) = eps cosh(tau) d(tau) / sqrt(1 - x^2).
  const double eps = mu / std::max(s, 1e-300);
  const double tau_end = std::asinh(0.5 / eps);
  // The integrand's features are of unit scale in tau, and tau_end grows as ln(1 / eps): nodes in proportion.
  const int n_middle = std::clamp(static_cast<int>(std::ceil(rule.phi_middle_per_tau * tau_end)), rule.phi_middle, max_panel_nodes);
  const GaussLegendreRule& middle = gauss_legendre_rule(n_middle);
  for (int i = 0; i < n_middle; ++i) {
    const double tau = tau_end * middle.nodes[static_cast<std::size_t>(i)];
    const double x = eps * std::sinh(tau);
    line(std::acos(x), tau_end * middle.weights[static_cast<std::size_t>(i)] * eps * std::cosh(tau) / std::sqrt(1.0 - x * x));
  }
  return count;
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

DfgValue dfg_gauss(double mu, double alpha, const DfgGaussRule& rule) {
  check_gauss_rule(rule);
  const double lambda_v = lambda_of_view(mu, alpha);
  double a = 0.0, b = 0.0;
  double ga[max_panel_nodes], gb[max_panel_nodes];
  const std::int64_t n = visit_gauss_nodes(mu, alpha, rule, [&](const GaussPanel& p) {
    for (int k = 0; k < p.n; ++k) {
      // G2 (V.H) / (N.V N.H) (1 - Fc, Fc): the integrand of A and B in the (xi, phi) measure (Integrand::eval).
      const double g = p.weight[k] * smith_g2_correlated_of_lz(p.lz[k], alpha, lambda_v) * p.vh[k] / (mu * p.cz[k]);
      const double fc = kernel::F_schlick(p.vh[k], 0.0);  // Schlick 1994: (1 - V.H)^5 at F0 = 0 (fresnel.sl)
      ga[k] = (1.0 - fc) * g;
      gb[k] = fc * g;
    }
    for (int k = 0; k < p.n; ++k) {
      a += ga[k];
      b += gb[k];
    }
  });
  DfgValue value;
  value.a = a;
  value.b = b;
  value.evaluations = n;
  return value;
}

DfgLobeMoments dfg_lobe_moments(double mu, double alpha, double rel_tol, double abs_tol) {
  const Integrand f = make_integrand(mu, alpha);
  // The same variables and horizon bound as dfg_quadrature: (phi, u) over [0, pi] (every integrand below is
  // even in phi: l.x and l.z are, l.y is odd and its integral vanishes), u = ln(1 + tan^2(theta_h) / alpha^2).
  const auto u_max = [&](double phi) { return f.u_max(phi); };
  QuadratureOptions options;
  options.rel_tol = rel_tol;
  options.abs_tol = abs_tol;
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

DfgGaussRule dfg_gauss_check_rule() {
  const DfgGaussRule r;
  DfgGaussRule fine = r;
  fine.phi_outer = r.phi_outer * 3 / 2;
  fine.phi_middle = r.phi_middle * 3 / 2;
  fine.phi_middle_per_tau = r.phi_middle_per_tau * 1.5;
  fine.w_core = r.w_core * 3 / 2;
  fine.w_tail = r.w_tail * 3 / 2;
  fine.w_horizon = r.w_horizon * 3 / 2;
  return fine;
}

DfgLobeMoments dfg_lobe_moments_gauss(double mu, double alpha, const DfgGaussRule& rule) {
  check_gauss_rule(rule);
  const double lambda_v = lambda_of_view(mu, alpha);
  const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  // Each node's weights of A and B (in the measure dl, as dfg_lobe_moments' at()) and its l, kept for the second
  // pass, which sums over the same nodes.
  struct Node {
    double wa, wb;
    Vec3 l;
  };
  std::vector<Node> nodes;
  nodes.reserve(1024);
  visit_gauss_nodes(mu, alpha, rule, [&](const GaussPanel& p) {
    for (int k = 0; k < p.n; ++k) {
      if (!(p.weight[k] > 0.0)) continue;
      const double g = p.weight[k] * smith_g2_correlated_of_lz(p.lz[k], alpha, lambda_v) * p.vh[k] / (mu * p.cz[k]);
      const double fc = kernel::F_schlick(p.vh[k], 0.0);  // Schlick 1994 at F0 = 0 (fresnel.sl)
      // l = 2 (v.h) h - v with h = (sz cphi, sz sphi, cz), v = (s, 0, mu).
      const Vec3 l{2.0 * p.vh[k] * p.sz[k] * p.cphi - s, 2.0 * p.vh[k] * p.sz[k] * p.sphi, p.lz[k]};
      nodes.push_back({(1.0 - fc) * g, fc * g, l});
    }
  });
  // The same quantities as dfg_lobe_moments, over the nodes: weights, mean directions (l.y's integral vanishes
  // by symmetry), then the spreads 1 - |m_k| = integral w_k |l - d_k|^2 / 2 / integral w_k.
  double first[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  for (const Node& n : nodes) {
    first[0] += n.wa;
    first[1] += n.wb;
    first[2] += n.wa * n.l.x;
    first[3] += n.wa * n.l.z;
    first[4] += n.wb * n.l.x;
    first[5] += n.wb * n.l.z;
  }
  DfgLobeMoments m;
  Vec3 d[2];
  for (int k = 0; k < 2; ++k) {
    const double w = first[k];
    m.weight[k] = w;
    const double mx = w > 0.0 ? first[2 + 2 * k] / w : 0.0;
    const double mz = w > 0.0 ? first[3 + 2 * k] / w : 1.0;
    m.angle[k] = std::atan2(-mx, mz);  // R lies at -x
    d[k] = normalize(Vec3{mx, 0.0, mz});
  }
  double second[2] = {0.0, 0.0};
  for (const Node& n : nodes) {
    const Vec3 ea = n.l - d[0], eb = n.l - d[1];
    second[0] += n.wa * 0.5 * dot(ea, ea);  // 1 - l.d = |l - d|^2 / 2 for unit l and d
    second[1] += n.wb * 0.5 * dot(eb, eb);
  }
  for (int k = 0; k < 2; ++k) m.spread[k] = m.weight[k] > 0.0 ? second[k] / m.weight[k] : 0.0;
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
                         : options.adaptive  ? dfg_quadrature(mu, alpha, options.tolerance)
                                             : dfg_gauss(mu, alpha);
      double* t = &table.texels[static_cast<std::size_t>(k) * 3];
      t[0] = v.a;
      t[1] = v.b;
      t[2] = options.multiscatter ? v.a + v.b : 0.0;
      errors[static_cast<std::size_t>(k)] = v.error;
      evaluations[static_cast<std::size_t>(k)] = v.evaluations;
    }
  });
  if (options.samples == 0 && !options.adaptive) {
    // The fixed rule has no error estimate of its own: its difference to the finer rule (dfg_gauss_check_rule,
    // 1.5 times the nodes in every direction, itself within 4e-8 of the adaptive quadrature wherever tried) at
    // the texels of the first two and the last columns and rows, where the rule's error is largest (grazing view,
    // the smoothest and roughest rows), and of every 8th column and row (docs/envmap.md).
    const auto edge = [&](int i) { return i < 2 || i == options.size - 1; };
    std::vector<std::size_t> subset;
    for (int j = 0; j < options.size; ++j) {
      for (int i = 0; i < options.size; ++i) {
        if (edge(i) || edge(j) || (i % 8 == 0 && j % 8 == 0)) subset.push_back(static_cast<std::size_t>(j) * n + static_cast<std::size_t>(i));
      }
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, subset.size()), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t q = r.begin(); q != r.end(); ++q) {
        const std::size_t k = subset[q];
        const double rough = (static_cast<double>(k / n) + 0.5) / options.size;
        const DfgValue fine = dfg_gauss((static_cast<double>(k % n) + 0.5) / options.size, rough * rough, dfg_gauss_check_rule());
        errors[k] = std::max(std::abs(fine.a - table.texels[k * 3]), std::abs(fine.b - table.texels[k * 3 + 1]));
        evaluations[k] += fine.evaluations;
      }
    });
  }
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
