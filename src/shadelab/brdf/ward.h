// ward and ward-anisotropic: Ward's Gaussian-slope lobe (Ward, "Measuring and Modeling Anisotropic
// Reflection", SIGGRAPH 1992, eq. 4 and 5a; lecture 5 "Ward Model"):
//
//   ward:             f_r = kd/pi + ks exp(-tan^2(theta_h)/alpha^2) / (4 pi alpha^2 sqrt(N.L N.V))
//   ward-anisotropic: f_r = kd/pi + ks exp(-tan^2(theta_h)(cos^2(phi_h)/ax^2 + sin^2(phi_h)/ay^2))
//                                      / (4 pi ax ay sqrt(N.L N.V))
//
// The lecture's anisotropic slide shows f_r times N.L (the sqrt(N.L / N.V) factor); eval here returns f_r
// without the cosine, as every model does. The slide's exponent 2((H.x/ax)^2 + (H.y/ay)^2)/(1 + H.N) is
// Ward's cheaper approximation of the tan^2 form, equal to first order near H = N; we use the exact
// tan^2 form so that ward-anisotropic with ax = ay equals ward (docs/models/ward.md).
// Reciprocal. Tangent = +X (alpha_x), bitangent = +Y (alpha_y).
// eval is the kernel kernels/ward.sl (the text shaders also use).
// Sampling (Walter, "Notes on the Ward BRDF", 2005): phi_h = atan(ay/ax tan(2 pi u1)),
// tan^2(theta_h) = -ln(u0) / (cos^2/ax^2 + sin^2/ay^2); p_H = exp(...) / (pi ax ay cos^3(theta_h)),
// pdf = p_H / (4 V.H).
#pragma once

#include "shadelab/brdf/gloss.h"
#include "shadelab/brdf/lobe_mixture.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class Ward final : public LobeMixtureBrdf {
 public:
  Ward(const Rgb& kd, const Rgb& ks, double alpha_x, double alpha_y);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::ward_eval(m_k, wi, wo); }
  std::optional<KernelBinding> kernel_binding() const override;
  // Ward's alpha as a Beckmann m (the mean of alpha_x and alpha_y), n = 2/m^2 - 2, as a Phong lobe of n/4.
  double game_phong_exponent() const override {
    return phong_exponent_from_blinn_phong(exponent_from_beckmann_m(0.5 * (m_ax + m_ay)));
  }

  // The exponent's argument tan^2(theta_h)(cos^2/ax^2 + sin^2/ay^2) for a unit half vector h.
  double slope_term(const Vec3& h) const;

 protected:
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::ward_eval>(m_k, wi, wo, out, n, check_unit);
  }

  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  kernel::WardParams m_kp;
  kernel::WardState m_k;
  double m_ax;
  double m_ay;
};

}  // namespace shadelab
