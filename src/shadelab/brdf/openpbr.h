// openpbr: OpenPBR Surface 1.1's reflection (the opaque, non-thin-walled material: base metal / glossy-diffuse
// dielectric with EON diffuse, coat with darkening and absorption, fuzz), albedo-scaled as its specification
// layers it, in two forms (layering = view | reciprocal). The formulas and their sources: kernels/openpbr.sl;
// parameters, departures and measured figures: docs/models/openpbr.md.
//
//   f = F_w f_fuzz + S_fuzz [C f_coat + lerp(1, T S_coat, C) lerp(1, Delta, C delta) f_base]
//   f_base = M f_metal(F82-tint, Kulla-Conty) + (1 - M) [f_dielectric + S_diel f_EON]
//
// eval is the kernel kernels/openpbr.sl (compiled through kernels/openpbr.h). The sampler is a one-sample mixture
// with an exact density (Veach 1997, 9.2.4): the cosine lobe (diffuse and the metal's multiple scattering), the
// bounded visible-normal samplers of the base's anisotropic GGX and of the coat's GGX (Eto & Tokuyoshi 2023), and
// the fuzz's LTC (a cosine lobe through the LTC's matrix, Heitz et al. 2016), each picked with a probability
// proportional to an estimate of its albedo. The model has no shader (docs/models/openpbr.md, "Shaders").
#pragma once

#include "shadelab/brdf/brdf.h"
#include "shadelab/kernels/openpbr.h"

namespace shadelab {

class Openpbr final : public Brdf {
 public:
  enum class Layering { view, reciprocal };  // the kernel's OPENPBR_LAYERING_* numbering
  struct Params {  // OpenPBR 1.1's defaults
    double base_weight = 1.0;
    Rgb base_color{0.8, 0.8, 0.8};
    double base_metalness = 0.0;
    double base_diffuse_roughness = 0.0;
    double specular_weight = 1.0;
    Rgb specular_color{1.0, 1.0, 1.0};
    double specular_roughness = 0.3;
    double specular_roughness_anisotropy = 0.0;
    double specular_ior = 1.5;
    double coat_weight = 0.0;
    Rgb coat_color{1.0, 1.0, 1.0};
    double coat_roughness = 0.0;
    double coat_ior = 1.6;
    double coat_darkening = 1.0;
    double fuzz_weight = 0.0;
    Rgb fuzz_color{1.0, 1.0, 1.0};
    double fuzz_roughness = 0.5;
    Layering layering = Layering::view;
  };
  explicit Openpbr(const Params& p);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::openpbr_eval(m_k, wi, wo); }
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::openpbr_eval>(m_k, wi, wo, out, n, check_unit);
  }
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override;
  bool pdf_smooth_below_horizon() const override { return false; }
  bool is_reciprocal() const override;
  Rgb diffuse_albedo() const override;
  double game_phong_exponent() const override;
  const Params& params() const { return m_p; }
  const kernel::OpenpbrState& state() const { return m_k; }

 private:
  // The lobes' selection probabilities: cosine (diffuse, the metal's multiple scattering), base specular, coat, fuzz.
  struct Mixture {
    double cosine = 1.0;
    double specular = 0.0;
    double coat = 0.0;
    double fuzz = 0.0;
  };
  Params m_p;
  kernel::OpenpbrState m_k;
  Mixture m_mix;
};

}  // namespace shadelab
