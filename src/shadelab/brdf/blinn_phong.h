// blinn-phong and blinn-phong-modified: the Blinn-Phong lobe (N.H)^n.
//
//   blinn-phong:          f_r = kd' + ks N (N.H)^n / (N.L)   (Blinn 1977; lecture 5, "The Blinn-Phong Model")
//   blinn-phong-modified: f_r = kd' + ks N (N.H)^n            (lecture 5, "The Modified Blinn-Phong Model")
//
// N, from the zoo (Schüler 2011), normalizing the RDF f_r cos(theta_i) with the viewer on the normal:
//   blinn-phong           exact (n+2)/(4 pi (2 - 2^(-n/2))),   lower (n+2)/(8 pi),   upper (n+4)/(8 pi)
//   blinn-phong-modified  exact (n+2)(n+4)/(8 pi (2^(-n/2)+n)), lower (n+6)/(8 pi), upper (n+8)/(8 pi)
// kd' = kd/pi when normalized, kd with normalization = none (the lecture's unnormalized form, N = 1).
// eval is the kernel kernels/blinn_phong.sl (the text shaders also use).
// Sampling: H from the power-cosine lobe (n+1)/(2 pi) (N.H)^n, L = reflect(V, H); pdf = p_H / (4 V.H).
#pragma once

#include "shadelab/brdf/gloss.h"
#include "shadelab/brdf/lobe_mixture.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class BlinnPhong final : public LobeMixtureBrdf {
 public:
  enum class Normalization { none, exact, lower, upper };
  BlinnPhong(const Rgb& kd, const Rgb& ks, double n, Normalization normalization, bool modified);

  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::blinn_phong_eval(m_k, wi, wo); }
  bool is_reciprocal() const override { return m_modified || m_ks.is_black(); }
  std::optional<KernelBinding> kernel_binding() const override;
  // (N.H)^n: the Phong lobe of n/4 (brdf/gloss.h); a gloss map's exponent is a Blinn-Phong one.
  double game_phong_exponent() const override { return phong_exponent_from_blinn_phong(m_n); }
  bool gloss_exponent_is_blinn_phong() const override { return true; }
  static double normalization_factor(double n, Normalization normalization, bool modified);

 protected:
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::blinn_phong_eval>(m_k, wi, wo, out, n, check_unit);
  }

  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  kernel::BlinnPhongParams m_kp;
  kernel::BlinnPhongState m_k;
  Rgb m_ks;
  double m_n;
  bool m_modified;
};

}  // namespace shadelab
