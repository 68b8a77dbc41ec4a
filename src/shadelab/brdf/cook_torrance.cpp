#include "shadelab/brdf/cook_torrance.h"

#include <cmath>

#include "shadelab/brdf/fresnel.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

namespace {

// The enums' order is the kernel's COOK_TORRANCE_* numbering.
static_assert(static_cast<int>(CookTorrance::Distribution::blinn_phong) == kernel::COOK_TORRANCE_D_BLINN_PHONG &&
              static_cast<int>(CookTorrance::Distribution::ggx) == kernel::COOK_TORRANCE_D_GGX);
static_assert(static_cast<int>(CookTorrance::Geometry::smith) == kernel::COOK_TORRANCE_G_SMITH &&
              static_cast<int>(CookTorrance::Geometry::kelemen) == kernel::COOK_TORRANCE_G_KELEMEN);
static_assert(static_cast<int>(CookTorrance::FresnelKind::none) == kernel::COOK_TORRANCE_F_NONE &&
              static_cast<int>(CookTorrance::FresnelKind::schlick) == kernel::COOK_TORRANCE_F_SCHLICK &&
              static_cast<int>(CookTorrance::FresnelKind::conductor) == kernel::COOK_TORRANCE_F_CONDUCTOR);
static_assert(static_cast<int>(CookTorrance::Form::cook_torrance_1981) == kernel::COOK_TORRANCE_FORM_1981);

kernel::CookTorranceParams kernel_params(const CookTorrance::Params& p) {
  return {p.kd,
          p.ks,
          p.m,
          p.n,
          static_cast<int>(p.d),
          static_cast<int>(p.g),
          static_cast<int>(p.f),
          p.ior,
          p.k,
          p.f0,
          static_cast<int>(p.form)};
}

}  // namespace

CookTorrance::CookTorrance(const Params& p)
    : LobeMixtureBrdf(p.kd * inv_pi, lobe_probability(p.kd.average(), p.ks.average())),
      m_p(p),
      m_k(kernel::cook_torrance_prepare(kernel_params(p))) {}

std::optional<KernelBinding> CookTorrance::kernel_binding() const {
  const kernel::CookTorranceParams& p = m_k.p;  // the parameters m_k was prepared from
  return KernelBinding{"cook_torrance", {}}
      .add("kd", p.kd)
      .add("ks", p.ks)
      .add("m", p.m)
      .add("n", p.n)
      .add("d", p.d)
      .add("g", p.g)
      .add("f", p.f)
      .add("ior", p.ior)
      .add("k", p.k)
      .add("f0", p.f0)
      .add("form", p.form);
}

Rgb CookTorrance::fresnel(double cos_i) const { return kernel::cook_torrance_fresnel(m_k.p, cos_i); }

double CookTorrance::distribution(double cos_h) const { return kernel::cook_torrance_distribution(m_k.p, cos_h); }

double CookTorrance::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  const Vec3 h = half_vector(wi, wo);
  return reflect_jacobian_pdf(distribution(h.z) * h.z, wo, h);
}

Vec3 CookTorrance::specular_sample(const Vec3& wo, Vec2 u, double) const {
  // Blinn-Phong D cos = (n+2)/(2pi) cos^(n+1): a power-cosine lobe of exponent n + 1.
  if (m_p.d == Distribution::ggx) return reflect(wo, sample_ggx_ndf(u, m_p.m, m_p.m));
  const Vec3 h = m_p.d == Distribution::beckmann ? sample_beckmann_h(u, m_p.m) : sample_power_cosine(u, m_p.n + 1.0);
  return reflect(wo, h);
}

ModelInfo cook_torrance_model() {
  ModelInfo info;
  info.name = "cook-torrance";
  // With Schlick's Fresnel the specular colour is f0 (ks is then a plain scale).
  info.ks_texture_param = [](const ParamValues& p) { return std::string(p.choice("f") == "schlick" ? "f0" : "ks"); };
  info.summary = "kd/pi + ks F D G / (4 N.L N.V)   (form=1981: F D' G / (pi N.L N.V), D' = pi D)";
  info.source = "Cook & Torrance 1981; lecture 5 'Cook-Torrance BRDF Model'; Walter et al. 2007";
  info.params = {
      kd_param("0.2"),
      ks_param("1"),
      {"m", ParamKind::scalar, "0.3", 1e-4, 10.0, {}, "Beckmann RMS slope (give m or n, not both)", 0, {}},
      {"n", ParamKind::scalar, "20.2222222222", 0.0, 1e6, {}, "Blinn-Phong exponent, n = 2/m^2 - 2", 0, {}},
      {"d", ParamKind::choice, "beckmann", 0, 0, {"beckmann", "blinn-phong", "ggx"}, "normal distribution (ggx: alpha = m)", 0, {}},
      {"g", ParamKind::choice, "smith", 0, 0, {"cook-torrance", "kelemen", "smith"}, "masking-shadowing", 0, {}},
      {"f", ParamKind::choice, "schlick", 0, 0, {"dielectric", "conductor", "schlick", "none"}, "Fresnel term", 0, {}},
      {"ior", ParamKind::color, "1.5", 1e-3, 100.0, {}, "real part of the relative IOR (dielectric, conductor)", 0, {}},
      {"k", ParamKind::color, "0", 0.0, 100.0, {}, "imaginary part of the IOR (conductor)", 0, {}},
      {"f0", ParamKind::color, "0.04", 0.0, 1.0, {}, "reflectance at normal incidence (schlick)", 0, {}},
      {"form", ParamKind::choice, "microfacet", 0, 0, {"1981", "microfacet"}, "the 1981 paper's form or the normalized microfacet form", 0, {}},
  };
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    CookTorrance::Params q;
    q.kd = p.color("kd");
    q.ks = p.color("ks");
    if (p.is_set("m") && p.is_set("n")) {
      return make_error("brdf cook-torrance: give parameter 'm' or 'n', not both (n = 2/m^2 - 2)");
    }
    if (p.is_set("n")) {
      q.n = p.scalar("n");
      q.m = beckmann_m_from_exponent(q.n);
    } else {
      q.m = p.scalar("m");
      q.n = exponent_from_beckmann_m(q.m);
      if (q.n < 0.0) {
        return make_error("brdf cook-torrance: parameter 'm' = " + std::to_string(q.m) +
                          " gives a negative Blinn-Phong exponent; m must be <= sqrt(2) with d=blinn-phong");
      }
    }
    q.d = pick_choice<CookTorrance::Distribution>(p.choice("d"), {{"beckmann", CookTorrance::Distribution::beckmann},
                                                           {"blinn-phong", CookTorrance::Distribution::blinn_phong},
                                                           {"ggx", CookTorrance::Distribution::ggx}});
    q.g = pick_choice<CookTorrance::Geometry>(p.choice("g"), {{"smith", CookTorrance::Geometry::smith},
                                                       {"cook-torrance", CookTorrance::Geometry::cook_torrance},
                                                       {"kelemen", CookTorrance::Geometry::kelemen}});
    q.f = pick_choice<CookTorrance::FresnelKind>(p.choice("f"), {{"schlick", CookTorrance::FresnelKind::schlick},
                                                          {"dielectric", CookTorrance::FresnelKind::dielectric},
                                                          {"conductor", CookTorrance::FresnelKind::conductor},
                                                          {"none", CookTorrance::FresnelKind::none}});
    q.ior = p.color("ior");
    q.k = p.color("k");
    q.f0 = p.color("f0");
    q.form = p.choice("form") == "1981" ? CookTorrance::Form::cook_torrance_1981 : CookTorrance::Form::microfacet;
    return BrdfPtr(new CookTorrance(q));
  };
  return info;
}

}  // namespace shadelab
