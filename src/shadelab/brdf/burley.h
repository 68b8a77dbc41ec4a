// burley: the Disney diffuse BRDF (Burley, "Physically-Based Shading at Disney", SIGGRAPH 2012 course notes,
// section 5.3):
//
//   f_r = kd/pi (1 + (F_D90 - 1)(1 - cos theta_l)^5) (1 + (F_D90 - 1)(1 - cos theta_v)^5),
//   F_D90 = 0.5 + 2 roughness cos^2(theta_d),  theta_d = the angle between L and H (= between V and H).
//
// roughness is Burley's artist parameter in [0, 1]. The form is symmetric in L and V, hence reciprocal
// (measured to 1e-12 by the suite); it is not energy conserving: its albedo exceeds kd at grazing for rough
// surfaces (the retro-reflective rise) and falls below kd for smooth ones (docs/models/burley.md).
// eval is the kernel kernels/burley.sl. Sampled with the cosine-weighted hemisphere.
#pragma once

#include "shadelab/brdf/brdf.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class Burley final : public Brdf {
 public:
  Burley(const Rgb& kd, double roughness)
      : m_kd(kd), m_roughness(roughness), m_k(kernel::burley_prepare({kd, roughness})) {}
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::burley_eval(m_k, wi, wo); }
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::burley_eval>(m_k, wi, wo, out, n, check_unit);
  }
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override;
  // kd: what a game multiplies by diffuse irradiance / pi (Burley's factors are 1 at normal incidence
  // for roughness 0.25 and average near 1; the view-dependent part is left to the direct lights).
  Rgb diffuse_albedo() const override { return m_kd; }
  std::optional<KernelBinding> kernel_binding() const override;

 private:
  Rgb m_kd;
  double m_roughness;
  kernel::BurleyState m_k;
};

}  // namespace shadelab
