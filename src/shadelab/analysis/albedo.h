// shadelab directional albedo, its maximum over the viewing angle, and reciprocity of a BRDF.
//
// Contract:
// - directional_albedo(f, theta_o) is rho(wo) = integral over the upper hemisphere of f(wi, wo) cos(theta_i)
//   d(wi), per RGB channel, for wo = (sin theta_o, 0, cos theta_o): theta_o in RADIANS, phi_o = 0. It is
//   computed by deterministic adaptive Gauss-Kronrod quadrature (quadrature.h) in polar coordinates about the
//   lobe's peak (lobe_peak: the best of +Z, the mirror direction and 64 stratified samples of the BRDF's own
//   sampler, refined by a local pattern search), with the horizon as an integration boundary. Defaults reach
//   about 1e-10 relative at normal incidence even for Phong / Blinn-Phong lobes with n = 10000 and about
//   1e-8 elsewhere. A second sharp lobe far from the first is found only through the adaptive subdivision
//   (initial_intervals pieces in azimuth): give AlbedoOptions::axis for such a model if needed. For a
//   stochastic model (Brdf::is_stochastic: eval is a Monte Carlo estimate) quadrature would chase the noise,
//   so the albedo is the mean of stochastic_samples sample weights and error is their standard error.
// - max_albedo scans theta_o over [theta_min, theta_max] (degrees) in steps and refines the best step by
//   golden-section search; it returns the argmax (radians and degrees) and the largest channel there.
// - reciprocity_error evaluates f(a, b) and f(b, a) over a fixed grid of directions (including grazing ones
//   down to 0.001 degrees above the horizon) and returns the largest relative difference per channel,
//   |f(a,b) - f(b,a)| / max(|f(a,b)|, |f(b,a)|); pairs where both values are below `floor` are skipped.
// No printing; randomness only with a fixed seed: the same inputs give the same results.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "shadelab/numeric/quadrature.h"
#include "shadelab/brdf/brdf.h"

namespace shadelab {

// The quadrature options of directional_albedo: rel_tol 1e-10, abs_tol 1e-15, 4 initial azimuth pieces.
QuadratureOptions albedo_quadrature();
// The loosest relative tolerance directional_albedo integrates a tabulated model (Brdf::is_tabulated) to: a
// tighter one chases the interpolation's kinks and, at grazing views, its jumps where measured neighbours drop out
// (a measured ggx table at 30 degrees: 1e-4 in 0.15 s, 1e-5 in 0.45 s, 1e-6 in 2.9 s, 1e-7 in 17 s; at 89 degrees
// 1e-4 in 8 s, 1e-5 in 27 s; the values within 3e-6 of each other, the table 6e-4 from the model it measured).
inline constexpr double tabulated_rel_tol = 1e-4;

struct AlbedoOptions {
  QuadratureOptions quadrature = albedo_quadrature();
  std::optional<Vec3> axis;  // integration axis; default: lobe_peak(f, wo, LobeQuantity::reflected)
  // A stochastic model (Brdf::is_stochastic, whose eval is noisy) is integrated by its own sampler instead:
  // the mean of this many sample weights (fixed seed), error = its standard error.
  int stochastic_samples = 20000;
};

struct AlbedoResult {
  Rgb albedo;
  Rgb error;  // estimated absolute error per channel
  Vec3 wo;
  Vec3 axis;  // the integration axis used
  std::int64_t evaluations = 0;
  bool converged = false;
};

AlbedoResult directional_albedo(const Brdf& f, double theta_o_rad, const AlbedoOptions& options = {});
AlbedoResult directional_albedo(const Brdf& f, const Vec3& wo, const AlbedoOptions& options = {});

enum class LobeQuantity {
  reflected,  // max channel of f(wi, wo) cos(theta_i), wi in the upper hemisphere
  pdf_upper,  // pdf(wi, wo), wi in the upper hemisphere
  pdf_lower,  // pdf(wi, wo), wi in the lower hemisphere
};
// The direction where the quantity peaks, as found by the search described above (for pdf_lower the
// candidates are -wo, -Z, the mirror direction reflected below the horizon and the samples below it).
Vec3 lobe_peak(const Brdf& f, const Vec3& wo, LobeQuantity quantity);

struct AlbedoScanOptions {
  double theta_min_deg = 0.0;
  double theta_max_deg = 89.0;
  double step_deg = 3.0;
  double theta_tol_deg = 1e-3;  // width at which the golden-section refinement stops
  AlbedoOptions albedo = [] {
    AlbedoOptions o;
    o.quadrature.rel_tol = 1e-8;
    return o;
  }();
};

struct AlbedoMax {
  double theta_rad = 0.0;
  double theta_deg = 0.0;
  double value = 0.0;  // largest channel of the albedo at theta
  Rgb albedo;
  int albedo_evaluations = 0;  // how many directional albedos were computed
  bool converged = false;      // every albedo integral converged
};

AlbedoMax max_albedo(const Brdf& f, const AlbedoScanOptions& options = {});

struct ReciprocityOptions {
  std::vector<double> theta_deg = {0.0, 1.0, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0, 89.9, 89.999};
  std::vector<double> phi_deg = {0.0, 40.0, 90.0, 135.0, 180.0, 200.0, 270.0, 315.0};
  double floor = 1e-200;  // values below this (1/sr) count as zero
};

struct ReciprocityResult {
  double max_relative_error = 0.0;  // infinity if a value was not finite
  Vec3 a;                           // the worst pair
  Vec3 b;
  Rgb f_ab;
  Rgb f_ba;
  int pairs = 0;    // unordered pairs of distinct directions compared
  int skipped = 0;  // pairs with both values below the floor in every channel
};

ReciprocityResult reciprocity_error(const Brdf& f, const ReciprocityOptions& options = {});

}  // namespace shadelab
