#include "shadelab/brdf/principled_v1.h"

#include <cmath>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"

namespace shadelab {

namespace {

kernel::PrincipledV1Params kernel_params(const PrincipledV1::Params& p) {
  return {p.base_color, p.metallic,   p.specular, p.specular_tint, p.roughness,          p.anisotropic,
          p.anisotropic_rotation, p.sheen, p.sheen_tint, p.clearcoat, p.clearcoat_roughness};
}

// The tangent frame of the specular lobe (kernels/principled_v1.sl principled_v1_to_tangent_frame) and back.
Vec3 to_tangent(const kernel::PrincipledV1State& s, const Vec3& w) {
  return kernel::principled_v1_to_tangent_frame(s, w);
}
Vec3 from_tangent(const kernel::PrincipledV1State& s, const Vec3& w) {
  return {s.cos_rot * w.x - s.sin_rot * w.y, s.sin_rot * w.x + s.cos_rot * w.y, w.z};
}

// GTR1 with the kernel's normalization (kernels/principled_v1.sl D_gtr1, principled_v1_gtr1_norm_pi).
double gtr1(const Vec3& h, double alpha) {
  const double a2 = alpha * alpha;
  return kernel::D_gtr1(h, a2, kernel::principled_v1_gtr1_norm_pi(a2) * inv_pi);
}

}  // namespace

Vec3 sample_gtr1(Vec2 u, double alpha) {
  // With L = ln(a^2) < 0: cos^2 = (1 - e^((1 - u) L)) / (1 - e^L) and sin^2 = e^((1 - u) L) (1 - e^(u L)) /
  // (1 - e^L) (the same 1 - cos^2 without the cancellation near the pole, where a sharp lobe puts its samples).
  double cos2 = 1.0 - u.x;
  double sin2 = u.x;
  const double a2 = alpha * alpha;
  if (a2 < 1.0) {
    const double l = std::log(a2);
    const double den = std::expm1(l);  // 1 - a^2 > 0 up to sign: a2 < 1
    cos2 = std::expm1((1.0 - u.x) * l) / den;
    sin2 = std::exp((1.0 - u.x) * l) * std::expm1(u.x * l) / den;
  }
  return spherical_direction(std::sqrt(std::max(0.0, sin2)), std::sqrt(std::max(0.0, cos2)), two_pi * u.y);
}

double gtr1_reflection_pdf(const Vec3& wi, const Vec3& wo, double alpha) {
  // Reflection about h and about -h is the same map, so the flipped half vector (common.sl) is right here.
  const Vec3 h = half_vector(wi, wo);
  return reflect_jacobian_pdf(gtr1(h, alpha) * h.z, wo, h);
}

PrincipledV1::PrincipledV1(const Params& p)
    : LobeMixtureBrdf(Rgb{}, 1.0), m_p(p), m_k(kernel::principled_v1_prepare(kernel_params(p))) {
  m_diffuse = Rgb(m_k.diffuse);  // base_color (1 - metallic) / pi: what a game's SH ambient multiplies
  // Albedo estimates that pick the lobes (any positive choice is unbiased; these keep the weights' variance low):
  // the diffuse lobe about its base albedo, the sheen lobe about a tenth of its weight (the grazing (1 - L.H)^5
  // is small elsewhere), the specular lobe about Schlick's F_avg = c0 + (1 - c0)/21 (its FH rises like Schlick's,
  // and is 0 with specular = 0), the clearcoat about 0.25 clearcoat F_avg(eta 1.5 ~ 0.09).
  const double cosine = Rgb(m_k.diffuse).average() * pi + 0.1 * Rgb(m_k.sheen).average();
  const double c0 = Rgb(m_k.cspec0).average();
  const double specular = m_k.spec_f0 > 0.0 ? c0 + (1.0 - c0) / 21.0 : c0;
  const double clearcoat = m_k.clearcoat * (20.0 * 0.04 + 1.0) / 21.0;
  m_p_diffuse = lobe_probability(cosine, specular + clearcoat);
  m_clearcoat_share = specular + clearcoat > 0.0 ? clearcoat / (specular + clearcoat) : 0.0;
}

std::optional<KernelBinding> PrincipledV1::kernel_binding() const {
  const kernel::PrincipledV1Params p = kernel_params(m_p);  // the parameters m_k was prepared from
  return KernelBinding{"principled_v1", {}}
      .add("base_color", p.base_color)
      .add("metallic", p.metallic)
      .add("specular", p.specular)
      .add("specular_tint", p.specular_tint)
      .add("roughness", p.roughness)
      .add("anisotropic", p.anisotropic)
      .add("anisotropic_rotation", p.anisotropic_rotation)
      .add("sheen", p.sheen)
      .add("sheen_tint", p.sheen_tint)
      .add("clearcoat", p.clearcoat)
      .add("clearcoat_roughness", p.clearcoat_roughness);
}

// The specular GGX's alpha (the geometric mean of alpha_x and alpha_y) as a Beckmann m (microfacet.h).
double PrincipledV1::game_phong_exponent() const {
  return phong_exponent_from_ggx_alpha(std::sqrt(m_k.alpha_x * m_k.alpha_y));
}

double PrincipledV1::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  double p = 0.0;
  if (m_clearcoat_share < 1.0) {
    p += (1.0 - m_clearcoat_share) *
         ggx_vndf_bounded_pdf(to_tangent(m_k, wi), to_tangent(m_k, wo), m_k.alpha_x, m_k.alpha_y);
  }
  if (m_clearcoat_share > 0.0) p += m_clearcoat_share * gtr1_reflection_pdf(wi, wo, m_k.clearcoat_alpha);
  return p;
}

Vec3 PrincipledV1::specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  if (u_lobe < m_clearcoat_share) return reflect(wo, sample_gtr1(u, m_k.clearcoat_alpha));
  const Vec3 h = sample_ggx_vndf_bounded(to_tangent(m_k, wo), u, m_k.alpha_x, m_k.alpha_y);
  return reflect(wo, from_tangent(m_k, h));
}

ModelInfo principled_v1_model() {
  ModelInfo info;
  info.name = "principled-v1";
  info.summary =
      "Blender 3.4 Principled (Cycles), reflection: base(1-metallic)/pi Fd_retro + sheen (1-L.H)^5 + F D_GGX G1 G1 / (4 N.L N.V)"
      " + 0.25 clearcoat F D_GTR1 G1 G1 / (4 N.L N.V)";
  info.source = "Cycles 3.4: svm/closure.h, closure/bsdf_principled_diffuse.h, bsdf_principled_sheen.h, bsdf_microfacet.h; "
                "Burley 2012";
  // Blender 3.4's sockets and defaults. Below roughness 0.0178 Cycles turns a GGX lobe into a perfect mirror
  // (bsdf_microfacet_ggx_eval: alpha_x alpha_y <= 1e-7), which no BRDF value can stand for: the range starts at 0.02.
  info.params = {
      {"base_color", ParamKind::color, "0.8", 0.0, 1.0, {}, "Base Color: diffuse albedo, metal F0, tints", 0, {}},
      {"metallic", ParamKind::scalar, "0", 0.0, 1.0, {}, "Metallic: 0 dielectric, 1 metal", 0, {}},
      {"specular", ParamKind::scalar, "0.5", 0.0, 1.0, {}, "Specular: dielectric F0 = 0.08 specular", 0, {}},
      {"specular_tint", ParamKind::scalar, "0", 0.0, 1.0, {}, "Specular Tint: F0 towards the base colour's hue", 0, {}},
      {"roughness", ParamKind::scalar, "0.5", 0.02, 1.0, {}, "Roughness: GGX alpha = roughness^2; diffuse retro-reflection", 0, {}},
      {"anisotropic", ParamKind::scalar, "0", 0.0, 1.0, {}, "Anisotropic: aspect = sqrt(1 - 0.9 anisotropic)", 0, {}},
      {"anisotropic_rotation", ParamKind::scalar, "0", 0.0, 1.0, {}, "Anisotropic Rotation: the tangent's turn (1 = 360 degrees)", 0, {}},
      {"sheen", ParamKind::scalar, "0", 0.0, 1.0, {}, "Sheen: weight of the (1 - L.H)^5 lobe", 0, {}},
      {"sheen_tint", ParamKind::scalar, "0.5", 0.0, 1.0, {}, "Sheen Tint: sheen towards the base colour's hue", 0, {}},
      {"clearcoat", ParamKind::scalar, "0", 0.0, 1.0, {}, "Clearcoat: the GTR1 coat's weight is 0.25 clearcoat", 0, {}},
      {"clearcoat_roughness", ParamKind::scalar, "0.03", 0.02, 1.0, {}, "Clearcoat Roughness: GTR1 alpha = its square", 0, {}},
      {"distribution", ParamKind::choice, "ggx", 0, 0, {"ggx"}, "GGX (Blender 3.4's default; Multiscatter GGX is not implemented)", 0, {}},
  };
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    PrincipledV1::Params q;
    q.base_color = p.color("base_color");
    q.metallic = p.scalar("metallic");
    q.specular = p.scalar("specular");
    q.specular_tint = p.scalar("specular_tint");
    q.roughness = p.scalar("roughness");
    q.anisotropic = p.scalar("anisotropic");
    q.anisotropic_rotation = p.scalar("anisotropic_rotation");
    q.sheen = p.scalar("sheen");
    q.sheen_tint = p.scalar("sheen_tint");
    q.clearcoat = p.scalar("clearcoat");
    q.clearcoat_roughness = p.scalar("clearcoat_roughness");
    return BrdfPtr(new PrincipledV1(q));
  };
  return info;
}

}  // namespace shadelab
