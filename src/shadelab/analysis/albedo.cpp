#include "shadelab/analysis/albedo.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {

namespace {

constexpr Vec3 normal{0.0, 0.0, 1.0};

Vec3 view_direction(double theta_rad) { return {std::sin(theta_rad), 0.0, std::cos(theta_rad)}; }

double score(const Brdf& f, const Vec3& wi, const Vec3& wo, LobeQuantity quantity) {
  double s = -1.0;
  switch (quantity) {
    case LobeQuantity::reflected:
      if (wi.z > 0.0) s = f.eval(wi, wo).max_component() * wi.z;
      break;
    case LobeQuantity::pdf_upper:
      if (wi.z > 0.0) s = f.pdf(wi, wo);
      break;
    case LobeQuantity::pdf_lower:
      if (wi.z < 0.0) s = f.pdf(wi, wo);
      break;
  }
  return std::isfinite(s) ? s : -1.0;  // a non-finite value is never a peak worth centring on
}

}  // namespace

QuadratureOptions albedo_quadrature() {
  QuadratureOptions o;
  o.rel_tol = 1e-10;
  o.abs_tol = 1e-15;
  o.max_subdivisions = 2000;
  o.initial_intervals = 4;
  return o;
}

Vec3 lobe_peak(const Brdf& f, const Vec3& wo, LobeQuantity quantity) {
  // Candidates: the mirror direction, the normal, and 8 x 8 stratified samples of the model's sampler (below
  // the horizon: -wo, -Z and the mirror direction reflected below).
  const bool lower = quantity == LobeQuantity::pdf_lower;
  Vec3 best = lower ? -wo : Vec3{-wo.x, -wo.y, wo.z};
  double best_score = score(f, best, wo, quantity);
  const auto consider = [&](const Vec3& w) {
    if (!is_finite(w)) return;
    const double s = score(f, w, wo, quantity);
    if (s > best_score) {
      best = w;
      best_score = s;
    }
  };
  consider(lower ? -normal : normal);
  if (lower) consider({-wo.x, -wo.y, -wo.z});
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const Vec2 u{(i + 0.5) / 8.0, (j + 0.5) / 8.0};
      const double u_lobe = (8 * i + j + 0.5) / 64.0;
      consider(f.sample(wo, u, u_lobe).wi);
    }
  }
  // Pattern search on the sphere: try 8 directions at angular distance `step`, halve it when none improves.
  double step = 0.05;
  for (int iteration = 0; iteration < 400 && step > 1e-7; ++iteration) {
    const Frame frame = Frame::from_normal(best);
    bool improved = false;
    for (int k = 0; k < 8; ++k) {
      const double a = k * (pi / 4.0);
      const Vec3 w = normalize(frame.to_world(spherical_direction(std::sin(step), std::cos(step), a)));
      const double s = score(f, w, wo, quantity);
      if (s > best_score) {
        best = w;
        best_score = s;
        improved = true;
      }
    }
    if (!improved) step *= 0.5;
  }
  return best;
}

AlbedoResult directional_albedo(const Brdf& f, const Vec3& wo, const AlbedoOptions& options) {
  AlbedoResult result;
  result.wo = wo;
  if (f.is_stochastic()) {
    // The mean of the model's own sample weights f cos / pdf (PCG32, fixed seed), error = standard error.
    Pcg32 rng(0xa1bed0, 3);
    Rgb sum;
    Rgb sum2;
    const int n = std::max(2, options.stochastic_samples);
    for (int i = 0; i < n; ++i) {
      const Vec2 u{rng.next_double(), rng.next_double()};
      const Rgb w = f.sample(wo, u, rng.next_double()).weight;
      sum += w;
      sum2 += w * w;
    }
    result.albedo = sum / n;
    for (int c = 0; c < 3; ++c) {
      const double var = std::max(0.0, sum2[c] / n - result.albedo[c] * result.albedo[c]) * n / (n - 1.0);
      result.error[c] = std::sqrt(var / n);
    }
    result.axis = normal;
    result.evaluations = n;
    result.converged = true;
    return result;
  }
  result.axis = options.axis ? *options.axis : lobe_peak(f, wo, LobeQuantity::reflected);
  if (!(result.axis.z > 0.0)) result.axis = normal;  // the peak search found nothing above the horizon
  QuadratureOptions quadrature = options.quadrature;
  if (f.is_tabulated()) quadrature.rel_tol = std::max(quadrature.rel_tol, tabulated_rel_tol);
  const VectorQuadratureResult q = integrate_directions(
      [&](const Vec3& wi, std::span<double> out) {
        const Rgb v = wi.z > 0.0 ? f.eval(wi, wo) * wi.z : Rgb{};  // f(wi, wo) cos(theta_i)
        out[0] = v.r;
        out[1] = v.g;
        out[2] = v.b;
      },
      3, result.axis, SphereRegion::upper, quadrature);
  result.albedo = {q.value[0], q.value[1], q.value[2]};
  result.error = {q.error[0], q.error[1], q.error[2]};
  result.evaluations = q.evaluations;
  result.converged = q.converged;
  return result;
}

AlbedoResult directional_albedo(const Brdf& f, double theta_o_rad, const AlbedoOptions& options) {
  return directional_albedo(f, view_direction(theta_o_rad), options);
}

AlbedoMax max_albedo(const Brdf& f, const AlbedoScanOptions& options) {
  AlbedoMax best;
  best.value = -std::numeric_limits<double>::infinity();
  bool all_converged = true;
  const auto at = [&](double theta_deg) {
    const AlbedoResult r = directional_albedo(f, deg_to_rad(theta_deg), options.albedo);
    ++best.albedo_evaluations;
    all_converged = all_converged && r.converged;
    const double v = r.albedo.max_component();
    if (v > best.value || best.albedo_evaluations == 1) {
      best.value = v;
      best.theta_deg = theta_deg;
      best.albedo = r.albedo;
    }
    return v;
  };
  const double lo = options.theta_min_deg;
  const double hi = std::max(options.theta_max_deg, lo);
  const double step = options.step_deg > 0.0 ? options.step_deg : hi - lo;
  const int steps = step > 0.0 ? static_cast<int>(std::ceil((hi - lo) / step - 1e-9)) : 0;
  for (int i = 0; i <= steps; ++i) at(std::min(hi, lo + i * step));

  // Golden-section refinement on the bracket of scan points around the best one (Kiefer 1953).
  double a = std::max(lo, best.theta_deg - step);
  double b = std::min(hi, best.theta_deg + step);
  const double inv_phi = 0.5 * (std::sqrt(5.0) - 1.0);  // 1/golden ratio
  double x1 = b - inv_phi * (b - a);
  double x2 = a + inv_phi * (b - a);
  double f1 = b > a ? at(x1) : 0.0;
  double f2 = b > a ? at(x2) : 0.0;
  while (b - a > options.theta_tol_deg) {
    if (f1 >= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - inv_phi * (b - a);
      f1 = at(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + inv_phi * (b - a);
      f2 = at(x2);
    }
  }
  best.theta_rad = deg_to_rad(best.theta_deg);
  best.converged = all_converged;
  return best;
}

ReciprocityResult reciprocity_error(const Brdf& f, const ReciprocityOptions& options) {
  std::vector<Vec3> dirs;
  for (double t : options.theta_deg) {
    const double tr = deg_to_rad(t);
    for (double p : options.phi_deg) {
      dirs.push_back(spherical_direction(std::sin(tr), std::cos(tr), deg_to_rad(p)));
      if (t == 0.0) break;  // the pole once
    }
  }
  ReciprocityResult result;
  bool have_worst = false;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    for (std::size_t j = i + 1; j < dirs.size(); ++j) {
      const Rgb ab = f.eval(dirs[i], dirs[j]);
      const Rgb ba = f.eval(dirs[j], dirs[i]);
      ++result.pairs;
      bool compared = false;
      for (int c = 0; c < 3; ++c) {
        double err = 0.0;
        if (!std::isfinite(ab[c]) || !std::isfinite(ba[c])) {
          err = std::numeric_limits<double>::infinity();
        } else {
          const double scale = std::max(std::abs(ab[c]), std::abs(ba[c]));
          if (scale < options.floor) continue;
          err = std::abs(ab[c] - ba[c]) / scale;  // relative difference of f(a,b) and f(b,a)
        }
        compared = true;
        if (err > result.max_relative_error || !have_worst) {
          have_worst = true;
          result.max_relative_error = err;
          result.a = dirs[i];
          result.b = dirs[j];
          result.f_ab = ab;
          result.f_ba = ba;
        }
      }
      if (!compared) ++result.skipped;
    }
  }
  return result;
}

}  // namespace shadelab
