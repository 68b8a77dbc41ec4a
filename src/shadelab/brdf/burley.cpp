#include "shadelab/brdf/burley.h"

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

std::optional<KernelBinding> Burley::kernel_binding() const {
  return KernelBinding{"burley", {}}.add("kd", m_kd).add("roughness", m_roughness);
}

double Burley::pdf(const Vec3& wi, const Vec3& wo) const { return wo.z > 0.0 ? cosine_hemisphere_pdf(wi) : 0.0; }

BrdfSample Burley::sample(const Vec3& wo, Vec2 u, double) const {
  BrdfSample s;
  if (wo.z <= 0.0) return s;
  s.wi = sample_cosine_hemisphere(u);
  s.pdf = cosine_hemisphere_pdf(s.wi);
  if (s.pdf > 0.0 && s.wi.z > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
  return s;
}

ModelInfo burley_model() {
  ModelInfo info;
  info.name = "burley";
  info.summary = "kd/pi (1 + (F_D90-1)(1-N.L)^5)(1 + (F_D90-1)(1-N.V)^5), F_D90 = 0.5 + 2 roughness (L.H)^2";
  info.source = "Burley 2012, 'Physically-Based Shading at Disney', section 5.3";
  info.params = {kd_param("0.8"),
                 {"roughness", ParamKind::scalar, "0.5", 0.0, 1.0, {}, "Burley's (perceptual) roughness", 0, {}}};
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    return BrdfPtr(new Burley(p.color("kd"), p.scalar("roughness")));
  };
  return info;
}

}  // namespace shadelab
