// minimalist-cook-torrance: f_r = kd/pi + ks (n + 1)(N.H)^n / (8 pi (L.H)^3)
// (Schüler, "An Efficient and Physically Plausible Real-Time Shading Model", ShaderX7 2.5, 2009; the zoo
// article's "Minimalist Cook-Torrance"). It is kd/pi + ks D F V with D = (n+1)/(2pi) (N.H)^n, the zoo's NDF
// row, and the combined FV = 1/(4 (L.H)^3): no Fresnel colour shift, linear in ks. Reciprocal, since
// L.H = V.H. Not energy conserving at grazing angles (the 1/(L.H)^3 grows without bound); `brdf check`
// reports its measured maximum albedo.
// eval is the kernel kernels/minimalist_cook_torrance.sl (the text shaders also use).
// Sampling: H from the power-cosine lobe (n+1)/(2pi) (N.H)^n, pdf = p_H / (4 V.H).
#pragma once

#include "shadelab/brdf/gloss.h"
#include "shadelab/brdf/lobe_mixture.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class MinimalistCookTorrance final : public LobeMixtureBrdf {
 public:
  MinimalistCookTorrance(const Rgb& kd, const Rgb& ks, double n);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override {
    return kernel::minimalist_cook_torrance_eval(m_k, wi, wo);
  }
  std::optional<KernelBinding> kernel_binding() const override;
  // (N.H)^n: the Phong lobe of n/4 (brdf/gloss.h); a gloss map's exponent is a Blinn-Phong one.
  double game_phong_exponent() const override { return phong_exponent_from_blinn_phong(m_n); }
  bool gloss_exponent_is_blinn_phong() const override { return true; }

 protected:
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::minimalist_cook_torrance_eval>(m_k, wi, wo, out, n, check_unit);
  }

  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  kernel::MinimalistCookTorranceParams m_kp;
  kernel::MinimalistCookTorranceState m_k;
  double m_n;
};

}  // namespace shadelab
