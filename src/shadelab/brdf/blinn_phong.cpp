#include "shadelab/brdf/blinn_phong.h"

#include <cmath>

#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

// The enum's order is the kernel's BLINN_PHONG_NORMALIZATION_* numbering.
static_assert(static_cast<int>(BlinnPhong::Normalization::upper) == kernel::BLINN_PHONG_NORMALIZATION_UPPER &&
              static_cast<int>(BlinnPhong::Normalization::exact) == kernel::BLINN_PHONG_NORMALIZATION_EXACT);

double BlinnPhong::normalization_factor(double n, Normalization normalization, bool modified) {
  return kernel::blinn_phong_normalization(n, static_cast<int>(normalization), modified ? 1 : 0);
}

namespace {
BlinnPhong::Normalization parse_normalization(const std::string& s) {
  if (s == "exact") return BlinnPhong::Normalization::exact;
  if (s == "lower") return BlinnPhong::Normalization::lower;
  if (s == "upper") return BlinnPhong::Normalization::upper;
  return BlinnPhong::Normalization::none;
}
}  // namespace

BlinnPhong::BlinnPhong(const Rgb& kd, const Rgb& ks, double n, Normalization normalization, bool modified)
    : LobeMixtureBrdf(normalization == Normalization::none ? kd : kd * inv_pi,
                  // Specular albedo estimate: N times the lobe integral bound 8 pi / (n + 2).
                  lobe_probability(normalization == Normalization::none ? kd.average() * pi : kd.average(),
                                   ks.average() * normalization_factor(n, normalization, modified) * 8.0 * pi /
                                       (n + 2.0))),
      m_kp{kd, ks, n, static_cast<int>(normalization), modified ? 1 : 0},
      m_k(kernel::blinn_phong_prepare(m_kp)),
      m_ks(ks),
      m_n(n),
      m_modified(modified) {}

std::optional<KernelBinding> BlinnPhong::kernel_binding() const {
  return KernelBinding{"blinn_phong", {}}
      .add("kd", m_kp.kd)
      .add("ks", m_kp.ks)
      .add("n", m_kp.n)
      .add("normalization", m_kp.normalization)
      .add("modified", m_kp.modified);
}

double BlinnPhong::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  const Vec3 h = half_vector(wi, wo);
  return reflect_jacobian_pdf(power_cosine_pdf(h, m_n), wo, h);
}

Vec3 BlinnPhong::specular_sample(const Vec3& wo, Vec2 u, double) const {
  return reflect(wo, sample_power_cosine(u, m_n));
}

namespace {
ModelInfo blinn_phong_info(bool modified) {
  ModelInfo info;
  info.name = modified ? "blinn-phong-modified" : "blinn-phong";
  info.summary = modified ? "kd/pi + ks (n+2)(n+4)/(8pi(2^(-n/2)+n)) (N.H)^n"
                          : "kd/pi + ks (n+2)/(4pi(2-2^(-n/2))) (N.H)^n / (N.L)";
  info.source = modified ? "lecture 5 'The Modified Blinn-Phong Model'; zoo row 'Blinn-Phong (modified)'"
                         : "Blinn 1977; lecture 5 'The Blinn-Phong Model'; zoo row 'Blinn-Phong'";
  info.params = {kd_param(), ks_param(), exponent_param(),
                 {"normalization", ParamKind::choice, "exact", 0, 0, {"none", "exact", "lower", "upper"},
                  "exact: the zoo's closed form; lower/upper: its bounds; none: the lecture's unnormalized form",
                  0, {}}};
  info.create = [modified](const ParamValues& p) -> Result<BrdfPtr> {
    return BrdfPtr(new BlinnPhong(p.color("kd"), p.color("ks"), p.scalar("n"),
                                  parse_normalization(p.choice("normalization")), modified));
  };
  return info;
}
}  // namespace

ModelInfo blinn_phong_model() { return blinn_phong_info(false); }
ModelInfo blinn_phong_modified_model() { return blinn_phong_info(true); }

}  // namespace shadelab
