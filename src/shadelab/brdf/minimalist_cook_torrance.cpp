#include "shadelab/brdf/minimalist_cook_torrance.h"

#include <cmath>

#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

MinimalistCookTorrance::MinimalistCookTorrance(const Rgb& kd, const Rgb& ks, double n)
    : LobeMixtureBrdf(kd * inv_pi, lobe_probability(kd.average(), ks.average())),
      m_kp{kd, ks, n},
      m_k(kernel::minimalist_cook_torrance_prepare(m_kp)),
      m_n(n) {}

std::optional<KernelBinding> MinimalistCookTorrance::kernel_binding() const {
  return KernelBinding{"minimalist_cook_torrance", {}}.add("kd", m_kp.kd).add("ks", m_kp.ks).add("n", m_kp.n);
}

double MinimalistCookTorrance::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  const Vec3 h = half_vector(wi, wo);
  return reflect_jacobian_pdf(power_cosine_pdf(h, m_n), wo, h);
}

Vec3 MinimalistCookTorrance::specular_sample(const Vec3& wo, Vec2 u, double) const {
  return reflect(wo, sample_power_cosine(u, m_n));
}

ModelInfo minimalist_cook_torrance_model() {
  ModelInfo info;
  info.name = "minimalist-cook-torrance";
  info.summary = "kd/pi + ks (n+1)(N.H)^n / (8 pi (L.H)^3)";
  info.source = "Schüler, ShaderX7 ch. 2.5 (2009); zoo article 'Minimalist Cook-Torrance'";
  info.params = {kd_param("0.2"), ks_param("0.05"), exponent_param("n", "100")};
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    return BrdfPtr(new MinimalistCookTorrance(p.color("kd"), p.color("ks"), p.scalar("n")));
  };
  return info;
}

}  // namespace shadelab
