#include "shadelab/brdf/openpbr.h"

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

static_assert(static_cast<int>(Openpbr::Layering::reciprocal) == kernel::OPENPBR_LAYERING_RECIPROCAL);

namespace {

kernel::OpenpbrParams kernel_params(const Openpbr::Params& p) {
  kernel::OpenpbrParams k;
  k.base_color = p.base_color;
  k.base_weight = p.base_weight;
  k.specular_color = p.specular_color;
  k.base_metalness = p.base_metalness;
  k.coat_color = p.coat_color;
  k.base_diffuse_roughness = p.base_diffuse_roughness;
  k.fuzz_color = p.fuzz_color;
  k.specular_weight = p.specular_weight;
  k.specular_roughness = p.specular_roughness;
  k.specular_roughness_anisotropy = p.specular_roughness_anisotropy;
  k.specular_ior = p.specular_ior;
  k.coat_weight = p.coat_weight;
  k.coat_roughness = p.coat_roughness;
  k.coat_ior = p.coat_ior;
  k.coat_darkening = p.coat_darkening;
  k.fuzz_weight = p.fuzz_weight;
  k.fuzz_roughness = p.fuzz_roughness;
  k.layering = static_cast<int>(p.layering);
  return k;
}

// The fuzz's LTC lobe in wo's azimuthal frame (openpbr.sl openpbr_fuzz_frame) and back.
Vec3 from_fuzz_frame(const Vec3& wo, const Vec3& w) {
  const double l = std::sqrt(wo.x * wo.x + wo.y * wo.y);
  const double cx = l > 0.0 ? wo.x / l : 1.0;
  const double cy = l > 0.0 ? wo.y / l : 0.0;
  return {cx * w.x - cy * w.y, cy * w.x + cx * w.y, w.z};
}

}  // namespace

Openpbr::Openpbr(const Params& p) : m_p(p), m_k(kernel::openpbr_prepare(kernel_params(p))) {
  // Albedo estimates per lobe (only their ratios matter; any positive choice keeps the estimator unbiased).
  const double m = p.base_metalness;
  const double below = (1.0 - 0.5 * p.coat_weight * m_k.coat_e) * (1.0 - 0.5 * p.fuzz_weight);
  const double e2 = m_k.spec_e * m_k.spec_e;
  m_mix.cosine = ((1.0 - m) * p.base_weight * p.base_color.average() + 0.1 * m) * below;
  m_mix.specular =
      ((1.0 - m) * std::max(0.04, e2) * p.specular_color.average() + m * p.specular_weight) * below;
  m_mix.coat = p.coat_weight * std::max(0.04, 2.0 * m_k.coat_e * m_k.coat_e);
  m_mix.fuzz = 0.5 * p.fuzz_weight * std::max(0.05, p.fuzz_color.average());
  const double total = m_mix.cosine + m_mix.specular + m_mix.coat + m_mix.fuzz;
  if (total > 0.0) {
    m_mix.cosine /= total;
    m_mix.specular /= total;
    m_mix.coat /= total;
    m_mix.fuzz /= total;
  } else {
    m_mix = Mixture{};  // a black material: the cosine lobe
  }
}

bool Openpbr::is_reciprocal() const {
  // The fuzz's LTC lobe is a function of wo in both forms; the view form's scalings read mu_o alone wherever a
  // layer lies above another: the diffuse under a reflecting dielectric, anything under the coat.
  if (m_p.fuzz_weight > 0.0) return false;
  if (m_p.layering == Layering::reciprocal) return true;
  if (m_p.coat_weight > 0.0) return false;
  const bool diffuse = m_p.base_metalness < 1.0 && m_p.base_weight > 0.0 && m_p.base_color.max_component() > 0.0;
  return !(diffuse && m_k.spec_e > 0.0);
}

double Openpbr::pdf(const Vec3& wi, const Vec3& wo) const {
  if (wo.z <= 0.0) return 0.0;
  double p = 0.0;
  if (m_mix.cosine > 0.0) p += m_mix.cosine * cosine_hemisphere_pdf(wi);
  if (m_mix.specular > 0.0) p += m_mix.specular * ggx_vndf_bounded_pdf(wi, wo, m_k.alpha_t, m_k.alpha_b);
  if (m_mix.coat > 0.0) p += m_mix.coat * ggx_vndf_bounded_pdf(wi, wo, m_k.coat_alpha, m_k.coat_alpha);
  if (m_mix.fuzz > 0.0) {
    const double a = kernel::openpbr_fuzz_ltc_a(wo.z, m_p.fuzz_roughness);
    const double b = kernel::openpbr_fuzz_ltc_b(wo.z, m_p.fuzz_roughness);
    p += m_mix.fuzz * kernel::openpbr_fuzz_ltc(a, b, kernel::openpbr_fuzz_frame(wo, wi));
  }
  return p;
}

BrdfSample Openpbr::sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  BrdfSample s;
  if (wo.z <= 0.0) return s;
  const double c0 = m_mix.cosine;
  const double c1 = c0 + m_mix.specular;
  const double c2 = c1 + m_mix.coat;
  if (u_lobe < c0) {
    s.wi = sample_cosine_hemisphere(u);
  } else if (u_lobe < c1) {
    s.wi = reflect(wo, sample_ggx_vndf_bounded(wo, u, m_k.alpha_t, m_k.alpha_b));
  } else if (u_lobe < c2) {
    s.wi = reflect(wo, sample_ggx_vndf_bounded(wo, u, m_k.coat_alpha, m_k.coat_alpha));
  } else {
    // The LTC: a cosine-distributed w' mapped by M = inverse of [[a, 0, b], [0, a, 0], [0, 0, 1]], normalized.
    const double a = kernel::openpbr_fuzz_ltc_a(wo.z, m_p.fuzz_roughness);
    const double b = kernel::openpbr_fuzz_ltc_b(wo.z, m_p.fuzz_roughness);
    const Vec3 c = sample_cosine_hemisphere(u);
    const Vec3 w = normalize(Vec3{(c.x - b * c.z) / a, c.y / a, c.z});
    s.wi = from_fuzz_frame(wo, w);
  }
  s.pdf = pdf(s.wi, wo);
  if (s.pdf > 0.0 && s.wi.z > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
  return s;
}

// The diffuse lobe's albedo at normal incidence under the dielectric's view-form scaling: (1 - M) w_d rho (1 -
// E_d(1)) (sigma = 0: exact; EON's own darkening at sigma > 0 and the coat and fuzz scalings left out).
Rgb Openpbr::diffuse_albedo() const {
  const double ed1 = kernel::openpbr_dielectric_energy_at(m_k.diel_rows, 1.0);
  return m_p.base_color * ((1.0 - m_p.base_metalness) * m_p.base_weight * (1.0 - ed1));
}

double Openpbr::game_phong_exponent() const {
  return phong_exponent_from_ggx_alpha(std::sqrt(m_k.alpha_t * m_k.alpha_b));
}

ModelInfo openpbr_model() {
  ModelInfo info;
  info.name = "openpbr";
  info.summary = "F_w f_fuzz + S_fuzz [C f_coat + lerp(1, T S_coat, C) lerp(1, Delta, C delta) (M f_metal(F82) + (1 - M) "
                 "(f_dielectric + S_diel f_EON))]";
  info.source = "OpenPBR Surface 1.1 (ASWF); EON (Portsmouth, Kutz, Hill 2024); F82-tint (Kutz et al. 2021); "
                "fuzz: Zeltner, Burley, Chiang 2022";
  info.no_shader = "its dielectric albedo table (48 x 32 x 32) exceeds a GLSL ES uniform block and the kernel is not "
                   "in the exporter's list (docs/models/openpbr.md, \"Shaders\")";
  info.params = {
      {"base_weight", ParamKind::scalar, "1", 0.0, 1.0, {}, "multiplier of base_color (diffuse w_d, metal F0)", 0, {}},
      {"base_color", ParamKind::color, "0.8", 0.0, 1.0, {}, "diffuse albedo rho; the metal's F0 (times base_weight)", 0, {}},
      {"base_metalness", ParamKind::scalar, "0", 0.0, 1.0, {}, "mix of metal (1) and glossy-diffuse dielectric (0)", 0, {}},
      {"base_diffuse_roughness", ParamKind::scalar, "0", 0.0, 1.0, {}, "EON roughness sigma (0: Lambert)", 0, {}},
      {"specular_weight", ParamKind::scalar, "1", 0.0, 1.0, {}, "xi_s: the dielectric's F0 times xi_s (via its ior); the metal's F times xi_s", 0, {}},
      {"specular_color", ParamKind::color, "1", 0.0, 1.0, {}, "tint of the dielectric's reflection; the metal's F82 edge tint", 0, {}},
      {"specular_roughness", ParamKind::scalar, "0.3", 0.0, 1.0, {}, "r (alpha = r^2 >= 1e-4) of the dielectric and the metal", 0, {}},
      {"specular_roughness_anisotropy", ParamKind::scalar, "0", 0.0, 1.0, {}, "a: alpha_t = r^2 sqrt(2/(1+(1-a)^2)), alpha_b = (1-a) alpha_t", 0, {}},
      {"specular_ior", ParamKind::scalar, "1.5", 1.0, 10.0, {}, "n_b, the dielectric's index (OpenPBR allows (0, inf); here >= 1)", 0, {}},
      {"coat_weight", ParamKind::scalar, "0", 0.0, 1.0, {}, "C, the coat's coverage", 0, {}},
      {"coat_color", ParamKind::color, "1", 0.0, 1.0, {}, "T^2, the coat's transmittance squared at normal incidence", 0, {}},
      {"coat_roughness", ParamKind::scalar, "0", 0.0, 1.0, {}, "r_c (alpha_c = r_c^2 >= 1e-4)", 0, {}},
      {"coat_ior", ParamKind::scalar, "1.6", 1.0, 10.0, {}, "n_c, the coat's index (OpenPBR allows (0, inf); here >= 1)", 0, {}},
      {"coat_darkening", ParamKind::scalar, "1", 0.0, 1.0, {}, "delta: 1 the physical darkening Delta, 0 none", 0, {}},
      {"fuzz_weight", ParamKind::scalar, "0", 0.0, 1.0, {}, "F_w, the fuzz's coverage", 0, {}},
      {"fuzz_color", ParamKind::color, "1", 0.0, 1.0, {}, "the fuzz lobe's albedo tint", 0, {}},
      {"fuzz_roughness", ParamKind::scalar, "0.5", 0.0, 1.0, {}, "the LTC fits' roughness (clamped to >= 0.01)", 0, {}},
      {"layering", ParamKind::choice, "view", 0, 0, {"view", "reciprocal"}, "albedo scaling by E(mu_o) (the spec's, furnace-exact) or symmetric in mu_i, mu_o", 0, {}},
  };
  info.create = [](const ParamValues& v) -> Result<BrdfPtr> {
    Openpbr::Params q;
    q.base_weight = v.scalar("base_weight");
    q.base_color = v.color("base_color");
    q.base_metalness = v.scalar("base_metalness");
    q.base_diffuse_roughness = v.scalar("base_diffuse_roughness");
    q.specular_weight = v.scalar("specular_weight");
    q.specular_color = v.color("specular_color");
    q.specular_roughness = v.scalar("specular_roughness");
    q.specular_roughness_anisotropy = v.scalar("specular_roughness_anisotropy");
    q.specular_ior = v.scalar("specular_ior");
    q.coat_weight = v.scalar("coat_weight");
    q.coat_color = v.color("coat_color");
    q.coat_roughness = v.scalar("coat_roughness");
    q.coat_ior = v.scalar("coat_ior");
    q.coat_darkening = v.scalar("coat_darkening");
    q.fuzz_weight = v.scalar("fuzz_weight");
    q.fuzz_color = v.color("fuzz_color");
    q.fuzz_roughness = v.scalar("fuzz_roughness");
    q.layering = v.choice("layering") == "reciprocal" ? Openpbr::Layering::reciprocal : Openpbr::Layering::view;
    return BrdfPtr(new Openpbr(q));
  };
  return info;
}

}  // namespace shadelab
