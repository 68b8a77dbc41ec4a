// wrapped-diffuse: energy-conserving wrap lighting (McAuley, "Energy-Conserving Wrapped Diffuse", 2011;
// Lagarde, "PI or not to PI in game lighting equation", 2012, section "Wrap lighting in game"):
//
//   f_r cos(theta_i) = kd (cos(theta_i) + w) / (pi (1 + w)^2),   i.e.   f_r = kd (N.L + w) / (pi (1 + w)^2 N.L)
//
// w in [0, 1]; w = 0 is Lambert. The game form is kd (N.L + w)/(1 + w)^2 in game light units. The wrap
// response integrates to kd over the directions with N.L > -w (its normalization 1/(pi (1 + w))); above the
// geometric horizon it integrates to kd (1 + 2w)/(1 + w)^2 <= kd, which is what a renderer that gathers light
// only above the surface sees. f_r depends on L alone, so it is NOT reciprocal for w > 0, by design.
// eval is the kernel kernels/wrapped_diffuse.sl (the text shaders also use).
// Sampling: density (cos + w) / (pi (1 + 2w)), a mix of cosine (weight 1/(1+2w)) and uniform (2w/(1+2w))
// hemisphere sampling, so the sample weight is the constant kd (1 + 2w)/(1 + w)^2.
#pragma once

#include "shadelab/brdf/brdf.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class WrappedDiffuse final : public Brdf {
 public:
  WrappedDiffuse(const Rgb& kd, double w) : m_kd(kd), m_w(w), m_kp{kd, w}, m_k(kernel::wrapped_diffuse_prepare(m_kp)) {}
  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override;
  bool is_reciprocal() const override { return m_w == 0.0 || m_kd.is_black(); }
  Rgb diffuse_albedo() const override { return m_kd; }  // the wrap itself is applied by SH band factors
  double wrap() const { return m_w; }
  std::optional<KernelBinding> kernel_binding() const override;
  double game_wrap() const override { return m_w; }

 protected:
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::wrapped_diffuse_eval>(m_k, wi, wo, out, n, check_unit);
  }

 private:
  Rgb m_kd;
  double m_w;
  kernel::WrappedDiffuseParams m_kp;
  kernel::WrappedDiffuseState m_k;
};

}  // namespace shadelab
