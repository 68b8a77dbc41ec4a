#include "shadelab/brdf/rough_dielectric.h"

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/microfacet.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

namespace {

// ln B(a, b) = ln Gamma(a) + ln Gamma(b) - ln Gamma(a + b); lgamma_r, not lgamma, which writes the global
// signgam (a data race between render threads). a, b >= 1 here, so every Gamma is positive.
double log_beta(double a, double b) {
  int sign = 0;
  return ::lgamma_r(a, &sign) + ::lgamma_r(b, &sign) - ::lgamma_r(a + b, &sign);
}

}  // namespace

RoughDielectric::RoughDielectric(double eta, double alpha) : m_eta(eta), m_alpha(std::max(alpha, min_alpha)) {}

double RoughDielectric::lambda(const Vec3& w) const {
  return kernel::lambda_ggx(Vec3{w.x, w.y, std::abs(w.z)}, m_alpha, m_alpha);
}

bool RoughDielectric::half_vector(const Vec3& wo, const Vec3& wi, Vec3& m, bool& reflect) const {
  if (wo.z == 0.0 || wi.z == 0.0) return false;
  reflect = wo.z * wi.z > 0.0;
  // Walter et al. 2007 eq. 16: h = -(eta_o wo + eta_i wi) with eta_o = 1 (wo's side), eta_i = wi's side
  // relative to it; reflection: wo + wi (eq. 13).
  const double etap = reflect ? 1.0 : (wo.z > 0.0 ? m_eta : 1.0 / m_eta);
  const Vec3 h = wo + wi * etap;
  const double len2 = dot(h, h);
  if (!(len2 > 0.0)) return false;
  m = h / std::sqrt(len2);
  if (m.z < 0.0) m = -m;
  if (m.z <= 0.0) return false;
  // The microfacet faces each direction from that direction's side of the surface.
  return dot(wo, m) * wo.z > 0.0 && dot(wi, m) * wi.z > 0.0;
}

double RoughDielectric::visible_normal_pdf(const Vec3& wo, const Vec3& m) const {
  // D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z (Heitz 2014 eq. 38); from below, the mirror configuration.
  const Vec3 w = wo.z < 0.0 ? -wo : wo;
  const double c = dot(w, m);
  if (c <= 0.0) return 0.0;
  return c * kernel::D_ggx(m.z, m_alpha) / ((1.0 + lambda(w)) * w.z);
}

double RoughDielectric::eval(const Vec3& wo, const Vec3& wi, Transport mode) const {
  Vec3 m;
  bool reflect = false;
  if (!half_vector(wo, wi, m, reflect)) return 0.0;
  const double d = kernel::D_ggx(m.z, m_alpha);
  const double f = kernel::F_dielectric(dot(wo, m), m_eta);
  const double lo = lambda(wo);
  const double li = lambda(wi);
  if (reflect) return f * d / ((1.0 + (lo + li)) * 4.0 * std::abs(wo.z) * std::abs(wi.z));
  const double etap = wo.z > 0.0 ? m_eta : 1.0 / m_eta;
  const double g = std::exp(log_beta(1.0 + lo, 1.0 + li));
  const double im = dot(wi, m);
  const double om = dot(wo, m);
  const double denom = (etap * im + om) * (etap * im + om);
  double value = std::abs(im * om) * (1.0 - f) * d * g / (std::abs(wi.z) * std::abs(wo.z) * denom);
  if (mode == Transport::importance) value *= etap * etap;
  return value;
}

double RoughDielectric::pdf(const Vec3& wo, const Vec3& wi, Lobes lobes) const {
  Vec3 m;
  bool reflect = false;
  if (!half_vector(wo, wi, m, reflect)) return 0.0;
  if ((reflect && lobes == Lobes::transmission) || (!reflect && lobes == Lobes::reflection)) return 0.0;
  const double pm = visible_normal_pdf(wo, m);
  const double om = dot(wo, m);
  const double f = kernel::F_dielectric(om, m_eta);
  if (reflect) {
    // Reflection's Jacobian 1 / (4 |wo.m|) (Walter et al. 2007 eq. 14).
    const double p = pm / (4.0 * std::abs(om));
    return lobes == Lobes::both ? p * f : p;
  }
  // Refraction's Jacobian eta_i^2 |wi.m| / (eta_i wi.m + eta_o wo.m)^2 (Walter et al. 2007 eq. 17).
  const double etap = wo.z > 0.0 ? m_eta : 1.0 / m_eta;
  const double im = dot(wi, m);
  const double denom = (etap * im + om) * (etap * im + om);
  const double p = pm * etap * etap * std::abs(im) / denom;
  return lobes == Lobes::both ? p * (1.0 - f) : p;
}

std::optional<RoughDielectric::Sample> RoughDielectric::sample(const Vec3& wo, double u_lobe, Vec2 u, Transport mode,
                                                               Lobes lobes) const {
  if (wo.z == 0.0) return std::nullopt;
  const Vec3 w = wo.z < 0.0 ? -wo : wo;
  const Vec3 m = sample_ggx_vndf_heitz(w, u, m_alpha, m_alpha);
  const double om = dot(wo, m);
  const double f = kernel::F_dielectric(om, m_eta);
  bool is_reflection = lobes == Lobes::reflection;
  if (lobes == Lobes::both) is_reflection = u_lobe < f;
  Vec3 wi;
  if (is_reflection) {
    wi = reflect(wo, m);
    if (wi.z * wo.z <= 0.0) return std::nullopt;
  } else {
    // Snell's law about the microfacet turned toward wo: wi = -wo / e + (cos_o / e - cos_t) n, e = n_t / n_i.
    const Vec3 n = om > 0.0 ? m : -m;
    const double cos_o = std::abs(om);
    const double e = wo.z > 0.0 ? m_eta : 1.0 / m_eta;
    const double sin2_t = (1.0 - cos_o * cos_o) / (e * e);
    if (sin2_t >= 1.0) return std::nullopt;  // total internal reflection: no transmitted direction
    const double cos_t = std::sqrt(1.0 - sin2_t);
    wi = normalize(-wo / e + n * (cos_o / e - cos_t));
    if (wi.z * wo.z >= 0.0) return std::nullopt;
  }
  Sample s;
  s.wi = wi;
  s.f = eval(wo, wi, mode);
  s.pdf = pdf(wo, wi, lobes);
  if (!(s.pdf > 0.0) || !(s.f > 0.0) || !std::isfinite(s.f) || !std::isfinite(s.pdf)) return std::nullopt;
  s.weight = s.f * std::abs(wi.z) / s.pdf;
  return s;
}

}  // namespace shadelab
