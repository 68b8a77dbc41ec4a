// principled-v1: Blender 3.4's Principled BSDF as Cycles 3.4 evaluates it, reflection only (no transmission,
// subsurface or emission), with the node's socket names and defaults:
//
//   f = f_diffuse + f_sheen + f_specular + f_clearcoat      (added, none dimming another: the albedo can exceed 1)
//   f_diffuse   = base_color (1 - metallic) / pi [(1 - FV/2)(1 - FL/2) + RR (FL + FV + FL FV (RR - 1))],
//                 FL, FV = (1 - N.L)^5, (1 - N.V)^5, RR = roughness (1 + L.V)     (Burley 2012 with retro-reflection)
//   f_sheen     = sheen (1 - metallic) mix(1, base_color / lum, sheen_tint) (1 - L.H)^5
//   f_specular  = F D_GGX(a_x, a_y) G1(L) G1(V) / (4 N.L N.V), a_x = min(1, r^2 / aspect), a_y = r^2 aspect,
//                 aspect = sqrt(1 - 0.9 anisotropic), tangent turned by 2 pi anisotropic_rotation,
//                 F = mix(cspec0, 1, FH), FH = (F_diel(L.H, eta) - F0) / (1 - F0), F0 = 0.08 specular,
//                 cspec0 = 0.08 specular mix(1, base_color / lum', specular_tint) (1 - metallic) + base_color metallic
//   f_clearcoat = 0.25 clearcoat F_diel(L.H, 1.5) D_GTR1(clearcoat_roughness^2) G1_0.25(L) G1_0.25(V) / (4 N.L N.V)
//
// The formulas, their sources line by line and what is left out: kernels/principled_v1.sl (eval is that kernel)
// and docs/models/principled-v1.md. Reciprocal exactly (is_reciprocal() true).
//
// Sampling: a one-sample mixture (LobeMixtureBrdf) of the cosine lobe (for the diffuse and sheen lobes), the
// bounded VNDF sampler of the specular GGX in the rotated tangent frame (microfacet.h) and GTR1's half-vector
// sampler for the clearcoat (Burley 2012, appendix B, eq. 5: h with density D_GTR1(h) cos(theta_h)), each with its
// exact density, picked in proportion to rough albedo estimates of the lobes.
#pragma once

#include "shadelab/brdf/lobe_mixture.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class PrincipledV1 final : public LobeMixtureBrdf {
 public:
  struct Params {  // Blender 3.4's Principled BSDF node defaults
    Rgb base_color{0.8, 0.8, 0.8};
    double metallic = 0.0;
    double specular = 0.5;
    double specular_tint = 0.0;
    double roughness = 0.5;
    double anisotropic = 0.0;
    double anisotropic_rotation = 0.0;
    double sheen = 0.0;
    double sheen_tint = 0.5;
    double clearcoat = 0.0;
    double clearcoat_roughness = 0.03;
  };
  explicit PrincipledV1(const Params& p);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::principled_v1_eval(m_k, wi, wo); }
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::principled_v1_eval>(m_k, wi, wo, out, n, check_unit);
  }
  // The bounded VNDF sampler's density jumps at its support's edge below the horizon (brdf.h).
  bool pdf_smooth_below_horizon() const override { return false; }
  std::optional<KernelBinding> kernel_binding() const override;
  double game_phong_exponent() const override;
  const Params& params() const { return m_p; }
  const kernel::PrincipledV1State& state() const { return m_k; }
  // The lobe probabilities of the sampler: cosine (diffuse and sheen), specular GGX, clearcoat GTR1.
  double cosine_probability() const { return m_p_diffuse; }
  double clearcoat_share() const { return m_clearcoat_share; }  // of the non-cosine part

 protected:
  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  Params m_p;
  kernel::PrincipledV1State m_k;
  double m_clearcoat_share = 0.0;
};

// GTR1's half-vector sampler (Burley 2012, appendix B, eq. 5): cos^2(theta_h) = (1 - a^(2 (1 - u.x))) / (1 - a^2),
// phi = 2 pi u.y, so h has the density D_GTR1(h) cos(theta_h) per solid angle; a in (0, 1] (a = 1: cos^2 = 1 - u.x).
Vec3 sample_gtr1(Vec2 u, double alpha);
// The density of wi = reflect(wo, h) for that h: D_GTR1(h) h.z / (4 |wo.h|), h the half vector of wi and wo.
double gtr1_reflection_pdf(const Vec3& wi, const Vec3& wo, double alpha);

}  // namespace shadelab
