// shadelab deterministic quadrature: globally adaptive Gauss-Kronrod (G7/K15) in 1D, nested 2D, and
// integrals over regions of the sphere of directions in polar coordinates about a chosen axis; fixed
// Gauss-Legendre rules for callers that choose their own variables and node counts.
//
// Contract:
// - integrate(f, a, b, options) estimates the integral of f over [a, b] (a < b, or a == b giving 0). Each
//   interval is integrated with the 15-point Kronrod rule; its error estimate is the QUADPACK heuristic
//   built from the difference to the embedded 7-point Gauss rule (Piessens et al., QUADPACK, 1983, qk15):
//   err = I_asc min(1, (200 |K - G| / I_asc)^1.5), never below 50 eps times the integral of |f|. The interval
//   with the largest error is bisected until the summed error <= max(abs_tol, rel_tol |value|) (converged)
//   or max_subdivisions bisections were made or the worst interval can no longer be split (not converged).
//   The result's error is that summed estimate. No random numbers: the same inputs give the same bits.
// - f is called at interior points only (never at a or b), so integrable endpoint singularities are fine.
// - The vector forms integrate dim components at once from one call of f per point; every component must
//   meet its own tolerance; the interval ranked worst is the one with the largest error in any component.
// - integrate_2d integrates f(x, y) over a <= x <= b, c(x) <= y <= d(x) as an outer adaptive integral of
//   inner adaptive integrals. Unless inner options are given, a rough first pass (rel_tol 1e-4, at most 50
//   subdivisions) sizes the integral I, and each inner integral gets rel_tol / 10 and
//   abs_tol = max(abs_tol, rel_tol |I|) / (10 (b - a)): lines where the integrand is negligible need not be
//   resolved relative to themselves. The reported error adds the integral of the inner errors to the outer
//   error; converged means the outer and every inner integral converged.
// - integrate_directions integrates g(w) d(omega) over the upper hemisphere (w.z > 0), the lower one, or the
//   sphere, in polar coordinates (theta', phi') about a unit axis: the outer integral runs over phi' in
//   [0, 2 pi] and the inner one over theta' from the axis to the horizon (or from the horizon to the
//   antipode), so the horizon is always an integration boundary and a peak at the axis sits at an endpoint.
//   Azimuth phi' = 0 points from the axis towards +Z and phi' = pi towards the horizon; the outer integral
//   starts with breakpoints at multiples of pi/2 (initial_intervals is raised to a multiple of 4), so the
//   thin lobes that reflection makes at grazing angles, long in that vertical plane, sit at breakpoints.
//   Put the axis on the integrand's peak. An axis closer to the horizon than |z| = 0.01 is tilted to
//   |z| = 0.01 at the same azimuth (about an axis on the horizon the bounds would jump); a zero axis is +Z. For the
//   sphere the two halves share the tolerance on the total; integrate_sphere takes one axis per half.
// - gauss_legendre_rule(n) is the n-point Gauss-Legendre rule on [-1, 1] (nodes ascending, weights), exact for
//   polynomials of degree 2n - 1; n in [1, 128]. The nodes are the roots of P_n found by Newton's method from
//   Tricomi's estimate, the weights 2 / ((1 - x^2) P_n'(x)^2) (Abramowitz & Stegun 25.4.29); built once per n,
//   thread-safe, the same bits every time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "shadelab/core/vec.h"

namespace shadelab {

struct QuadratureOptions {
  double rel_tol = 1e-10;     // relative tolerance on the whole integral
  double abs_tol = 0.0;       // absolute tolerance on the whole integral
  int max_subdivisions = 2000;
  int initial_intervals = 1;  // [a, b] is first cut into this many equal pieces
};

struct QuadratureResult {
  double value = 0.0;
  double error = 0.0;  // estimated absolute error
  std::int64_t evaluations = 0;
  int subdivisions = 0;
  bool converged = false;
};

struct VectorQuadratureResult {
  std::vector<double> value;
  std::vector<double> error;  // per component
  std::int64_t evaluations = 0;
  int subdivisions = 0;
  bool converged = false;
};

using ScalarFunction = std::function<double(double)>;
// Writes the dim components of the integrand at x into out (out.size() == dim).
using VectorFunction = std::function<void(double, std::span<double>)>;
using ScalarFunction2d = std::function<double(double, double)>;
using VectorFunction2d = std::function<void(double, double, std::span<double>)>;
using BoundFunction = std::function<double(double)>;
using DirectionFunction = std::function<void(const Vec3&, std::span<double>)>;

QuadratureResult integrate(const ScalarFunction& f, double a, double b, const QuadratureOptions& options = {});

VectorQuadratureResult integrate_vector(const VectorFunction& f, std::size_t dim, double a, double b,
                                        const QuadratureOptions& options = {});

QuadratureResult integrate_2d(const ScalarFunction2d& f, double a, double b, const BoundFunction& c,
                              const BoundFunction& d, const QuadratureOptions& options = {},
                              const std::optional<QuadratureOptions>& inner = std::nullopt);

VectorQuadratureResult integrate_2d_vector(const VectorFunction2d& f, std::size_t dim, double a, double b,
                                           const BoundFunction& c, const BoundFunction& d,
                                           const QuadratureOptions& options = {},
                                           const std::optional<QuadratureOptions>& inner = std::nullopt);

struct GaussLegendreRule {
  std::vector<double> nodes;    // ascending, in (-1, 1)
  std::vector<double> weights;  // sum 2
};
// Throws std::invalid_argument for n outside [1, 128].
const GaussLegendreRule& gauss_legendre_rule(int n);

enum class SphereRegion { upper, lower, sphere };

VectorQuadratureResult integrate_directions(const DirectionFunction& g, std::size_t dim, const Vec3& axis,
                                            SphereRegion region, const QuadratureOptions& options = {},
                                            const std::optional<QuadratureOptions>& inner = std::nullopt);

// The whole sphere as the upper hemisphere about axis_upper plus the lower one about axis_lower (each axis
// may lie in either hemisphere); the tolerance applies to the total.
VectorQuadratureResult integrate_sphere(const DirectionFunction& g, std::size_t dim, const Vec3& axis_upper,
                                        const Vec3& axis_lower, const QuadratureOptions& options = {});

}  // namespace shadelab
