#include "shadelab/brdf/phong.h"

#include <cmath>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

namespace {
constexpr Vec3 normal{0.0, 0.0, 1.0};

Phong::Normalization parse_normalization(const std::string& s) {
  return s == "exact" ? Phong::Normalization::exact : Phong::Normalization::none;
}

double lobe_albedo(double n) { return two_pi / (n + 1.0); }  // integral of cos^n over the hemisphere
}  // namespace

double Phong::normalization_factor(double n, Normalization normalization, bool modified) {
  return kernel::phong_normalization(n,
                                     normalization == Normalization::none ? kernel::PHONG_NORMALIZATION_NONE
                                                                          : kernel::PHONG_NORMALIZATION_EXACT,
                                     modified ? 1 : 0);
}

Phong::Phong(const Rgb& kd, const Rgb& ks, double n, Normalization normalization, bool modified)
    : LobeMixtureBrdf(normalization == Normalization::exact ? kd * inv_pi : kd,
                  lobe_probability(normalization == Normalization::exact ? kd.average() : kd.average() * pi,
                                   ks.average() * normalization_factor(n, normalization, modified) * lobe_albedo(n))),
      m_kp{kd, ks, n,
           normalization == Normalization::none ? kernel::PHONG_NORMALIZATION_NONE : kernel::PHONG_NORMALIZATION_EXACT,
           modified ? 1 : 0},
      m_k(kernel::phong_prepare(m_kp)),
      m_ks(ks),
      m_n(n),
      m_modified(modified) {}

std::optional<KernelBinding> Phong::kernel_binding() const {
  return KernelBinding{"phong", {}}
      .add("kd", m_kp.kd)
      .add("ks", m_kp.ks)
      .add("n", m_kp.n)
      .add("normalization", m_kp.normalization)
      .add("modified", m_kp.modified);
}

double Phong::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  const Vec3 r = reflect(wo, normal);
  const double c = dot(r, wi);
  return c > 0.0 ? (m_n + 1.0) * inv_two_pi * std::pow(c, m_n) : 0.0;
}

Vec3 Phong::specular_sample(const Vec3& wo, Vec2 u, double) const {
  return Frame::from_normal(reflect(wo, normal)).to_world(sample_power_cosine(u, m_n));
}

namespace {
ModelInfo phong_info(bool modified) {
  ModelInfo info;
  info.name = modified ? "phong-modified" : "phong";
  info.summary = modified ? "kd/pi + ks (n+2)/(2pi) (R.L)^n" : "kd/pi + ks (n+1)/(2pi) (R.L)^n / (N.L)";
  info.source = modified ? "Lewis 1994; Lafortune & Willems 1994; zoo row 'Phong (modified)'"
                         : "Phong 1975; lecture 5 'Phong Reflection Model'; zoo row 'Phong'";
  info.params = {kd_param(), ks_param(), exponent_param(),
                 {"normalization", ParamKind::choice, "exact", 0, 0, {"none", "exact"},
                  "exact: the zoo's normalization and kd/pi; none: the lecture's unnormalized form", 0, {}}};
  info.create = [modified](const ParamValues& p) -> Result<BrdfPtr> {
    return BrdfPtr(new Phong(p.color("kd"), p.color("ks"), p.scalar("n"),
                             parse_normalization(p.choice("normalization")), modified));
  };
  return info;
}
}  // namespace

ModelInfo phong_model() { return phong_info(false); }
ModelInfo phong_modified_model() { return phong_info(true); }

}  // namespace shadelab
