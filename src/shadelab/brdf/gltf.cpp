#include "shadelab/brdf/gltf.h"

#include <algorithm>

#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

static_assert(static_cast<int>(Gltf::SheenVisibility::ashikhmin) == kernel::SHEEN_VISIBILITY_ASHIKHMIN);

namespace {

kernel::GltfParams kernel_params(const Gltf::Params& p) {
  return {p.base_color,      p.metallic, p.specular_color,      p.roughness,           p.sheen_color,
          p.sheen_roughness, p.ior,      p.specular,            p.anisotropy_strength, p.anisotropy_rotation,
          static_cast<int>(p.sheen_visibility), p.clearcoat, p.clearcoat_roughness};
}

// Schlick's cosine-weighted average of F over the hemisphere: f0 + (1 - f0) / 21 (fresnel.sl F_average).
double schlick_average(double f0) { return f0 + (1.0 - f0) / 21.0; }

Vec3 to_frame(const kernel::GltfState& s, const Vec3& w) { return kernel::gltf_anisotropy_frame(s, w); }
Vec3 from_frame(const kernel::GltfState& s, const Vec3& w) {
  return {s.cos_rotation * w.x - s.sin_rotation * w.y, s.sin_rotation * w.x + s.cos_rotation * w.y, w.z};
}

}  // namespace

Gltf::Gltf(const Params& p) : m_p(p), m_k(kernel::gltf_prepare(kernel_params(p))) {
  // Albedo estimates per lobe (only their ratios matter; any positive choice keeps the estimator unbiased).
  const Rgb f0(m_k.f0);
  const double m = p.metallic;
  const double spec_dielectric =
      p.specular * (schlick_average(f0.r) + schlick_average(f0.g) + schlick_average(f0.b)) / 3.0;
  const double spec_metal =
      (schlick_average(p.base_color.r) + schlick_average(p.base_color.g) + schlick_average(p.base_color.b)) / 3.0;
  const double below = (1.0 - p.clearcoat * schlick_average(0.04)) * (1.0 - 0.3 * m_k.sheen_max);
  m_mix.diffuse = (1.0 - m) * p.base_color.average() * (1.0 - p.specular * f0.max_component()) * below;
  m_mix.specular = ((1.0 - m) * spec_dielectric + m * spec_metal) * below;
  m_mix.clearcoat = p.clearcoat * schlick_average(0.04);
  m_mix.sheen = 0.3 * m_k.sheen_max;
  const double total = m_mix.diffuse + m_mix.specular + m_mix.clearcoat + m_mix.sheen;
  if (total > 0.0) {
    m_mix.diffuse /= total;
    m_mix.specular /= total;
    m_mix.clearcoat /= total;
    m_mix.sheen /= total;
  } else {
    m_mix = Mixture{};  // a black material: the cosine lobe
  }
}

double Gltf::pdf(const Vec3& wi, const Vec3& wo) const {
  if (wo.z <= 0.0) return 0.0;
  double p = 0.0;
  if (m_mix.diffuse > 0.0) p += m_mix.diffuse * cosine_hemisphere_pdf(wi);
  if (m_mix.specular > 0.0) {
    p += m_mix.specular * ggx_vndf_bounded_pdf(to_frame(m_k, wi), to_frame(m_k, wo), m_k.alpha_t, m_k.alpha_b);
  }
  if (m_mix.clearcoat > 0.0) {
    p += m_mix.clearcoat * ggx_vndf_bounded_pdf(wi, wo, m_k.clearcoat_alpha, m_k.clearcoat_alpha);
  }
  if (m_mix.sheen > 0.0) p += m_mix.sheen * uniform_hemisphere_pdf(wi);
  return p;
}

BrdfSample Gltf::sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  BrdfSample s;
  if (wo.z <= 0.0) return s;
  const double c0 = m_mix.diffuse;
  const double c1 = c0 + m_mix.specular;
  const double c2 = c1 + m_mix.clearcoat;
  if (u_lobe < c0) {
    s.wi = sample_cosine_hemisphere(u);
  } else if (u_lobe < c1) {
    const Vec3 o = to_frame(m_k, wo);
    s.wi = from_frame(m_k, reflect(o, sample_ggx_vndf_bounded(o, u, m_k.alpha_t, m_k.alpha_b)));
  } else if (u_lobe < c2) {
    s.wi = reflect(wo, sample_ggx_vndf_bounded(wo, u, m_k.clearcoat_alpha, m_k.clearcoat_alpha));
  } else {
    s.wi = sample_uniform_hemisphere(u);
  }
  s.pdf = pdf(s.wi, wo);
  if (s.pdf > 0.0 && s.wi.z > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
  return s;
}

// The Lambertian part at normal incidence: (1 - metallic) base_color (1 - specular max3(f0)) (the dielectric's
// diffuse weight 1 - specular max3(F) at V.H = 1), under the clearcoat's and the sheen's scaling left out.
Rgb Gltf::diffuse_albedo() const {
  return m_p.base_color * ((1.0 - m_p.metallic) * (1.0 - m_p.specular * Rgb(m_k.f0).max_component()));
}

double Gltf::game_phong_exponent() const {
  return phong_exponent_from_ggx_alpha(std::sqrt(m_k.alpha_t * m_k.alpha_b));
}

std::optional<KernelBinding> Gltf::kernel_binding() const {
  const kernel::GltfParams p = kernel_params(m_p);  // the parameters m_k was prepared from
  return KernelBinding{"gltf", {}}
      .add("base_color", p.base_color)
      .add("metallic", p.metallic)
      .add("specular_color", p.specular_color)
      .add("roughness", p.roughness)
      .add("sheen_color", p.sheen_color)
      .add("sheen_roughness", p.sheen_roughness)
      .add("ior", p.ior)
      .add("specular", p.specular)
      .add("anisotropy_strength", p.anisotropy_strength)
      .add("anisotropy_rotation", p.anisotropy_rotation)
      .add("sheen_visibility", p.sheen_visibility)
      .add("clearcoat", p.clearcoat)
      .add("clearcoat_roughness", p.clearcoat_roughness);
}

ModelInfo gltf_model() {
  ModelInfo info;
  info.name = "gltf";
  info.summary = "(1 - cc Fc(N.V)) [sheen D_charlie V + s mix(fresnel_mix(ior, specular), conductor_fresnel, metallic)] "
                 "+ cc Fc D_GGX V_GGX";
  info.source = "glTF 2.0 Appendix B; KHR_materials_ior, _specular, _anisotropy, _sheen, _clearcoat, _emissive_strength";
  info.params = {
      {"base_color", ParamKind::color, "1", 0.0, 1.0, {}, "baseColorFactor (linear)", 0, {}},
      {"metallic", ParamKind::scalar, "1", 0.0, 1.0, {}, "metallicFactor", 0, {}},
      {"roughness", ParamKind::scalar, "1", 0.0, 1.0, {}, "roughnessFactor (perceptual; alpha = roughness^2 >= 1e-4)", 0, {}},
      {"ior", ParamKind::scalar, "1.5", 0.0, 10.0, {}, "KHR_materials_ior: f0 = ((ior-1)/(ior+1))^2 (glTF: 1 or more, or 0)", 0, {}},
      {"specular", ParamKind::scalar, "1", 0.0, 1.0, {}, "KHR_materials_specular: specularFactor", 0, {}},
      {"specular_color", ParamKind::color, "1", 0.0, 10.0, {}, "KHR_materials_specular: specularColorFactor (f0 clamped to 1)", 0, {}},
      {"anisotropy_strength", ParamKind::scalar, "0", 0.0, 1.0, {}, "KHR_materials_anisotropy: alpha_t = mix(alpha, 1, strength^2)", 0, {}},
      {"anisotropy_rotation", ParamKind::scalar, "0", -100.0, 100.0, {}, "KHR_materials_anisotropy: radians from the tangent", 0, {}},
      {"sheen_color", ParamKind::color, "0", 0.0, 1.0, {}, "KHR_materials_sheen: sheenColorFactor", 0, {}},
      {"sheen_roughness", ParamKind::scalar, "0", 0.0, 1.0, {}, "KHR_materials_sheen: sheenRoughnessFactor (alpha = r^2, r >= 0.07)", 0, {}},
      {"sheen_visibility", ParamKind::choice, "charlie", 0, 0, {"charlie", "ashikhmin"}, "the sheen lobe's visibility term", 0, {}},
      {"clearcoat", ParamKind::scalar, "0", 0.0, 1.0, {}, "KHR_materials_clearcoat: clearcoatFactor", 0, {}},
      {"clearcoat_roughness", ParamKind::scalar, "0", 0.0, 1.0, {}, "KHR_materials_clearcoat: clearcoatRoughnessFactor", 0, {}},
      {"emissive", ParamKind::color, "0", 0.0, 1.0, {}, "emissiveFactor (emission, not part of f)", 0, {}},
      {"emissive_strength", ParamKind::scalar, "1", 0.0, 1e6, {}, "KHR_materials_emissive_strength (emission, not part of f)", 0, {}},
  };
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    Gltf::Params q;
    q.base_color = p.color("base_color");
    q.metallic = p.scalar("metallic");
    q.roughness = p.scalar("roughness");
    q.ior = p.scalar("ior");
    q.specular = p.scalar("specular");
    q.specular_color = p.color("specular_color");
    q.anisotropy_strength = p.scalar("anisotropy_strength");
    q.anisotropy_rotation = p.scalar("anisotropy_rotation");
    q.sheen_color = p.color("sheen_color");
    q.sheen_roughness = p.scalar("sheen_roughness");
    q.sheen_visibility = p.choice("sheen_visibility") == "ashikhmin" ? Gltf::SheenVisibility::ashikhmin
                                                                     : Gltf::SheenVisibility::charlie;
    q.clearcoat = p.scalar("clearcoat");
    q.clearcoat_roughness = p.scalar("clearcoat_roughness");
    q.emissive = p.color("emissive");
    q.emissive_strength = p.scalar("emissive_strength");
    return BrdfPtr(new Gltf(q));
  };
  return info;
}

}  // namespace shadelab
