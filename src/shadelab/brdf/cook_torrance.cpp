#include "shadelab/brdf/cook_torrance.h"

#include <cmath>

#include "shadelab/brdf/fresnel.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

CookTorrance::CookTorrance(const Params& p)
    : LayeredBrdf(p.kd * inv_pi, lobe_probability(p.kd.average(), p.ks.average())), m_p(p) {}

Rgb CookTorrance::fresnel(double cos_i) const {
  switch (m_p.f) {
    case FresnelKind::dielectric:
      return {F_dielectric(cos_i, m_p.ior.r), F_dielectric(cos_i, m_p.ior.g), F_dielectric(cos_i, m_p.ior.b)};
    case FresnelKind::conductor: return F_conductor(cos_i, m_p.ior, m_p.k);
    case FresnelKind::schlick: return F_schlick(cos_i, m_p.f0);
    case FresnelKind::none: break;
  }
  return Rgb::gray(1.0);
}

double CookTorrance::distribution(double cos_h) const {
  return m_p.d == Distribution::beckmann ? D_beckmann(cos_h, m_p.m) : D_blinn_phong(cos_h, m_p.n);
}

Rgb CookTorrance::specular_eval(const Vec3& wi, const Vec3& wo) const {
  const Vec3 h = half_vector(wi, wo);
  const double nl = wi.z;
  const double nv = wo.z;
  const double nh = h.z;
  // L.H == V.H for a reflection pair in exact arithmetic; their mean keeps f(wi, wo) == f(wo, wi) exactly.
  const double lh = 0.5 * (dot(wi, h) + dot(wo, h));
  if (nh <= 0.0 || lh <= 0.0) return {};
  const double d = distribution(nh);
  if (d == 0.0) return {};
  // Visibility V = G / (4 N.L N.V), the microfacet form's denominator folded in.
  double v = 0.0;
  switch (m_p.g) {
    case Geometry::cook_torrance: v = G_cook_torrance(nh, nv, nl, lh) / (4.0 * nl * nv); break;
    case Geometry::kelemen: v = V_kelemen(lh); break;
    case Geometry::smith: v = G_smith_beckmann(nl, nv, m_p.m) / (4.0 * nl * nv); break;
  }
  // The 1981 form: F (pi D) G / (pi N.L N.V) = 4 F D G / (4 N.L N.V).
  const double form_scale = m_p.form == Form::cook_torrance_1981 ? 4.0 : 1.0;
  return m_p.ks * fresnel(lh) * (d * v * form_scale);
}

double CookTorrance::specular_pdf(const Vec3& wi, const Vec3& wo) const {
  const Vec3 h = half_vector(wi, wo);
  return reflect_jacobian_pdf(distribution(h.z) * h.z, wo, h);
}

Vec3 CookTorrance::specular_sample(const Vec3& wo, Vec2 u, double) const {
  // Blinn-Phong D cos = (n+2)/(2pi) cos^(n+1): a power-cosine lobe of exponent n + 1.
  const Vec3 h = m_p.d == Distribution::beckmann ? sample_beckmann_h(u, m_p.m) : sample_power_cosine(u, m_p.n + 1.0);
  return reflect(wo, h);
}

namespace {

template <typename E>
E pick(const std::string& word, std::initializer_list<std::pair<const char*, E>> table) {
  for (const auto& [name, value] : table) {
    if (word == name) return value;
  }
  return table.begin()->second;
}

}  // namespace

ModelInfo cook_torrance_model() {
  ModelInfo info;
  info.name = "cook-torrance";
  info.summary = "kd/pi + ks F D G / (4 N.L N.V)   (form=1981: F D' G / (pi N.L N.V), D' = pi D)";
  info.source = "Cook & Torrance 1981; lecture 5 'Cook-Torrance BRDF Model'; Walter et al. 2007";
  info.params = {
      kd_param("0.2"),
      ks_param("1"),
      {"m", ParamKind::scalar, "0.3", 1e-4, 10.0, {}, "Beckmann RMS slope (give m or n, not both)", 0, {}},
      {"n", ParamKind::scalar, "20.2222222222", 0.0, 1e6, {}, "Blinn-Phong exponent, n = 2/m^2 - 2", 0, {}},
      {"d", ParamKind::choice, "beckmann", 0, 0, {"beckmann", "blinn-phong"}, "normal distribution", 0, {}},
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
    q.d = pick<CookTorrance::Distribution>(p.choice("d"), {{"beckmann", CookTorrance::Distribution::beckmann},
                                                           {"blinn-phong", CookTorrance::Distribution::blinn_phong}});
    q.g = pick<CookTorrance::Geometry>(p.choice("g"), {{"smith", CookTorrance::Geometry::smith},
                                                       {"cook-torrance", CookTorrance::Geometry::cook_torrance},
                                                       {"kelemen", CookTorrance::Geometry::kelemen}});
    q.f = pick<CookTorrance::FresnelKind>(p.choice("f"), {{"schlick", CookTorrance::FresnelKind::schlick},
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
