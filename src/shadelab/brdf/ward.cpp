#include "shadelab/brdf/ward.h"

#include <cmath>

#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"

namespace shadelab {

Ward::Ward(const Rgb& kd, const Rgb& ks, double alpha_x, double alpha_y)
    : LobeMixtureBrdf(kd * inv_pi, lobe_probability(kd.average(), ks.average())),
      m_kp{kd, ks, alpha_x, alpha_y},
      m_k(kernel::ward_prepare(m_kp)),
      m_ax(alpha_x),
      m_ay(alpha_y) {}

std::optional<KernelBinding> Ward::kernel_binding() const {
  return KernelBinding{"ward", {}}
      .add("kd", m_kp.kd)
      .add("ks", m_kp.ks)
      .add("alpha_x", m_kp.alpha_x)
      .add("alpha_y", m_kp.alpha_y);
}

double Ward::slope_term(const Vec3& h) const { return kernel::ward_slope_term(h, m_ax, m_ay); }

double Ward::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  const Vec3 h = half_vector(wi, wo);
  if (h.z <= 0.0) return 0.0;
  // Walter 2005: p_H = exp(-slope) / (pi ax ay cos^3(theta_h))
  const double p_h = std::exp(-slope_term(h)) / (pi * m_ax * m_ay * h.z * h.z * h.z);
  return reflect_jacobian_pdf(p_h, wo, h);
}

Vec3 Ward::specular_sample(const Vec3& wo, Vec2 u, double) const {
  const double angle = two_pi * u.y;
  const double phi = std::atan2(m_ay * std::sin(angle), m_ax * std::cos(angle));  // Walter 2005 eq. 7
  const double c = std::cos(phi);
  const double s = std::sin(phi);
  const double tan2 = -std::log1p(-u.x) / (c * c / (m_ax * m_ax) + s * s / (m_ay * m_ay));
  const double cos_t = 1.0 / std::sqrt(1.0 + tan2);
  const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
  return reflect(wo, Vec3{sin_t * c, sin_t * s, cos_t});
}

namespace {
ParamSpec alpha_param(std::string name, std::string description) {
  return {std::move(name), ParamKind::scalar, "0.2", 1e-4, 10.0, {}, std::move(description), 0, {}};
}
}  // namespace

ModelInfo ward_model() {
  ModelInfo info;
  info.name = "ward";
  info.summary = "kd/pi + ks exp(-tan^2(th)/a^2) / (4 pi a^2 sqrt(N.L N.V))";
  info.source = "Ward 1992 eq. 4; lecture 5 'Ward Model: Isotropic'";
  info.params = {kd_param("0.2"), ks_param("0.3"), alpha_param("alpha", "RMS surface slope")};
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    return BrdfPtr(new Ward(p.color("kd"), p.color("ks"), p.scalar("alpha"), p.scalar("alpha")));
  };
  return info;
}

ModelInfo ward_anisotropic_model() {
  ModelInfo info;
  info.name = "ward-anisotropic";
  info.summary = "kd/pi + ks exp(-tan^2(th)(cos^2/ax^2 + sin^2/ay^2)) / (4 pi ax ay sqrt(N.L N.V))";
  info.source = "Ward 1992 eq. 5a; lecture 5 'Ward Model: Anisotropic'";
  info.params = {kd_param("0.2"), ks_param("0.3"), alpha_param("alpha_x", "RMS slope along the tangent (+X)"),
                 alpha_param("alpha_y", "RMS slope along the bitangent (+Y)")};
  info.params[3].default_value = "0.05";
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    return BrdfPtr(new Ward(p.color("kd"), p.color("ks"), p.scalar("alpha_x"), p.scalar("alpha_y")));
  };
  return info;
}

}  // namespace shadelab
