#include "shadelab/brdf/game_lobe.h"

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/filament.h"
#include "shadelab/brdf/ggx.h"
#include "shadelab/brdf/gloss.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/wrapped_diffuse.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {

double phong_exponent_from_alpha(double perceptual_roughness) {
  const double alpha = perceptual_roughness * perceptual_roughness;  // alpha = r^2
  return phong_exponent_from_blinn_phong(exponent_from_beckmann_m(alpha));
}

double game_phong_exponent(const std::string& model, const ParamValues& p) {
  if (model == "phong" || model == "phong-modified") return p.scalar("n");
  if (model == "blinn-phong" || model == "blinn-phong-modified" || model == "minimalist-cook-torrance") {
    return phong_exponent_from_blinn_phong(p.scalar("n"));
  }
  if (model == "cook-torrance") {
    const double n = p.is_set("n") ? p.scalar("n") : exponent_from_beckmann_m(p.scalar("m"));
    return phong_exponent_from_blinn_phong(n);
  }
  if (model == "ward") return phong_exponent_from_blinn_phong(exponent_from_beckmann_m(p.scalar("alpha")));
  if (model == "ward-anisotropic") {
    const double a = 0.5 * (p.scalar("alpha_x") + p.scalar("alpha_y"));
    return phong_exponent_from_blinn_phong(exponent_from_beckmann_m(a));
  }
  if (model == "lafortune") return p.lobes("lobes").front()[3];
  // GGX's alpha is a roughness like Beckmann's m (both the RMS slope's scale; Walter et al. 2007 section 5.2).
  if (model == "ggx") {
    double ax = p.scalar("alpha");
    double ay = ax;
    if (p.is_set("roughness")) ax = ay = p.scalar("roughness") * p.scalar("roughness");
    if (p.is_set("alpha_x")) {
      ax = p.scalar("alpha_x");
      ay = p.scalar("alpha_y");
    }
    return phong_exponent_from_blinn_phong(exponent_from_beckmann_m(std::sqrt(ax * ay)));
  }
  if (model == "filament") return phong_exponent_from_alpha(p.scalar("perceptual_roughness"));
  return 0.0;  // no specular lobe
}

GameLobe game_lobe(const std::string& model, const ParamValues& p, const Brdf& f) {
  GameLobe info;
  info.exponent = game_phong_exponent(model, p);
  info.blinn_like = model.find("blinn") != std::string::npos || model == "minimalist-cook-torrance" || model == "cook-torrance";
  if (const auto* w = dynamic_cast<const WrappedDiffuse*>(&f)) info.wrap = w->wrap();
  constexpr int bins = kernel::GAME_ALBEDO_BINS;
  for (int b = 0; b < bins; ++b) {
    const double c = (b + 0.5) / bins;
    const Vec3 wo{std::sqrt(1.0 - c * c), 0.0, c};
    Pcg32 rng(1234, static_cast<std::uint64_t>(b));
    Rgb sum;
    const int samples = 4096;
    for (int s = 0; s < samples; ++s) {
      sum += f.sample(wo, {rng.next_double(), rng.next_double()}, rng.next_double()).weight;
    }
    const Rgb spec = sum / samples - f.diffuse_albedo();
    info.specular_albedo[static_cast<std::size_t>(b)] = {std::max(0.0, spec.r), std::max(0.0, spec.g), std::max(0.0, spec.b)};
  }
  return info;
}

kernel::GameSpecularAlbedo game_specular_albedo_table(const GameLobe& lobe) {
  kernel::GameSpecularAlbedo t;
  for (std::size_t b = 0; b < lobe.specular_albedo.size(); ++b) t.bin[b] = lobe.specular_albedo[b];
  return t;
}

std::optional<GgxSplitSumLobe> ggx_split_sum_lobe(const Brdf& f) {
  if (const auto* g = dynamic_cast<const Ggx*>(&f)) {
    const Ggx::Params& p = g->params();
    GgxSplitSumLobe lobe;
    lobe.roughness = std::sqrt(std::sqrt(p.alpha_x * p.alpha_y));  // alpha = r^2
    // Reflectance at normal incidence by the model's own Fresnel (fresnel.sl F_by_kind_rgb at cos = 1).
    const Rgb f0 = Rgb(kernel::F_by_kind_rgb(static_cast<int>(p.f), 1.0, p.ior, p.k, p.f0));
    lobe.f0 = p.ks * f0;
    lobe.f90 = p.ks;
    if (p.ms == Ggx::MultipleScattering::kulla_conty) lobe.ggx_ms = &g->state();
    return lobe;
  }
  if (const auto* m = dynamic_cast<const Filament*>(&f)) {
    const kernel::FilamentState& s = m->state();
    GgxSplitSumLobe lobe;
    lobe.roughness = std::sqrt(s.alpha);
    lobe.f0 = Rgb(s.f0);
    lobe.f90 = Rgb::gray(1.0);
    if (s.energy_compensation == 1) lobe.filament = &s;
    return lobe;
  }
  return std::nullopt;
}

}  // namespace shadelab

