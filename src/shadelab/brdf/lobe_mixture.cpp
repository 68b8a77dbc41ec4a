#include "shadelab/brdf/lobe_mixture.h"

#include "shadelab/sampling/warp.h"

namespace shadelab {

double LobeMixtureBrdf::lobe_probability(double diffuse_albedo, double specular_albedo) {
  const double total = diffuse_albedo + specular_albedo;
  return total > 0.0 ? diffuse_albedo / total : 1.0;
}

double LobeMixtureBrdf::pdf(const Vec3& wi, const Vec3& wo) const {
  if (wo.z <= 0.0) return 0.0;
  double p = m_p_diffuse > 0.0 ? m_p_diffuse * cosine_hemisphere_pdf(wi) : 0.0;
  if (m_p_diffuse < 1.0) p += (1.0 - m_p_diffuse) * specular_pdf(wi, wo);
  return p;
}

BrdfSample LobeMixtureBrdf::sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  BrdfSample s;
  if (wo.z <= 0.0) return s;
  if (u_lobe < m_p_diffuse) {
    s.wi = sample_cosine_hemisphere(u);
  } else {
    // Reuse the rest of u_lobe (rescaled to [0, 1)) for models that pick among several specular lobes.
    const double u_rest = m_p_diffuse < 1.0 ? (u_lobe - m_p_diffuse) / (1.0 - m_p_diffuse) : 0.0;
    s.wi = specular_sample(wo, u, u_rest < 1.0 ? u_rest : 0x1.fffffffffffffp-1);
  }
  s.pdf = pdf(s.wi, wo);
  if (s.pdf > 0.0 && s.wi.z > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
  return s;
}

}  // namespace shadelab
