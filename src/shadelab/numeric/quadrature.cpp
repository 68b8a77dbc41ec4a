#include "shadelab/numeric/quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"

namespace shadelab {

namespace {

// Gauss-Kronrod 7/15 abscissae on [-1, 1] (positive half, descending) and weights (Kronrod 1965; the values
// tabulated in QUADPACK's qk15). xgk[1], xgk[3], xgk[5] and 0 are the 7-point Gauss-Legendre nodes.
constexpr std::array<double, 8> xgk = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr std::array<double, 8> wgk = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
// 7-point Gauss-Legendre weights for xgk[1], xgk[3], xgk[5] and the centre.
constexpr std::array<double, 4> wg = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                      0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

constexpr double epsilon = std::numeric_limits<double>::epsilon();
constexpr double min_normal = std::numeric_limits<double>::min();

// One interval's Kronrod estimate and error per component.
struct IntervalEstimate {
  bool finite = true;
};

// Integrates the dim components of f over [a, b] with the G7/K15 pair. scratch holds 15 * dim values.
IntervalEstimate gauss_kronrod_15(const VectorFunction& f, std::size_t dim, double a, double b,
                                  std::span<double> value, std::span<double> error, std::vector<double>& scratch) {
  const double centre = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  scratch.resize(15 * dim);
  // Layout: node 0 = centre, nodes 1 + 2j / 2 + 2j = centre -/+ half xgk[j], j = 0..6.
  f(centre, std::span<double>(scratch.data(), dim));
  for (std::size_t j = 0; j < 7; ++j) {
    const double dx = half * xgk[j];
    f(centre - dx, std::span<double>(scratch.data() + (1 + 2 * j) * dim, dim));
    f(centre + dx, std::span<double>(scratch.data() + (2 + 2 * j) * dim, dim));
  }
  IntervalEstimate estimate;
  for (std::size_t k = 0; k < dim; ++k) {
    const auto at = [&](std::size_t node) { return scratch[node * dim + k]; };
    const double fc = at(0);
    double res_k = wgk[7] * fc;   // Kronrod sum
    double res_g = wg[3] * fc;    // Gauss sum
    double res_abs = std::abs(res_k);
    for (std::size_t j = 0; j < 7; ++j) {
      const double f1 = at(1 + 2 * j);
      const double f2 = at(2 + 2 * j);
      res_k += wgk[j] * (f1 + f2);
      res_abs += wgk[j] * (std::abs(f1) + std::abs(f2));
      if (j % 2 == 1) res_g += wg[j / 2] * (f1 + f2);
    }
    // I_asc: the integral of |f - mean f|, the scale of the error heuristic (QUADPACK qk15).
    const double mean = 0.5 * res_k;
    double res_asc = wgk[7] * std::abs(fc - mean);
    for (std::size_t j = 0; j < 7; ++j) {
      res_asc += wgk[j] * (std::abs(at(1 + 2 * j) - mean) + std::abs(at(2 + 2 * j) - mean));
    }
    const double scale = std::abs(half);
    value[k] = res_k * half;
    res_abs *= scale;
    res_asc *= scale;
    double err = std::abs((res_k - res_g) * half);
    // QUADPACK's error heuristic: err = I_asc min(1, (200 |K - G| / I_asc)^1.5).
    if (res_asc != 0.0 && err != 0.0) err = res_asc * std::min(1.0, std::pow(200.0 * err / res_asc, 1.5));
    // Roundoff floor: the sum of 15 terms cannot be trusted below 50 eps times the integral of |f|.
    if (res_abs > min_normal / (50.0 * epsilon)) err = std::max(50.0 * epsilon * res_abs, err);
    error[k] = err;
    if (!std::isfinite(value[k]) || !std::isfinite(err)) estimate.finite = false;
  }
  return estimate;
}

struct HeapEntry {
  double priority;
  double a;
  double b;
  std::size_t slot;
  bool operator<(const HeapEntry& o) const { return priority < o.priority; }
};

// The adaptive driver. Only the first `controlled` components take part in the stopping rule and the
// ranking of intervals; the rest are integrated along (used for the inner errors of nested integrals).
VectorQuadratureResult adaptive(const VectorFunction& f, std::size_t dim, std::size_t controlled, double a,
                                double b, const QuadratureOptions& options) {
  VectorQuadratureResult result;
  result.value.assign(dim, 0.0);
  result.error.assign(dim, 0.0);
  if (a == b) {
    result.converged = true;
    return result;
  }
  if (b < a) {
    VectorQuadratureResult r = adaptive(f, dim, controlled, b, a, options);
    for (auto& v : r.value) v = -v;
    return r;
  }

  std::vector<double> values;  // slot * dim
  std::vector<double> errors;
  std::vector<HeapEntry> heap;
  std::vector<double> scratch;
  bool finite = true;

  const auto evaluate = [&](double lo, double hi, std::size_t slot) {
    if (values.size() < (slot + 1) * dim) {
      values.resize((slot + 1) * dim);
      errors.resize((slot + 1) * dim);
    }
    std::span<double> v(values.data() + slot * dim, dim);
    std::span<double> e(errors.data() + slot * dim, dim);
    if (!gauss_kronrod_15(f, dim, lo, hi, v, e, scratch).finite) finite = false;
    result.evaluations += 15;
    double priority = 0.0;
    for (std::size_t k = 0; k < controlled; ++k) priority = std::max(priority, e[k]);
    heap.push_back({priority, lo, hi, slot});
    std::push_heap(heap.begin(), heap.end());
  };

  const int pieces = std::max(1, options.initial_intervals);
  std::size_t next_slot = 0;
  for (int i = 0; i < pieces; ++i) {
    const double lo = i == 0 ? a : a + (b - a) * i / pieces;
    const double hi = i + 1 == pieces ? b : a + (b - a) * (i + 1) / pieces;
    evaluate(lo, hi, next_slot++);
  }

  std::vector<double> total(dim);
  std::vector<double> total_error(dim);
  // Slots whose interval was split are recycled: a split interval's slot goes to its left half.
  const auto sum_live = [&] {
    std::fill(total.begin(), total.end(), 0.0);
    std::fill(total_error.begin(), total_error.end(), 0.0);
    for (const auto& entry : heap) {
      for (std::size_t k = 0; k < dim; ++k) {
        total[k] += values[entry.slot * dim + k];
        total_error[k] += errors[entry.slot * dim + k];
      }
    }
  };
  const auto within_tolerance = [&] {
    for (std::size_t k = 0; k < controlled; ++k) {
      if (!(total_error[k] <= std::max(options.abs_tol, options.rel_tol * std::abs(total[k])))) return false;
    }
    return true;
  };

  while (finite) {
    sum_live();
    if (within_tolerance()) {
      result.converged = true;
      break;
    }
    if (result.subdivisions >= options.max_subdivisions) break;
    std::pop_heap(heap.begin(), heap.end());
    const HeapEntry worst = heap.back();
    const double mid = 0.5 * (worst.a + worst.b);
    if (!(worst.a < mid && mid < worst.b)) {
      heap.push_back(worst);  // cannot be split in double precision: the limit of what can be resolved
      std::push_heap(heap.begin(), heap.end());
      break;
    }
    heap.pop_back();
    evaluate(worst.a, mid, worst.slot);
    evaluate(mid, worst.b, next_slot++);
    ++result.subdivisions;
  }
  sum_live();
  result.value = total;
  result.error = total_error;
  if (!finite) result.converged = false;
  return result;
}

QuadratureOptions derived_inner(const QuadratureOptions& outer, double a, double b) {
  QuadratureOptions inner = outer;
  inner.rel_tol = 0.1 * outer.rel_tol;
  inner.abs_tol = outer.abs_tol > 0.0 && b != a ? 0.1 * outer.abs_tol / std::abs(b - a) : 0.0;
  inner.initial_intervals = 1;
  return inner;
}

}  // namespace

VectorQuadratureResult integrate_vector(const VectorFunction& f, std::size_t dim, double a, double b,
                                        const QuadratureOptions& options) {
  return adaptive(f, dim, dim, a, b, options);
}

QuadratureResult integrate(const ScalarFunction& f, double a, double b, const QuadratureOptions& options) {
  const VectorQuadratureResult r = integrate_vector([&f](double x, std::span<double> out) { out[0] = f(x); }, 1, a, b,
                                                    options);
  return {r.value[0], r.error[0], r.evaluations, r.subdivisions, r.converged};
}

namespace {

// Outer adaptive integral of inner adaptive integrals, with the options as given.
VectorQuadratureResult nested(const VectorFunction2d& f, std::size_t dim, double a, double b, const BoundFunction& c,
                              const BoundFunction& d, const QuadratureOptions& options,
                              const QuadratureOptions& inner_options) {
  std::int64_t inner_evaluations = 0;
  bool inner_converged = true;
  // The outer integrand: the inner integral's dim values followed by its dim error estimates.
  const VectorFunction outer = [&](double x, std::span<double> out) {
    const VectorQuadratureResult r = adaptive(
        [&f, x](double y, std::span<double> o) { f(x, y, o); }, dim, dim, c(x), d(x), inner_options);
    inner_evaluations += r.evaluations;
    inner_converged = inner_converged && r.converged;
    for (std::size_t k = 0; k < dim; ++k) {
      out[k] = r.value[k];
      out[dim + k] = r.error[k];
    }
  };
  const VectorQuadratureResult o = adaptive(outer, 2 * dim, dim, a, b, options);
  VectorQuadratureResult result;
  result.value.assign(o.value.begin(), o.value.begin() + static_cast<std::ptrdiff_t>(dim));
  result.error.resize(dim);
  for (std::size_t k = 0; k < dim; ++k) result.error[k] = o.error[k] + std::abs(o.value[dim + k]);
  result.evaluations = inner_evaluations;
  result.subdivisions = o.subdivisions;
  result.converged = o.converged && inner_converged;
  return result;
}

// Cheap, capped options for a first estimate of the integral's size.
QuadratureOptions rough(const QuadratureOptions& options) {
  QuadratureOptions r = options;
  r.rel_tol = std::max(options.rel_tol, 1e-4);
  r.max_subdivisions = std::min(options.max_subdivisions, 50);
  return r;
}

// The smallest non-zero magnitude among the components (0 if all are zero).
double smallest_scale(const std::vector<double>& values) {
  double scale = 0.0;
  for (double v : values) {
    if (v != 0.0 && std::isfinite(v) && (scale == 0.0 || std::abs(v) < scale)) scale = std::abs(v);
  }
  return scale;
}

// Inner options for an outer integral whose absolute target is `target`: the inner integrals need only
// resolve their share of it, target / (10 (b - a)), however small their own value, plus 1/10 of the
// outer relative tolerance of their own value.
QuadratureOptions inner_for(const QuadratureOptions& outer, double target, double a, double b) {
  QuadratureOptions inner = derived_inner(outer, a, b);
  if (b != a) inner.abs_tol = std::max(inner.abs_tol, 0.1 * target / std::abs(b - a));
  return inner;
}

}  // namespace

VectorQuadratureResult integrate_2d_vector(const VectorFunction2d& f, std::size_t dim, double a, double b,
                                           const BoundFunction& c, const BoundFunction& d,
                                           const QuadratureOptions& options,
                                           const std::optional<QuadratureOptions>& inner) {
  if (inner) return nested(f, dim, a, b, c, d, options, *inner);
  // A rough first pass sizes the integral, so that inner integrals along lines where the integrand is
  // negligible (but perhaps singular) are not resolved to a relative accuracy nobody asked for.
  const QuadratureOptions r = rough(options);
  QuadratureOptions r_inner = derived_inner(r, a, b);
  r_inner.max_subdivisions = std::min(r_inner.max_subdivisions, 50);
  const VectorQuadratureResult estimate = nested(f, dim, a, b, c, d, r, r_inner);
  const double target = std::max(options.abs_tol, options.rel_tol * smallest_scale(estimate.value));
  VectorQuadratureResult result = nested(f, dim, a, b, c, d, options, inner_for(options, target, a, b));
  result.evaluations += estimate.evaluations;
  return result;
}

QuadratureResult integrate_2d(const ScalarFunction2d& f, double a, double b, const BoundFunction& c,
                              const BoundFunction& d, const QuadratureOptions& options,
                              const std::optional<QuadratureOptions>& inner) {
  const VectorQuadratureResult r = integrate_2d_vector(
      [&f](double x, double y, std::span<double> out) { out[0] = f(x, y); }, 1, a, b, c, d, options, inner);
  return {r.value[0], r.error[0], r.evaluations, r.subdivisions, r.converged};
}

namespace {

// Polar coordinates (theta', phi') about one axis, split at the horizon.
class PolarCoordinates {
 public:
  PolarCoordinates(const DirectionFunction& g, const Vec3& axis)
      : m_g(g), m_axis(usable_axis(axis)), m_frame(zenith_frame(m_axis)) {}

  // A frame about the axis whose phi' = 0 points along the sphere towards +Z (and phi' = pi towards the
  // horizon): lobes stretched by the reflection Jacobian at grazing angles are long in that vertical plane
  // and very thin across it, and the inner integrals along them peak sharply at phi' = 0 and pi, which are
  // therefore made breakpoints of the outer integral.
  static Frame zenith_frame(const Vec3& c) {
    const Vec3 up = Vec3{0.0, 0.0, 1.0} - c * c.z;
    const double len = length(up);
    if (!(len > 1e-9)) return Frame::from_normal(c);
    Frame f;
    f.n = c;
    f.s = up / len;
    f.t = cross(c, f.s);
    return f;
  }

  // An axis closer to the horizon than |z| = 0.01 is tilted to |z| = 0.01 at the same azimuth: about an axis
  // at height z the horizon bound theta_h(phi) swings from ~z to ~pi - z within ~z radians of phi, a feature
  // the outer integral could not resolve (nor its error estimate see) for z -> 0.
  static Vec3 usable_axis(const Vec3& axis) {
    constexpr double min_z = 0.01;
    const double len = length(axis);
    if (!(len > 0.0) || !is_finite(axis)) return {0.0, 0.0, 1.0};
    const Vec3 a = axis / len;
    if (std::abs(a.z) >= min_z) return a;
    const double horizontal = std::hypot(a.x, a.y);
    const double scale = std::sqrt(1.0 - min_z * min_z) / horizontal;
    return {a.x * scale, a.y * scale, a.z < 0.0 ? -min_z : min_z};
  }

  // The integral over the upper (or lower) hemisphere: outer phi' in [0, 2 pi], inner theta' between the
  // axis (or the antipode) and the horizon. On the axis' side theta' is graded towards the axis,
  // theta' = theta_h expm1(a u) / expm1(a) with u in [0, 1] and a = 12, so that the inner rule's nodes reach
  // from theta_h down to ~1e-7 theta_h, about two per decade: a lobe that is very thin across (at grazing
  // angles its width is ~2 cos(theta_o) times its length) and crosses a ray at a tiny theta' is still seen.
  VectorQuadratureResult half(bool upper, std::size_t dim, const QuadratureOptions& outer,
                              const std::optional<QuadratureOptions>& inner) const {
    constexpr double grading = 12.0;
    const double expm1_grading = std::expm1(grading);
    // Along the great semicircle from the axis at azimuth phi, w.z = A sin(theta) + B cos(theta) with
    // A = cos(phi) s.z + sin(phi) t.z and B = axis.z; it crosses the horizon once, at theta_h in (0, pi).
    const double b_coef = m_axis.z;
    const auto theta_horizon = [this, b_coef](double phi) {
      const double a_coef = std::cos(phi) * m_frame.s.z + std::sin(phi) * m_frame.t.z;
      return b_coef > 0.0 ? std::atan2(b_coef, -a_coef) : std::atan2(-b_coef, a_coef);
    };
    // The part of the semicircle next to the axis is on the axis' side of the horizon.
    const bool near = upper == (b_coef > 0.0);
    double cached_phi = std::numeric_limits<double>::quiet_NaN();
    double cached_theta_h = 0.0;
    const VectorFunction2d integrand = [&](double phi, double u, std::span<double> out) {
      if (!(phi == cached_phi)) {  // the inner integral runs at one phi: theta_h once per line
        cached_phi = phi;
        cached_theta_h = theta_horizon(phi);
      }
      const double th = cached_theta_h;
      double theta = 0.0;
      double jacobian = 0.0;
      if (near) {
        theta = th * std::expm1(grading * u) / expm1_grading;
        jacobian = th * grading * std::exp(grading * u) / expm1_grading;  // d(theta) / du
      } else {
        theta = th + (pi - th) * u;
        jacobian = pi - th;
      }
      const double sin_t = std::sin(theta);
      const Vec3 w = m_frame.to_world(spherical_direction(sin_t, std::cos(theta), phi));
      m_g(w, out);
      for (auto& v : out) v *= sin_t * jacobian;  // d(omega) = sin(theta) d(theta) d(phi)
    };
    const BoundFunction zero = [](double) { return 0.0; };
    const BoundFunction one = [](double) { return 1.0; };
    QuadratureOptions o = outer;
    o.initial_intervals = std::max(4, (outer.initial_intervals + 3) / 4 * 4);  // breakpoints at 0, pi/2, pi, 3pi/2
    return integrate_2d_vector(integrand, dim, 0.0, two_pi, zero, one, o, inner);
  }

 private:
  const DirectionFunction& m_g;
  Vec3 m_axis;
  Frame m_frame;
};

VectorQuadratureResult sum_halves(VectorQuadratureResult up, const VectorQuadratureResult& down) {
  for (std::size_t k = 0; k < up.value.size(); ++k) {
    up.value[k] += down.value[k];
    up.error[k] += down.error[k];
  }
  up.evaluations += down.evaluations;
  up.subdivisions += down.subdivisions;
  up.converged = up.converged && down.converged;
  return up;
}

// Both halves, each with its share of the tolerance on the total, so that a half holding a negligible part
// of the total is not resolved relative to itself.
VectorQuadratureResult both_halves(const PolarCoordinates& upper_coords, const PolarCoordinates& lower_coords,
                                   std::size_t dim, const QuadratureOptions& options,
                                   const std::optional<QuadratureOptions>& inner) {
  QuadratureOptions half = options;
  std::optional<QuadratureOptions> half_inner = inner;
  std::int64_t rough_evaluations = 0;
  if (!inner) {
    const QuadratureOptions r = rough(options);
    QuadratureOptions r_inner = derived_inner(r, 0.0, two_pi);
    r_inner.max_subdivisions = std::min(r_inner.max_subdivisions, 50);
    const VectorQuadratureResult estimate =
        sum_halves(upper_coords.half(true, dim, r, r_inner), lower_coords.half(false, dim, r, r_inner));
    rough_evaluations = estimate.evaluations;
    const double target = std::max(options.abs_tol, options.rel_tol * smallest_scale(estimate.value));
    half.abs_tol = 0.5 * target;
    half_inner = inner_for(half, half.abs_tol, 0.0, two_pi);
  }
  VectorQuadratureResult result =
      sum_halves(upper_coords.half(true, dim, half, half_inner), lower_coords.half(false, dim, half, half_inner));
  result.evaluations += rough_evaluations;
  return result;
}

}  // namespace

VectorQuadratureResult integrate_directions(const DirectionFunction& g, std::size_t dim, const Vec3& axis,
                                            SphereRegion region, const QuadratureOptions& options,
                                            const std::optional<QuadratureOptions>& inner) {
  const PolarCoordinates coords(g, axis);
  if (region == SphereRegion::upper) return coords.half(true, dim, options, inner);
  if (region == SphereRegion::lower) return coords.half(false, dim, options, inner);
  return both_halves(coords, coords, dim, options, inner);
}

VectorQuadratureResult integrate_sphere(const DirectionFunction& g, std::size_t dim, const Vec3& axis_upper,
                                        const Vec3& axis_lower, const QuadratureOptions& options) {
  return both_halves(PolarCoordinates(g, axis_upper), PolarCoordinates(g, axis_lower), dim, options, std::nullopt);
}

namespace {

// P_n(x) and P_{n-1}(x) by Bonnet's recurrence k P_k = (2k - 1) x P_{k-1} - (k - 1) P_{k-2}.
void legendre(int n, double x, double& pn, double& pn1) {
  double p0 = 1.0, p1 = x;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  pn = n == 0 ? 1.0 : p1;
  pn1 = n == 0 ? 0.0 : p0;
}

GaussLegendreRule build_gauss_legendre(int n) {
  GaussLegendreRule r;
  r.nodes.resize(static_cast<std::size_t>(n));
  r.weights.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Root i (descending) of P_n: Tricomi's estimate cos(pi (i + 3/4) / (n + 1/2)), then Newton's method.
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double pn = 0.0, pn1 = 0.0, dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      legendre(n, x, pn, pn1);
      dp = n * (x * pn - pn1) / (x * x - 1.0);  // P_n'(x) = n (x P_n - P_{n-1}) / (x^2 - 1)
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) <= 4.0 * epsilon) break;
    }
    legendre(n, x, pn, pn1);
    dp = n * (x * pn - pn1) / (x * x - 1.0);
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);  // Abramowitz & Stegun 25.4.29
    // Symmetric pairs: -x at the front, +x at the back (the middle node of an odd rule is x = 0 exactly).
    const auto lo = static_cast<std::size_t>(i), hi = static_cast<std::size_t>(n - 1 - i);
    r.nodes[lo] = lo == hi ? 0.0 : -x;
    r.nodes[hi] = lo == hi ? 0.0 : x;
    r.weights[lo] = w;
    r.weights[hi] = w;
  }
  return r;
}

}  // namespace

const GaussLegendreRule& gauss_legendre_rule(int n) {
  constexpr int max_n = 128;
  if (n < 1 || n > max_n) throw std::invalid_argument("gauss_legendre_rule: n = " + std::to_string(n) + " is not in [1, 128]");
  static std::once_flag once[max_n + 1];
  static std::unique_ptr<GaussLegendreRule> rules[max_n + 1];
  const auto k = static_cast<std::size_t>(n);
  std::call_once(once[k], [&] { rules[k] = std::make_unique<GaussLegendreRule>(build_gauss_legendre(n)); });
  return *rules[k];
}

}  // namespace shadelab
