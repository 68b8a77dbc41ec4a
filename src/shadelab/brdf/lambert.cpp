#include "shadelab/brdf/lambert.h"

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

std::optional<KernelBinding> Lambert::kernel_binding() const {
  return KernelBinding{"lambert", {}}.add("kd", m_kp.kd);
}

Rgb Lambert::eval(const Vec3& wi, const Vec3& wo) const {
  return kernel::lambert_eval(m_k, wi, wo);  // kd / pi above the horizon
}

double Lambert::pdf(const Vec3& wi, const Vec3& wo) const {
  return wo.z > 0.0 ? cosine_hemisphere_pdf(wi) : 0.0;
}

BrdfSample Lambert::sample(const Vec3& wo, Vec2 u, double) const {
  BrdfSample s;
  if (wo.z <= 0.0) return s;
  s.wi = sample_cosine_hemisphere(u);
  s.pdf = cosine_hemisphere_pdf(s.wi);
  if (s.pdf > 0.0) s.weight = m_kd;  // (kd/pi) cos / (cos/pi)
  return s;
}

ModelInfo lambert_model() {
  return {"lambert", "kd / pi", "Lambert 1760; lecture 5, 'Pure Lambertian'", {kd_param("0.8")},
          [](const ParamValues& p) -> Result<BrdfPtr> { return BrdfPtr(new Lambert(p.color("kd"))); }, {}, {}, {}};
}

}  // namespace shadelab
