// phong and phong-modified: the Phong lobe (R.L)^n about the mirror direction R of the viewer.
//
//   phong:          f_r = kd' + ks N (R.L)^n / (N.L)   (Phong 1975 as a BRDF; lecture 5, "Phong Reflection Model")
//   phong-modified: f_r = kd' + ks N (R.L)^n            (Lewis 1994; Lafortune & Willems 1994)
//
// normalization = exact: N = (n + 1)/(2 pi) for phong and (n + 2)/(2 pi) for phong-modified (the zoo's RDF
// rows, Schüler 2011), and kd' = kd/pi; then with the viewer on the normal the specular albedo is exactly ks.
// normalization = none: N = 1 and kd' = kd, the lecture's unnormalized form (it does not conserve energy).
// The original form divides by N.L and so is not reciprocal; the modified form is.
// eval is the kernel kernels/phong.sl (the text shaders also use).
// Sampling: a power-cosine lobe of exponent n about R (pdf (n + 1)/(2 pi) (R.L)^n over the sphere).
#pragma once

#include "shadelab/brdf/lobe_mixture.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class Phong final : public LobeMixtureBrdf {
 public:
  enum class Normalization { none, exact };
  Phong(const Rgb& kd, const Rgb& ks, double n, Normalization normalization, bool modified);

  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::phong_eval(m_k, wi, wo); }
  bool is_reciprocal() const override { return m_modified || m_ks.is_black(); }
  std::optional<KernelBinding> kernel_binding() const override;
  double game_phong_exponent() const override { return m_n; }  // the lobe is (R.L)^n
  // The constant N in front of the lobe.
  static double normalization_factor(double n, Normalization normalization, bool modified);

 protected:
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::phong_eval>(m_k, wi, wo, out, n, check_unit);
  }

  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  kernel::PhongParams m_kp;
  kernel::PhongState m_k;
  Rgb m_ks;
  double m_n;
  bool m_modified;
};

}  // namespace shadelab
