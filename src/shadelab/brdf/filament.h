// filament: Filament's standard (metallic-roughness) model, with its documentation's formulas
// ("Physically Based Rendering in Filament", chapter "Material system"):
//
//   f_r = Fd + Fr
//   Fd  = (1 - metallic) base_color / pi                  (diffuse = lambert, "Diffuse BRDF")
//       | (1 - metallic) base_color Fd_Burley(alpha)     (diffuse = burley, burley.sl's factor / pi)
//   Fr  = D_GGX(N.H, a) V_SmithGGXCorrelated(N.V, N.L, a) F_Schlick(L.H, f0, f90 = 1), a = perceptual_roughness^2
//   f0  = 0.16 reflectance^2 (1 - metallic) + base_color metallic ("Reflectance remapping")
//   energy_compensation = on: Fr *= 1 + f0 (1/E(N.V) - 1), E the single-scattering albedo with F = 1 (Filament's
//       dfg.y; here the table of kernels/ggx_energy.sl, "Energy loss in specular reflectance").
//
// The compensation scales the lobe by a function of N.V alone: with f0 > 0 the model is not reciprocal
// (is_reciprocal() says so). eval is the kernel kernels/filament.sl. The specular lobe is sampled with the
// bounded VNDF sampler (microfacet.h), the diffuse one with the cosine lobe.
#pragma once

#include "shadelab/brdf/lobe_mixture.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class Filament final : public LobeMixtureBrdf {
 public:
  enum class Diffuse { lambert, burley };  // the kernel's FILAMENT_DIFFUSE_* numbering
  struct Params {
    Rgb base_color{0.8, 0.8, 0.8};
    double metallic = 0.0;
    double perceptual_roughness = 0.5;
    double reflectance = 0.5;
    Diffuse diffuse = Diffuse::lambert;
    bool energy_compensation = true;
  };
  explicit Filament(const Params& p);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::filament_eval(m_k, wi, wo); }
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::filament_eval>(m_k, wi, wo, out, n, check_unit);
  }
  // The visible-normal samplers' densities jump at their support's edge below the horizon (brdf.h).
  bool pdf_smooth_below_horizon() const override { return false; }
  bool is_reciprocal() const override;
  std::optional<KernelBinding> kernel_binding() const override;
  double game_phong_exponent() const override { return phong_exponent_from_ggx_alpha(m_k.alpha); }
  std::optional<SplitSumInputs> split_sum_inputs() const override;
  const kernel::FilamentState& state() const { return m_k; }

 protected:
  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  Params m_p;
  kernel::FilamentState m_k;
};

}  // namespace shadelab
