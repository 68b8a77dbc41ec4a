#include "shadelab/brdf/wrapped_diffuse.h"

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

std::optional<KernelBinding> WrappedDiffuse::kernel_binding() const {
  return KernelBinding{"wrapped_diffuse", {}}.add("kd", m_kp.kd).add("w", m_kp.w);
}

Rgb WrappedDiffuse::eval(const Vec3& wi, const Vec3& wo) const { return kernel::wrapped_diffuse_eval(m_k, wi, wo); }

double WrappedDiffuse::pdf(const Vec3& wi, const Vec3& wo) const {
  if (wo.z <= 0.0 || wi.z < 0.0) return 0.0;
  return (wi.z + m_w) / (pi * (1.0 + 2.0 * m_w));  // (cos + w) / integral over the hemisphere
}

BrdfSample WrappedDiffuse::sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  BrdfSample s;
  if (wo.z <= 0.0) return s;
  const double p_cos = 1.0 / (1.0 + 2.0 * m_w);
  s.wi = u_lobe < p_cos ? sample_cosine_hemisphere(u) : sample_uniform_hemisphere(u);
  s.pdf = pdf(s.wi, wo);
  if (s.pdf > 0.0 && s.wi.z > 0.0) {
    const double one_w = 1.0 + m_w;
    s.weight = m_kd * ((1.0 + 2.0 * m_w) / (one_w * one_w));  // f cos / pdf, constant
  }
  return s;
}

ModelInfo wrapped_diffuse_model() {
  ModelInfo info;
  info.name = "wrapped-diffuse";
  info.summary = "kd (N.L + w) / (pi (1 + w)^2 N.L)";
  info.source = "McAuley 2011 'Energy-Conserving Wrapped Diffuse'; Lagarde 2012 'PI or not to PI'";
  info.params = {kd_param("0.8"), {"w", ParamKind::scalar, "0.5", 0.0, 1.0, {}, "wrap amount (0 = Lambert)", 0, {}}};
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    return BrdfPtr(new WrappedDiffuse(p.color("kd"), p.scalar("w")));
  };
  return info;
}

}  // namespace shadelab
