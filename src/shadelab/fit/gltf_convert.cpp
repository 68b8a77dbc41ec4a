#include "shadelab/fit/gltf_convert.h"

#include <nlopt.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>

#include "shadelab/analysis/albedo.h"
#include "shadelab/brdf/fresnel.h"
#include "shadelab/core/constants.h"
#include "shadelab/numeric/quadrature.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

namespace {

constexpr double kIor = 1000.0;  // PR #1719's "infinite" ior
constexpr int kDims = 9;         // base_color (3), metallic, roughness, specular, specular_color (3)
constexpr double kStopRms = 1e-7;  // the fit stops below this RMS (the fit quadrature's own accuracy)

// f0 = ((ior - 1)/(ior + 1))^2 specular_color (KHR_materials_ior, KHR_materials_specular; brdf/fresnel.h).
double ior_f0(double ior) { return f0_from_ior(ior); }

double specular_color_max() { return 1.0 / ior_f0(kIor); }

// The fit's quadrature (1e-6 relative) and the report's (1e-8).
enum class Precision { fit, report };

// The albedo about the mirror direction of wo (both models' lobes peak near it; the adaptive subdivision finds the
// rest), which spares the lobe-peak search of every call.
std::vector<Rgb> albedos(const Brdf& f, const GltfConvertOptions& options, Precision precision) {
  AlbedoOptions o;
  o.quadrature.rel_tol = precision == Precision::fit ? 1e-6 : 1e-8;
  o.quadrature.abs_tol = precision == Precision::fit ? 1e-9 : 1e-12;
  std::vector<Rgb> out(options.theta_deg.size());
  tbb::parallel_for(std::size_t{0}, out.size(), [&](std::size_t i) {
    const double t = deg_to_rad(options.theta_deg[i]);
    AlbedoOptions oi = o;
    oi.axis = Vec3{-std::sin(t), 0.0, std::cos(t)};
    out[i] = directional_albedo(f, Vec3{std::sin(t), 0.0, std::cos(t)}, oi).albedo;
  });
  return out;
}

AlbedoDifference difference_of(const std::vector<Rgb>& sg, const std::vector<Rgb>& mr,
                               const GltfConvertOptions& options) {
  AlbedoDifference d;
  double sum = 0.0;
  for (std::size_t i = 0; i < sg.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double e = mr[i][c] - sg[i][c];
      sum += e * e;
      if (std::abs(e) > d.max_abs[c]) d.max_abs[c] = std::abs(e);
      if (std::abs(e) > d.max) {
        d.max = std::abs(e);
        d.worst_theta_deg = options.theta_deg[i];
      }
    }
  }
  d.rms = sg.empty() ? 0.0 : std::sqrt(sum / (3.0 * static_cast<double>(sg.size())));
  return d;
}

// The unit box <-> the factors (linear in each range).
MetalRoughFactors from_unit(const double* u) {
  MetalRoughFactors m;
  m.base_color = Rgb{u[0], u[1], u[2]};
  m.metallic = u[3];
  m.roughness = u[4];
  m.ior = kIor;
  m.specular = u[5];
  const double s = specular_color_max();
  m.specular_color = Rgb{u[6] * s, u[7] * s, u[8] * s};
  return m;
}

std::array<double, kDims> to_unit(const MetalRoughFactors& m) {
  const double s = specular_color_max();
  std::array<double, kDims> u{m.base_color.r, m.base_color.g, m.base_color.b, m.metallic, m.roughness, m.specular,
                              m.specular_color.r / s, m.specular_color.g / s, m.specular_color.b / s};
  for (double& x : u) x = std::clamp(x, 0.0, 1.0);
  return u;
}

}  // namespace

// baseColor = diffuse, metallic = 0, roughness = 1 - glossiness, ior = 1000, specular = 1, specularColor = specular
// (glTF PR #1719, comment 674365677; gltf-transform's metalRough()).
MetalRoughFactors pr1719_conversion(const SpecGloss::Params& sg) {
  MetalRoughFactors m;
  m.base_color = sg.diffuse;
  m.metallic = 0.0;
  m.roughness = 1.0 - sg.glossiness;
  m.ior = kIor;
  m.specular = 1.0;
  m.specular_color = sg.specular;
  return m;
}

AlbedoDifference albedo_difference(const SpecGloss::Params& sg, const MetalRoughFactors& m,
                                   const GltfConvertOptions& options) {
  return difference_of(albedos(SpecGloss(sg), options, Precision::report),
                       albedos(Gltf(gltf_params(m)), options, Precision::report), options);
}

GltfMaterialConversion convert_spec_gloss(const SpecGloss::Params& sg, const GltfConvertOptions& options) {
  GltfMaterialConversion out;
  const std::vector<Rgb> target = albedos(SpecGloss(sg), options, Precision::fit);
  out.start = pr1719_conversion(sg);

  // The metal start: metallic 1, baseColor = specular (the extension's README: "the same as the base color value
  // ... for metals"), roughness = 1 - glossiness; exact when diffuse = 0.
  MetalRoughFactors metal = out.start;
  metal.base_color = sg.specular;
  metal.metallic = 1.0;

  struct Ctx {
    const std::vector<Rgb>* target;
    const GltfConvertOptions* options;
    double best = std::numeric_limits<double>::max();
    std::array<double, kDims> best_u{};
    std::int64_t evaluations = 0;
  };
  Ctx ctx{&target, &options};
  const auto objective = [](unsigned, const double* x, double*, void* context) -> double {
    auto* c = static_cast<Ctx*>(context);
    ++c->evaluations;
    const double rms =
        difference_of(*c->target, albedos(Gltf(gltf_params(from_unit(x))), *c->options, Precision::fit), *c->options).rms;
    if (rms < c->best) {
      c->best = rms;
      std::copy(x, x + kDims, c->best_u.begin());
    }
    return rms;
  };
  // BOBYQA from the better of the two starts.
  std::array<double, kDims> u = to_unit(out.start);
  const double rms_pr = objective(kDims, u.data(), nullptr, &ctx);
  std::array<double, kDims> u_metal = to_unit(metal);
  if (objective(kDims, u_metal.data(), nullptr, &ctx) < rms_pr) u = u_metal;
  // NLopt's C interface (Debian's libnlopt-dev has no C++ header), as fit/fit.cpp calls it.
  const std::unique_ptr<nlopt_opt_s, decltype(&nlopt_destroy)> opt(nlopt_create(NLOPT_LN_BOBYQA, kDims), &nlopt_destroy);
  if (opt && ctx.best > kStopRms && options.max_evaluations > 0) {
    nlopt_set_lower_bounds1(opt.get(), 0.0);
    nlopt_set_upper_bounds1(opt.get(), 1.0);
    nlopt_set_xtol_rel(opt.get(), 1e-6);
    nlopt_set_ftol_abs(opt.get(), 1e-8);
    nlopt_set_stopval(opt.get(), kStopRms);
    nlopt_set_maxeval(opt.get(), options.max_evaluations);
    nlopt_set_initial_step1(opt.get(), 0.05);
    nlopt_set_min_objective(opt.get(), objective, &ctx);
    double value = 0.0;
    // A failure code (NLOPT_ROUNDOFF_LIMITED and the like) keeps the best point seen (tracked in ctx).
    (void)nlopt_optimize(opt.get(), u.data(), &value);
  }
  out.evaluations = ctx.evaluations;
  out.result = from_unit(ctx.best_u.data());
  const std::vector<Rgb> target_report = albedos(SpecGloss(sg), options, Precision::report);
  out.start_difference =
      difference_of(target_report, albedos(Gltf(gltf_params(out.start)), options, Precision::report), options);
  out.difference =
      difference_of(target_report, albedos(Gltf(gltf_params(out.result)), options, Precision::report), options);
  return out;
}

// ---- The fast per-texel rule ----

namespace {

constexpr int kTableNodes = 65;  // roughness nodes r_j = j / 64 (docs/conversions.md: the interpolation error)
constexpr double kTableRelTol = 1e-7;  // each entry's quadrature (far below the interpolation error)

// (1/pi) (1 - V.H)^5 above the horizon: its directional albedo is L5 (the diffuse weight's Schlick share). A test
// double of the Brdf interface, sampled by the cosine-weighted hemisphere.
class SchlickWeightedLambert final : public Brdf {
 public:
  Rgb eval(const Vec3& wi, const Vec3& wo) const override {
    if (wi.z <= 0.0 || wo.z <= 0.0) return {};
    const Vec3 h = normalize(wi + wo);
    const double w = std::pow(std::clamp(1.0 - dot(wo, h), 0.0, 1.0), 5.0);  // Schlick's (1 - V.H)^5
    return Rgb{w, w, w} * inv_pi;
  }
  double pdf(const Vec3& wi, const Vec3& wo) const override { return wo.z > 0.0 ? cosine_hemisphere_pdf(wi) : 0.0; }
  BrdfSample sample(const Vec3& wo, Vec2 u, double) const override {
    BrdfSample s;
    if (wo.z <= 0.0) return s;
    s.wi = sample_cosine_hemisphere(u);
    s.pdf = cosine_hemisphere_pdf(s.wi);
    if (s.pdf > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
    return s;
  }
};

Rgb table_albedo_at(int k, const Brdf& f) {
  const double t = deg_to_rad(10.0 * k);
  AlbedoOptions o;
  o.quadrature.rel_tol = kTableRelTol;
  o.quadrature.abs_tol = 1e-10;
  o.axis = Vec3{-std::sin(t), 0.0, std::cos(t)};  // the mirror direction of wo
  return directional_albedo(f, Vec3{std::sin(t), 0.0, std::cos(t)}, o).albedo;
}

// E and E5 of GGX (height-correlated Smith) at theta_o, alpha, in the half-vector domain warped by GGX's own sampling
// (Walter et al. 2007, eq. 35-36: tan^2 theta_h = alpha^2 u / (1 - u) gives D(h) cos(theta_h) d(omega_h) = du dphi / (2 pi)):
//   E = integral f cos(theta_i) d(wi) = integral G2 F (wo.h) / (mu_o cos(theta_h)) du dphi / (2 pi),   d(wi) = 4 (wo.h) d(omega_h)
// (Walter et al. 2007, eq. 14),
// over the h whose mirror direction wi = 2 (wo.h) h - wo is above the horizon: for each phi, theta_h below
// theta_max = atan2(cos theta_o, -sin theta_o cos phi) / 2 (where wi.z = sin(2 theta_h) a + cos(2 theta_h) cos theta_o
// = 0, a = sin theta_o cos phi). The integrand is smooth inside (G2 vanishes linearly at the horizon), even and
// periodic in phi: the trapezoid rule over [0, pi] in phi (exponentially convergent for such functions) and
// Gauss-Legendre over [0, u_max(phi)] in w = sqrt(1 - u). F = 1 gives E, F = (1 - wo.h)^5 gives E5.
std::pair<double, double> ggx_energies(double theta_o, double alpha) {
  constexpr int kPhi = 96;
  const GaussLegendreRule& rule = gauss_legendre_rule(64);
  const Vec3 wo{std::sin(theta_o), 0.0, std::cos(theta_o)};
  const double a2 = alpha * alpha;
  // Lambda of the height-correlated Smith G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014, eq. 72 and 99).
  const auto lambda = [a2](double cos_t) {
    const double c2 = cos_t * cos_t;
    return 0.5 * (-1.0 + std::sqrt(1.0 + a2 * (1.0 - c2) / c2));
  };
  const double lambda_o = lambda(wo.z);
  double e = 0.0, e5 = 0.0;
  for (int p = 0; p <= kPhi; ++p) {
    const double phi = pi * p / kPhi;
    const double w_phi = (p == 0 || p == kPhi) ? 0.5 : 1.0;  // trapezoid
    const double theta_max = 0.5 * std::atan2(wo.z, -wo.x * std::cos(phi));
    const double tan2_max = std::tan(theta_max) * std::tan(theta_max);
    const double u_max = tan2_max / (a2 + tan2_max);
    double se = 0.0, se5 = 0.0;
    // In w = sqrt(1 - u) (du = 2 w dw): tan(theta_h) = alpha sqrt(u) / w, so the integrand's 1/w growth toward
    // u = 1 (grazing microfacets, reached when theta_o is large) becomes smooth.
    const double w_min = std::sqrt(1.0 - u_max);
    for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
      const double w = w_min + 0.5 * (1.0 - w_min) * (rule.nodes[q] + 1.0);
      const double u = 1.0 - w * w;
      const double tan2 = a2 * u / (w * w);
      const double cos_h = 1.0 / std::sqrt(1.0 + tan2);
      const double sin_h = std::sqrt(tan2) * cos_h;
      const Vec3 h{sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h};
      const double oh = dot(wo, h);
      const double wi_z = 2.0 * oh * cos_h - wo.z;
      if (wi_z <= 0.0 || oh <= 0.0) continue;
      const double g = 2.0 * w * oh / (wo.z * cos_h * (1.0 + lambda_o + lambda(wi_z)));
      se += rule.weights[q] * g;
      se5 += rule.weights[q] * g * std::pow(1.0 - oh, 5.0);  // Schlick's weight
    }
    e += w_phi * 0.5 * (1.0 - w_min) * se;
    e5 += w_phi * 0.5 * (1.0 - w_min) * se5;
  }
  // (1 / (2 pi)) * 2 (both halves of phi) * (pi / kPhi) (the trapezoid's step) = 1 / kPhi.
  return {e / kPhi, e5 / kPhi};
}

GltfAlbedoTables build_tables() {
  GltfAlbedoTables t;
  t.nodes = kTableNodes;
  const int n = GltfAlbedoTables::angles * kTableNodes;
  t.e.assign(static_cast<std::size_t>(n), 0.0);
  t.e5.assign(static_cast<std::size_t>(n), 0.0);
  t.l5.assign(GltfAlbedoTables::angles, 0.0);
  // Each entry is its own integral: the same values whatever the thread count.
  tbb::parallel_for(0, n + GltfAlbedoTables::angles, [&](int i) {
    if (i >= n) {
      t.l5[static_cast<std::size_t>(i - n)] = table_albedo_at(i - n, SchlickWeightedLambert()).r;
      return;
    }
    const int k = i / kTableNodes;
    const int j = i % kTableNodes;
    const double r = static_cast<double>(j) / (kTableNodes - 1);
    const auto [e, e5] = ggx_energies(deg_to_rad(10.0 * k), std::max(r * r, kernel::GLTF_ALPHA_MIN));
    t.e[static_cast<std::size_t>(i)] = e;
    t.e5[static_cast<std::size_t>(i)] = e5;
  });
  return t;
}

// Catmull-Rom through p0..p3 at t in [0, 1] (the segment p1..p2) and its derivative in t.
void catmull_rom(double p0, double p1, double p2, double p3, double t, double& value, double& slope) {
  const double a = -p0 + p2, b = 2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3, c = -p0 + 3.0 * p1 - 3.0 * p2 + p3;
  value = 0.5 * (2.0 * p1 + t * (a + t * (b + t * c)));  // Catmull & Rom 1974, tension 1/2
  slope = 0.5 * (a + t * (2.0 * b + 3.0 * t * c));
}

double node(const std::vector<double>& v, int k, int j, int nodes) {
  const auto at = [&](int jj) { return v[static_cast<std::size_t>(k * nodes + jj)]; };
  if (j < 0) return 2.0 * at(0) - at(1);  // linearly extrapolated ghosts
  if (j > nodes - 1) return 2.0 * at(nodes - 1) - at(nodes - 2);
  return at(j);
}

constexpr double kFastIor = 1000.0;

}  // namespace

const GltfAlbedoTables& gltf_albedo_tables() {
  static const GltfAlbedoTables tables = build_tables();  // thread-safe initialisation (C++11 statics)
  return tables;
}

GltfEnergies gltf_energies(double roughness) {
  const GltfAlbedoTables& t = gltf_albedo_tables();
  const double x = std::clamp(roughness, 0.0, 1.0) * (t.nodes - 1);
  const int i = std::min(static_cast<int>(std::floor(x)), t.nodes - 2);
  const double u = x - i;
  GltfEnergies out;
  for (int k = 0; k < GltfAlbedoTables::angles; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    catmull_rom(node(t.e, k, i - 1, t.nodes), node(t.e, k, i, t.nodes), node(t.e, k, i + 1, t.nodes),
                node(t.e, k, i + 2, t.nodes), u, out.e[kk], out.de[kk]);
    catmull_rom(node(t.e5, k, i - 1, t.nodes), node(t.e5, k, i, t.nodes), node(t.e5, k, i + 1, t.nodes),
                node(t.e5, k, i + 2, t.nodes), u, out.e5[kk], out.de5[kk]);
    out.de[kk] *= t.nodes - 1;
    out.de5[kk] *= t.nodes - 1;
  }
  return out;
}

// rho_sg = c_diff + specular (E - E5) + E5 (spec_gloss.h: Lambert c_diff/pi, Schlick F = f0 + (1 - f0) w).
GridAlbedo table_albedo(const SpecGloss::Params& sg) {
  const GltfEnergies en = gltf_energies(1.0 - sg.glossiness);
  const Rgb cd = SpecGloss::c_diff(sg);
  GridAlbedo out;
  for (std::size_t k = 0; k < out.size(); ++k) {
    for (int c = 0; c < 3; ++c) out[k][c] = cd[c] + sg.specular[c] * (en.e[k] - en.e5[k]) + en.e5[k];
  }
  return out;
}

// rho_gltf (kernels/gltf.sl: dielectric base (1 - s max3(F)) / pi + s F DV, metal (base + (1 - base) w) DV).
GridAlbedo table_albedo(const MetalRoughFactors& m) {
  const GltfEnergies en = gltf_energies(m.roughness);
  const GltfAlbedoTables& t = gltf_albedo_tables();
  const double q = ior_f0(m.ior);
  Rgb f0;
  for (int c = 0; c < 3; ++c) f0[c] = std::min(q * m.specular_color[c], 1.0);  // KHR_materials_specular
  const double fmax = f0.max_component();
  GridAlbedo out;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double l5 = t.l5[k];
    for (int c = 0; c < 3; ++c) {
      const double dielectric = m.base_color[c] * (1.0 - m.specular * (fmax * (1.0 - l5) + l5)) +
                                m.specular * (f0[c] * (en.e[k] - en.e5[k]) + en.e5[k]);
      const double metal = m.base_color[c] * (en.e[k] - en.e5[k]) + en.e5[k];
      out[k][c] = (1.0 - m.metallic) * dielectric + m.metallic * metal;
    }
  }
  return out;
}

AlbedoDifference table_albedo_difference(const SpecGloss::Params& sg, const MetalRoughFactors& m) {
  const GridAlbedo a = table_albedo(sg), b = table_albedo(m);
  GltfConvertOptions grid;
  return difference_of(std::vector<Rgb>(a.begin(), a.end()), std::vector<Rgb>(b.begin(), b.end()), grid);
}

FastConversion convert_spec_gloss_fast(const SpecGloss::Params& sg, const FastOptions& options) {
  constexpr int kN = 8;  // base (3), roughness, specular, f0 (3)
  constexpr int kK = GltfAlbedoTables::angles;
  const GltfAlbedoTables& t = gltf_albedo_tables();
  const GridAlbedo target = table_albedo(sg);
  const double q = ior_f0(kFastIor);
  // PR #1719's start: base = diffuse, roughness = 1 - glossiness, s = 1, f0 = 0.996 specular.
  std::array<double, kN> x{sg.diffuse.r, sg.diffuse.g, sg.diffuse.b, 1.0 - sg.glossiness, 1.0,
                           q * sg.specular.r, q * sg.specular.g, q * sg.specular.b};
  // The box: [0, 1] for each, roughness within the band about the source's 1 - glossiness.
  const double r_lo = std::max(0.0, 1.0 - sg.glossiness - options.roughness_band);
  const double r_hi = std::min(1.0, 1.0 - sg.glossiness + options.roughness_band);
  const auto clamp_x = [&](std::array<double, kN>& v) {
    for (double& e : v) e = std::clamp(e, 0.0, 1.0);
    v[3] = std::clamp(v[3], r_lo, r_hi);
  };
  clamp_x(x);
  // Residuals rho_gltf - rho_sg (27) and, when J is given, their Jacobian (analytic; d/dr from the interpolant).
  const auto residuals = [&](const std::array<double, kN>& v, std::array<double, 3 * kK>& res,
                             std::array<std::array<double, kN>, 3 * kK>* jac) {
    const GltfEnergies en = gltf_energies(v[3]);
    const double s = v[4];
    int a = 5;  // argmax of f0 (the first on ties)
    for (int c = 6; c < 8; ++c) if (v[static_cast<std::size_t>(c)] > v[static_cast<std::size_t>(a)]) a = c;
    const double fmax = v[static_cast<std::size_t>(a)];
    double sum = 0.0;
    for (std::size_t k = 0; k < static_cast<std::size_t>(kK); ++k) {
      const double l5 = t.l5[k];
      const double weight = fmax * (1.0 - l5) + l5;  // the albedo of max3(F) / pi
      for (std::size_t c = 0; c < 3; ++c) {
        const double b = v[c], f0 = v[5 + c];
        const double r = b * (1.0 - s * weight) + s * (f0 * (en.e[k] - en.e5[k]) + en.e5[k]) - target[k][static_cast<int>(c)];
        res[3 * k + c] = r;
        sum += r * r;
        if (!jac) continue;
        std::array<double, kN>& row = (*jac)[3 * k + c];
        row.fill(0.0);
        row[c] = 1.0 - s * weight;
        row[3] = s * (f0 * (en.de[k] - en.de5[k]) + en.de5[k]);
        row[4] = -b * weight + f0 * (en.e[k] - en.e5[k]) + en.e5[k];
        row[5 + c] += s * (en.e[k] - en.e5[k]);
        row[static_cast<std::size_t>(a)] -= b * s * (1.0 - l5);
      }
    }
    return sum;
  };
  std::array<double, 3 * kK> res{};
  std::array<std::array<double, kN>, 3 * kK> jac{};
  double cost = residuals(x, res, &jac);
  double lambda = 1e-3;
  FastConversion out;
  for (int it = 0; it < options.max_steps && cost > 1e-20 && lambda < 1e12; ++it) {
    ++out.iterations;
    // Normal equations (J^T J + lambda diag) d = -J^T r, solved by Gaussian elimination with partial pivoting.
    std::array<std::array<double, kN + 1>, kN> a{};
    for (std::size_t i = 0; i < kN; ++i) {
      for (std::size_t j = 0; j < kN; ++j) {
        double sum = 0.0;
        for (std::size_t r = 0; r < res.size(); ++r) sum += jac[r][i] * jac[r][j];
        a[i][j] = sum;
      }
      double g = 0.0;
      for (std::size_t r = 0; r < res.size(); ++r) g += jac[r][i] * res[r];
      a[i][kN] = -g;
      a[i][i] += lambda * (a[i][i] + 1e-9);  // Marquardt's scaling; 1e-9 keeps a flat direction solvable
    }
    for (std::size_t col = 0; col < kN; ++col) {
      std::size_t p = col;
      for (std::size_t r = col + 1; r < kN; ++r) if (std::abs(a[r][col]) > std::abs(a[p][col])) p = r;
      std::swap(a[p], a[col]);
      for (std::size_t r = col + 1; r < kN; ++r) {
        const double f = a[r][col] / a[col][col];
        for (std::size_t c = col; c <= kN; ++c) a[r][c] -= f * a[col][c];
      }
    }
    std::array<double, kN> d{};
    for (std::size_t i = kN; i-- > 0;) {
      double sum = a[i][kN];
      for (std::size_t j = i + 1; j < kN; ++j) sum -= a[i][j] * d[j];
      d[i] = sum / a[i][i];
    }
    std::array<double, kN> y = x;
    for (std::size_t i = 0; i < kN; ++i) y[i] += d[i];
    clamp_x(y);
    std::array<double, 3 * kK> res_y{};
    const double cost_y = residuals(y, res_y, nullptr);
    if (cost_y < cost) {
      const bool small = cost - cost_y < 1e-12 * cost;
      x = y;
      cost = residuals(x, res, &jac);
      lambda = std::max(lambda / 4.0, 1e-9);
      if (small) break;
    } else {
      lambda *= 8.0;
    }
  }
  MetalRoughFactors& m = out.result;
  m.base_color = Rgb{x[0], x[1], x[2]};
  m.metallic = 0.0;
  m.roughness = x[3];
  m.ior = kFastIor;
  m.specular = x[4];
  m.specular_color = Rgb{x[5] / q, x[6] / q, x[7] / q};
  return out;
}

}  // namespace shadelab
