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

RoughDielectric::RoughDielectric(double eta, double alpha, Scattering scattering)
    : m_eta(eta), m_alpha(std::max(alpha, min_alpha)), m_scattering(scattering) {}

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

double RoughDielectric::walk_visible_normal_pdf(const Vec3& v, const Vec3& m) const {
  const double c = dot(v, m);
  if (m.z <= 0.0 || c <= 0.0) return 0.0;
  // The projected area of the normals facing v, integral max(0, v.m) D(m) dm: v.z (1 + Lambda(v)) above, and
  // below, where Lambda(v) = -1 - Lambda(-v) (Heitz et al. 2016, the microvolume's Lambda), |v.z| Lambda(-v);
  // its limit alpha / 2 at the horizon (Lambda ~ alpha tan(theta) / 2), where Lambda itself is 0 / 0.
  const double l = v.z != 0.0 ? lambda(v) : 0.0;
  const double area = v.z > 0.0 ? v.z * (1.0 + l) : (v.z < 0.0 ? -v.z * l : 0.5 * m_alpha);
  if (!(area > 0.0)) return 0.0;
  return c * kernel::D_ggx(m.z, m_alpha) / area;  // D_v(m) = max(0, v.m) D(m) / area (Heitz 2014 eq. 38)
}

double RoughDielectric::phase_reflection(const Vec3& v, const Vec3& t, double eta) const {
  const Vec3 h = v + t;
  const double len2 = dot(h, h);
  if (!(len2 > 0.0)) return 0.0;
  const Vec3 m = h / std::sqrt(len2);
  const double c = dot(v, m);
  if (m.z <= 0.0 || c <= 0.0) return 0.0;
  // F D_v(m) / (4 v.m): the visible normal's density times reflection's Jacobian (Heitz et al. 2016, the
  // dielectric phase function).
  return kernel::F_dielectric(c, eta) * walk_visible_normal_pdf(v, m) / (4.0 * c);
}

double RoughDielectric::phase_transmission(const Vec3& v, const Vec3& t, double eta) const {
  // m = -(v + eta t) turned to +Z (Walter et al. 2007 eq. 16, eta the relative index of t's side).
  Vec3 h = -(v + t * eta);
  const double len2 = dot(h, h);
  if (!(len2 > 0.0)) return 0.0;
  Vec3 m = h / std::sqrt(len2);
  if (m.z < 0.0) m = -m;
  const double vm = dot(v, m);
  const double tm = dot(t, m);
  if (m.z <= 0.0 || vm <= 0.0 || tm >= 0.0) return 0.0;
  // (1 - F) D_v(m) eta^2 |t.m| / (v.m + eta t.m)^2: refraction's Jacobian (Walter et al. 2007 eq. 17; Heitz et
  // al. 2016, the dielectric phase function).
  const double denom = (vm + eta * tm) * (vm + eta * tm);
  return (1.0 - kernel::F_dielectric(vm, eta)) * walk_visible_normal_pdf(v, m) * eta * eta * std::abs(tm) / denom;
}

std::optional<Vec3> RoughDielectric::random_walk(const Vec3& wo, Pcg32& rng, const Vec3* target, double* nee,
                                                 int* events) const {
  if (wo.z == 0.0) return std::nullopt;
  // The frame of the side the ray is on: the surface's for above, its point reflection for below (the
  // microsurface seen from below is the same random surface: isotropic normals, a symmetric height law).
  bool below = wo.z < 0.0;
  Vec3 d = below ? wo : -wo;  // the direction of travel, in the side's frame: down
  double c = 1.0;             // C1 of the ray's height: above the whole microsurface
  for (int k = 0; k < max_walk_events; ++k) {
    // The next height (Heitz et al. 2016's height sampling, in terms of c = C1(h)).
    const double lu = std::log1p(-rng.next_double());  // ln(1 - u), u in [0, 1): finite, <= 0
    if (d.z > 0.0) {
      const double l = lambda(d);
      // Going up: no hit with probability G1(d, h) = c^Lambda(d), so it leaves when 1 - u <= c^Lambda.
      if (!(l > 0.0) || lu <= l * std::log(c)) return below ? -d : d;
      c *= std::exp(-lu / l);  // C1(h') = C1(h) / (1 - u)^(1 / Lambda(d)), < 1 here
    } else if (d.z < 0.0) {
      c *= std::exp(lu / (1.0 + lambda(d)));  // going down: C1(h') = C1(h) (1 - u)^(1 / (1 + Lambda(-d)))
    }  // exactly horizontal (measure zero): a hit at the same height
    if (events) ++*events;
    const double eta = below ? 1.0 / m_eta : m_eta;  // relative index of the other side
    const Vec3 v = -d;
    if (target && k > 0) {
      // Next-event estimation: leave along the target from this hit; reflection stays on this side, escaping up
      // with c^Lambda(t); transmission goes to the other side, escaping there with (1 - c)^Lambda(-t).
      const Vec3 t = below ? -*target : *target;
      if (t.z > 0.0) {
        *nee += phase_reflection(v, t, eta) * std::pow(c, lambda(t));
      } else if (t.z < 0.0) {
        *nee += phase_transmission(v, t, eta) * std::pow(1.0 - c, lambda(t));
      }
    }
    // The phase function: a visible normal of v, either side of the mean surface (the spherical cap of
    // sample_ggx_vndf_caps holds for v.z < 0 too: z in [-v_s.z, 1]), then Fresnel's choice.
    const double u1 = rng.next_double();
    const double u2 = rng.next_double();
    const Vec3 m = sample_ggx_vndf_caps(v, Vec2{u1, u2}, m_alpha, m_alpha);
    const double vm = dot(v, m);
    if (!(vm > 0.0)) return std::nullopt;  // a rounding at the cap's rim: no direction (never seen in tests)
    const double f = kernel::F_dielectric(vm, eta);
    if (rng.next_double() < f) {
      d = reflect(v, m);
    } else {
      // Snell's law about m (facing v): t = -v / eta + (cos_v / eta - cos_t) m; f < 1 here, so no total
      // internal reflection. Then the frame of the other side: directions and heights point-reflected.
      const double sin2_t = (1.0 - vm * vm) / (eta * eta);
      const double cos_t = std::sqrt(std::max(0.0, 1.0 - sin2_t));
      const Vec3 t = normalize(-v / eta + m * (vm / eta - cos_t));
      d = -t;
      c = 1.0 - c;
      below = !below;
    }
  }
  return std::nullopt;
}

std::optional<RoughDielectric::WalkSample> RoughDielectric::sample_walk(const Vec3& wo, Pcg32& rng, Transport mode) const {
  if (m_scattering == Scattering::single) {
    const double ul = rng.next_double();
    const double u1 = rng.next_double();
    const double u2 = rng.next_double();
    const auto s = sample(wo, ul, Vec2{u1, u2}, mode, Lobes::both);
    if (!s) return std::nullopt;
    return WalkSample{s->wi, s->weight};
  }
  const auto wi = random_walk(wo, rng, nullptr, nullptr, nullptr);
  if (!wi || wi->z == 0.0) return std::nullopt;
  WalkSample s{*wi, 1.0};
  // The walk's density is the importance form's f |wi.z|; the radiance form is 1 / eta_i^2 of it across.
  if (mode == Transport::radiance && wi->z * wo.z < 0.0) {
    const double etap = wo.z > 0.0 ? m_eta : 1.0 / m_eta;
    s.weight = 1.0 / (etap * etap);
  }
  return s;
}

double RoughDielectric::eval_walk(const Vec3& wo, const Vec3& wi, Transport mode, Pcg32& rng) const {
  if (m_scattering == Scattering::single) return eval(wo, wi, mode);
  if (wo.z == 0.0 || wi.z == 0.0) return 0.0;
  double nee = 0.0;
  random_walk(wo, rng, &wi, &nee, nullptr);
  // The walk's density of leaving along wi, over |wi.z|, is the importance form (radiance: 1 / eta_i^2 across).
  double higher = nee / std::abs(wi.z);
  if (mode == Transport::radiance && wi.z * wo.z < 0.0) {
    const double etap = wo.z > 0.0 ? m_eta : 1.0 / m_eta;
    higher /= etap * etap;
  }
  return eval(wo, wi, mode) + higher;
}

}  // namespace shadelab
