// gltf: glTF 2.0's metallic-roughness material with KHR_materials_ior, _specular, _anisotropy, _sheen and _clearcoat,
// as the specifications write its BRDF (the formulas and their sources: kernels/gltf.sl; docs/models/gltf.md):
//
//   f = (1 - clearcoat Fc(N.V)) [sheen_color D_charlie V_sheen + s mix(dielectric, metal, metallic)]
//       + clearcoat Fc(N.V) D_GGX V_GGX(clearcoat_roughness^2)
//   dielectric = (1 - specular max3 F) base_color / pi + specular F D V,  F = Schlick(f0 = ((ior-1)/(ior+1))^2
//       specular_color (clamped to 1), V.H);  metal = (base_color + (1 - base_color)(1 - V.H)^5) D V
//   D V: anisotropic GGX, alpha_t = mix(roughness^2, 1, anisotropy_strength^2), height-correlated Smith
//   s = max(0, min(1 - max3(sheen_color) E(N.V), 1 - max3(sheen_color) E(N.L))), E the sheen table (sheen.sl)
//
// eval is the kernel kernels/gltf.sl. emissive and emissive_strength (KHR_materials_emissive_strength) are carried
// for renderers (emission() = emissive x emissive_strength, radiance in the scene's units) and are not part of f.
// The sampler is a one-sample mixture with an exact density (Veach 1997, 9.2.4): the cosine lobe (diffuse), the
// bounded visible-normal sampler of the anisotropic specular lobe (in its rotated frame) and of the clearcoat
// lobe, and the uniform hemisphere for the sheen (its lobe reaches grazing directions a cosine lobe rarely
// draws), each picked with a probability proportional to an estimate of its albedo.
#pragma once

#include "shadelab/brdf/brdf.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class Gltf final : public Brdf {
 public:
  enum class SheenVisibility { charlie, ashikhmin };  // the kernel's SHEEN_VISIBILITY_* numbering
  struct Params {
    Rgb base_color{1.0, 1.0, 1.0};
    double metallic = 1.0;
    double roughness = 1.0;
    double ior = 1.5;
    double specular = 1.0;
    Rgb specular_color{1.0, 1.0, 1.0};
    double anisotropy_strength = 0.0;
    double anisotropy_rotation = 0.0;  // radians
    Rgb sheen_color{0.0, 0.0, 0.0};
    double sheen_roughness = 0.0;
    SheenVisibility sheen_visibility = SheenVisibility::charlie;
    double clearcoat = 0.0;
    double clearcoat_roughness = 0.0;
    Rgb emissive{0.0, 0.0, 0.0};
    double emissive_strength = 1.0;
  };
  explicit Gltf(const Params& p);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::gltf_eval(m_k, wi, wo); }
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::gltf_eval>(m_k, wi, wo, out, n, check_unit);
  }
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override;
  bool pdf_smooth_below_horizon() const override { return false; }
  bool is_reciprocal() const override { return !(m_p.clearcoat > 0.0); }
  Rgb diffuse_albedo() const override;
  std::optional<KernelBinding> kernel_binding() const override;
  double game_phong_exponent() const override;
  Rgb emission() const { return m_p.emissive * m_p.emissive_strength; }
  const kernel::GltfState& state() const { return m_k; }

 private:
  // The lobes' selection probabilities: diffuse (cosine), specular, clearcoat, sheen (uniform).
  struct Mixture {
    double diffuse = 1.0;
    double specular = 0.0;
    double clearcoat = 0.0;
    double sheen = 0.0;
  };
  Params m_p;
  kernel::GltfState m_k;
  Mixture m_mix;
};

}  // namespace shadelab
