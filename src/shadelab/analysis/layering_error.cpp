#include "shadelab/analysis/layering_error.h"

#include <cmath>
#include <cstdio>

#include "shadelab/analysis/albedo.h"
#include "shadelab/brdf/gltf.h"
#include "shadelab/core/constants.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/numeric/quadrature.h"

namespace shadelab {

namespace {

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

// The glTF clearcoat's own lobe with the Fresnel at V.H: D_GGX V_GGX F_schlick(0.04) (the lobe the albedo-scaled
// form adds, and whose directional albedo E_c dims the base).
double coat_lobe(const Vec3& wi, const Vec3& wo, double alpha) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
  const Vec3 h = normalize(wi + wo);
  return kernel::D_ggx(h.z, alpha) * kernel::V_smith_ggx_correlated(wo.z, wi.z, alpha) *
         kernel::F_schlick(dot(wo, h), 0.04);
}

// E_c(wo): the coat lobe's directional albedo by quadrature about the mirror direction.
double coat_albedo(const Vec3& wo, double alpha) {
  QuadratureOptions o;
  o.rel_tol = 1e-8;
  o.abs_tol = 1e-12;
  const Vec3 mirror{-wo.x, -wo.y, wo.z};
  const VectorQuadratureResult q = integrate_directions(
      [&](const Vec3& wi, std::span<double> out) { out[0] = coat_lobe(wi, wo, alpha) * wi.z; }, 1, mirror,
      SphereRegion::upper, o);
  return q.value[0];
}

ParamAssignments with(ParamAssignments p, const std::string& name, const std::string& value) {
  for (auto& [k, v] : p) {
    if (k == name) {
      v = value;
      return p;
    }
  }
  p.emplace_back(name, value);
  return p;
}

}  // namespace

Result<LayeringErrorReport> layering_error(const std::string& model, const ParamAssignments& params,
                                           const LayeringErrorOptions& options) {
  if (model != "gltf") {
    return make_error("layering-error: model '" + model +
                      "' has no layering shortcut this measures (it measures gltf's clearcoat)");
  }
  auto made = make_brdf(model, params);
  if (!made) return made.error();
  const auto* g = dynamic_cast<const Gltf*>(made->get());
  if (g == nullptr) throw std::logic_error("the gltf model is not a Gltf");
  const kernel::GltfState& s = g->state();
  const std::string who = "layering-error gltf: ";
  if (!(s.clearcoat > 0.0)) return make_error(who + "parameter 'clearcoat' is 0: nothing is layered");
  if (s.sheen_max > 0.0) {
    return make_error(who + "parameter 'sheen_color' is not 0: the ground truth has no sheen layer (set it to 0)");
  }
  if (s.alpha_t != s.alpha_b) {
    return make_error(who + "parameter 'anisotropy_strength' is not 0: the ground truth's bases are isotropic");
  }
  std::string base;
  if (s.metallic == 1.0) {
    base = "conductor";
  } else if (s.metallic == 0.0 && s.specular == 0.0) {
    base = "lambert";
  } else {
    return make_error(who + "parameter 'metallic' = " + number(s.metallic) + " (specular " + number(s.specular) +
                      "): the ground truth holds a conductor (metallic 1) or a Lambertian base (metallic 0 with "
                      "specular 0) exactly, not glTF's Fresnel-mixed dielectric");
  }
  const Rgb color(s.base_color);
  const std::string color_text = number(color.r) + "," + number(color.g) + "," + number(color.b);
  LayeringErrorReport report;
  report.model = model;
  report.params = params;
  report.truth_params = {{"coat_ior", "1.5"},
                         {"coat_roughness", number(std::sqrt(s.clearcoat_alpha))},
                         {"coat_color", "1"},
                         {"coat_thickness", "0"},
                         {"base", base},
                         {"base_color", color_text},
                         {"base_roughness", number(std::sqrt(s.alpha_b))},
                         {"base_f82", "1"},
                         {"walk_samples", std::to_string(options.walks)},
                         {"seed", std::to_string(options.seed)}};
  auto layered = make_brdf("layered", report.truth_params);
  if (!layered) return layered.error();
  // The albedo by the truth's sampler: one walk per sample (each weight is unbiased; more walks per eval only
  // cost time there).
  ParamAssignments one_walk = report.truth_params;
  for (auto& [k, v] : one_walk) {
    if (k == "walk_samples") v = "1";
  }
  auto layered_albedo = make_brdf("layered", one_walk);
  if (!layered_albedo) return layered_albedo.error();
  for (auto& [k, v] : one_walk) {
    if (k == "base_color") v = "1";
  }
  auto layered_white = make_brdf("layered", one_walk);
  if (!layered_white) return layered_white.error();
  auto base_only = make_brdf(model, with(params, "clearcoat", "0"));
  if (!base_only) return base_only.error();
  const Brdf& fl = **layered;
  const Brdf& fb = **base_only;
  const double c = s.clearcoat;
  const double ac = s.clearcoat_alpha;

  AlbedoOptions quad;
  quad.quadrature.rel_tol = 1e-8;
  AlbedoOptions sampled;
  sampled.stochastic_samples = options.albedo_samples;
  for (double t : options.thetas_deg) {
    const double th = t * pi / 180.0;
    const Vec3 wo{std::sin(th), 0.0, std::cos(th)};
    const AlbedoResult al = directional_albedo(**layered_albedo, wo, sampled);
    const double ab = directional_albedo(fb, wo, quad).albedo.g;
    const double ec = coat_albedo(wo, ac);
    LayeringAlbedoRow row;
    row.theta_deg = t;
    row.truth = (1.0 - c) * ab + c * al.albedo.g;
    row.truth_error = c * al.error.g;
    row.model = directional_albedo(*g, wo, quad).albedo.g;
    row.albedo_scaled = (1.0 - c * ec) * ab + c * ec;
    AlbedoOptions furnace = sampled;
    furnace.stochastic_samples = std::max(1000, options.albedo_samples / 5);
    row.truth_furnace = directional_albedo(**layered_white, wo, furnace).albedo.g;
    report.max_albedo_difference = std::max(report.max_albedo_difference, std::abs(row.model - row.truth));
    report.max_albedo_scaled_difference =
        std::max(report.max_albedo_scaled_difference, std::abs(row.albedo_scaled - row.truth));
    report.albedo.push_back(row);

    // The lobe over a 16 x 32 grid uniform in (cos theta_i, phi_i).
    const int nt = 16;
    const int np = 32;
    double sum_t = 0.0, sum_n = 0.0, sum_m = 0.0, sum_a = 0.0;
    for (int a = 0; a < nt; ++a) {
      const double ci = (a + 0.5) / nt;
      const double si = std::sqrt(1.0 - ci * ci);
      for (int b = 0; b < np; ++b) {
        const double phi = two_pi * (b + 0.5) / np;
        const Vec3 wi{si * std::cos(phi), si * std::sin(phi), ci};
        const double base_v = fb.eval(wi, wo).g;
        const double truth = (1.0 - c) * base_v + c * fl.eval(wi, wo).g;
        const double noise = c * fl.eval_standard_error(wi, wo).value_or(Rgb{}).g;
        const double m = g->eval(wi, wo).g;
        const double scaled = (1.0 - c * ec) * base_v + c * coat_lobe(wi, wo, ac);
        sum_t += truth * truth * ci * ci;
        sum_n += noise * noise * ci * ci;
        sum_m += (m - truth) * (m - truth) * ci * ci;
        sum_a += (scaled - truth) * (scaled - truth) * ci * ci;
      }
    }
    const double n = nt * np;
    report.lobe.push_back({t, std::sqrt(sum_t / n), std::sqrt(sum_n / n), std::sqrt(sum_m / n), std::sqrt(sum_a / n)});
  }
  return report;
}

}  // namespace shadelab
