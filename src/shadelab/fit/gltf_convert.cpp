#include "shadelab/fit/gltf_convert.h"

#include <nlopt.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "shadelab/analysis/albedo.h"

namespace shadelab {

namespace {

constexpr double kIor = 1000.0;  // PR #1719's "infinite" ior
constexpr int kDims = 9;         // base_color (3), metallic, roughness, specular, specular_color (3)
constexpr double kStopRms = 1e-7;  // the fit stops below this RMS (the fit quadrature's own accuracy)

// f0 = ((ior - 1)/(ior + 1))^2 specular_color (KHR_materials_ior, KHR_materials_specular).
double ior_f0(double ior) {
  const double q = (ior - 1.0) / (ior + 1.0);
  return q * q;
}

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

Gltf::Params gltf_params(const MetalRoughFactors& m) {
  Gltf::Params p;
  p.base_color = m.base_color;
  p.metallic = m.metallic;
  p.roughness = m.roughness;
  p.ior = m.ior;
  p.specular = m.specular;
  p.specular_color = m.specular_color;
  return p;
}

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

}  // namespace shadelab
