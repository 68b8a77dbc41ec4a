// lambert: f_r = kd / pi (Lambert 1760; the lecture's "Pure Lambertian" slide: rho_d / pi).
// eval is the kernel kernels/lambert.sl, the text the shader exporter also uses.
// Sampled with the cosine-weighted hemisphere, so the sample weight is exactly kd.
#pragma once

#include "shadelab/brdf/brdf.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class Lambert final : public Brdf {
 public:
  explicit Lambert(const Rgb& kd) : m_kd(kd), m_kp{kd}, m_k(kernel::lambert_prepare(m_kp)) {}
  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override;
  Rgb diffuse_albedo() const override { return m_kd; }
  std::optional<KernelBinding> kernel_binding() const override;

 protected:
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::lambert_eval>(m_k, wi, wo, out, n, check_unit);
  }

 private:
  Rgb m_kd;
  kernel::LambertParams m_kp;
  kernel::LambertState m_k;
};

}  // namespace shadelab
