#include "shadelab/brdf/layered.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "shadelab/brdf/ggx.h"
#include "shadelab/brdf/lambert.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

namespace {

using Transport = RoughDielectric::Transport;
using Lobes = RoughDielectric::Lobes;

// The conductor base: GGX with height-correlated G2 and the F82-tint Fresnel (kernels/fresnel.sl
// F_schlick_f82_rgb), sampled by visible normals (Heitz 2018).
class F82Conductor final : public Brdf {
 public:
  F82Conductor(const Rgb& f0, const Rgb& tint, double alpha) : m_f0(f0), m_tint(tint), m_alpha(alpha) {}
  Rgb eval(const Vec3& wi, const Vec3& wo) const override {
    if (wi.z <= 0.0 || wo.z <= 0.0) return {};
    const Vec3 h = half_vector(wi, wo);
    const double dg = kernel::D_ggx(h.z, m_alpha) * kernel::G2_ggx_correlated(wi, wo, m_alpha, m_alpha);
    return Rgb(kernel::F_schlick_f82_rgb(dot(wi, h), m_f0, m_tint)) * (dg / (4.0 * wi.z * wo.z));
  }
  double pdf(const Vec3& wi, const Vec3& wo) const override { return ggx_vndf_pdf(wi, wo, m_alpha, m_alpha); }
  BrdfSample sample(const Vec3& wo, Vec2 u, double) const override {
    BrdfSample s;
    if (wo.z <= 0.0) return s;
    s.wi = reflect(wo, sample_ggx_vndf_heitz(wo, u, m_alpha, m_alpha));
    s.pdf = pdf(s.wi, wo);
    if (s.pdf > 0.0 && s.wi.z > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
    return s;
  }

 private:
  Rgb m_f0;
  Rgb m_tint;
  double m_alpha;
};

// The power heuristic with exponent 2 (Veach 1997, eq. 9.13): the weight of the strategy of density a.
double power_heuristic(double a, double b) {
  if (std::isinf(a)) return 1.0;
  const double a2 = a * a;
  const double b2 = b * b;
  return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

// SplitMix64's finalizer (Steele, Lea & Flood 2014) over the bits of each coordinate: the walk's seed.
std::uint64_t mix_bits(std::uint64_t h, double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  h ^= bits;
  h += 0x9e3779b97f4a7c15ULL;
  h = (h ^ (h >> 30u)) * 0xbf58476d1ce4e5b9ULL;
  h = (h ^ (h >> 27u)) * 0x94d049bb133111ebULL;
  return h ^ (h >> 31u);
}

std::uint64_t pair_hash(const Vec3& wi, const Vec3& wo, std::uint64_t seed) {
  std::uint64_t h = seed;
  for (double v : {wi.x, wi.y, wi.z, wo.x, wo.y, wo.z}) h = mix_bits(h, v);
  return h;
}

}  // namespace

LayeredSlab::LayeredSlab(const Params& p) : m_p(p), m_coat(p.coat_ior, p.coat_alpha, p.coat_scattering) {
  switch (p.base) {
    case Base::lambert: m_base = std::make_shared<Lambert>(p.base_color); break;
    case Base::conductor:
      m_base = std::make_shared<F82Conductor>(p.base_color, p.base_f82, std::max(p.base_alpha, RoughDielectric::min_alpha));
      break;
    case Base::ggx: {
      Ggx::Params g;
      g.kd = p.base_color;
      g.alpha_x = g.alpha_y = std::max(p.base_alpha, RoughDielectric::min_alpha);
      g.f = Ggx::FresnelKind::schlick;
      g.f0 = Rgb::gray(p.base_f0);
      g.ms = Ggx::MultipleScattering::kulla_conty;
      m_base = std::make_shared<Ggx>(g);
      break;
    }
  }
}

Rgb LayeredSlab::transmittance(const Vec3& w) const {
  if (m_p.coat_thickness == 0.0 || (m_p.coat_color.r == 1.0 && m_p.coat_color.g == 1.0 && m_p.coat_color.b == 1.0)) {
    return Rgb::gray(1.0);  // a clear slab (pow(1, d) = 1: skip the three pows)
  }
  const double d = m_p.coat_thickness / std::abs(w.z);
  return {std::pow(m_p.coat_color.r, d), std::pow(m_p.coat_color.g, d), std::pow(m_p.coat_color.b, d)};
}

template <typename Rng>
Rgb LayeredSlab::walk(const Vec3& wi, const Vec3& wo, Rng& rng) const {
  auto r = [&rng] { return rng.next_double(); };
  const double u0 = r();
  const Vec2 u1{r(), r()};
  const double u2 = r();
  const Vec2 u3{r(), r()};
  const auto entry = m_coat.sample(wo, u0, u1, Transport::radiance, Lobes::transmission);
  const auto exit = m_coat.sample(wi, u2, u3, Transport::importance, Lobes::transmission);
  if (!entry || !exit) return {};
  // The next-event path's last factors: T(e) f*(wi, e) |e.z| / p(e), e below the coat (the adjoint transmission
  // f*(wi, e) equals the radiance transmission f(e, wi): rough_dielectric.h).
  const Vec3 e = exit->wi;
  const Rgb exit_factor = transmittance(e) * (exit->f * std::abs(e.z) / exit->pdf);
  Rgb beta = Rgb::gray(entry->weight);
  Vec3 w = entry->wi;  // travelling down
  Rgb f;
  for (int depth = 0; depth < max_depth; ++depth) {
    if (depth > 3) {
      const double m = beta.max_component();
      if (m < 0.25) {
        const double q = 1.0 - m;
        if (r() < q) break;
        beta = beta / (1.0 - q);
      }
    }
    beta = beta * transmittance(w);  // down to the base
    const Vec3 v = -w;               // the base's view direction
    const Rgb fb = m_base->eval(-e, v);
    if (fb.max_component() > 0.0) {
      f += beta * fb * exit_factor * power_heuristic(exit->pdf, m_base->pdf(-e, v));
    }
    const Vec2 ub{r(), r()};
    const BrdfSample bs = m_base->sample(v, ub, r());
    if (!(bs.pdf > 0.0) || bs.wi.z <= 0.0 || !(bs.weight.max_component() > 0.0)) break;
    beta = beta * bs.weight;
    w = bs.wi;  // travelling up
    const double ft = m_coat.eval(-w, wi, Transport::radiance);
    if (ft > 0.0) {
      f += beta * transmittance(w) * (ft * power_heuristic(bs.pdf, m_coat.pdf(wi, -w, Lobes::transmission)));
    }
    beta = beta * transmittance(w);  // up to the coat
    const double ul = r();
    const Vec2 uc{r(), r()};
    const auto internal = m_coat.sample(-w, ul, uc, Transport::radiance, Lobes::reflection);
    if (!internal) break;
    beta = beta * internal->weight;
    w = internal->wi;  // travelling down again
  }
  return f;
}

Rgb LayeredSlab::walk_multiple(const Vec3& wi, const Vec3& wo, Pcg32& rng) const {
  // The coat's own reflection, from one walk on its microsurface.
  Rgb f = Rgb::gray(m_coat.eval_walk(wo, wi, Transport::radiance, rng));
  const auto entry = m_coat.sample_walk(wo, rng, Transport::radiance);
  if (!entry || entry->wi.z >= 0.0) return f;  // reflected by the coat: in its term above
  // The exit direction e below the coat, a walk from wi (importance: f*(wi, e) |e.z| / p(e) = its weight); a
  // walk from wi that is reflected gives no next-event path this time.
  const auto exit = m_coat.sample_walk(wi, rng, Transport::importance);
  const bool has_exit = exit && exit->wi.z < 0.0;
  const Vec3 e = has_exit ? exit->wi : Vec3{0.0, 0.0, -1.0};
  const Rgb exit_factor = has_exit ? transmittance(e) * exit->weight : Rgb{};
  const double exit_proxy = has_exit ? m_coat.pdf(wi, e, Lobes::transmission) : 0.0;  // the stand-in density
  Rgb beta = Rgb::gray(entry->weight);
  Vec3 w = entry->wi;  // travelling down
  for (int depth = 0; depth < max_depth; ++depth) {
    if (depth > 3) {
      const double m = beta.max_component();
      if (m < 0.25) {
        const double q = 1.0 - m;
        if (rng.next_double() < q) break;
        beta = beta / (1.0 - q);
      }
    }
    beta = beta * transmittance(w);  // down to the base
    const Vec3 v = -w;               // the base's view direction
    if (has_exit) {
      const Rgb fb = m_base->eval(-e, v);
      if (fb.max_component() > 0.0) {
        // The power heuristic (Veach 1997 eq. 9.13) with the stand-in; all of it where both densities are 0.
        const double a = exit_proxy * exit_proxy;
        const double pb = m_base->pdf(-e, v);
        const double weight = std::isinf(exit_proxy) || !(a + pb * pb > 0.0) ? 1.0 : a / (a + pb * pb);
        f += beta * fb * exit_factor * weight;
      }
    }
    const double ub0 = rng.next_double();
    const double ub1 = rng.next_double();
    const double ub2 = rng.next_double();
    const BrdfSample bs = m_base->sample(v, Vec2{ub0, ub1}, ub2);
    if (!(bs.pdf > 0.0) || bs.wi.z <= 0.0 || !(bs.weight.max_component() > 0.0)) break;
    beta = beta * bs.weight;
    w = bs.wi;  // travelling up
    const double q = m_coat.pdf(wi, -w, Lobes::transmission);
    const double weight = power_heuristic(bs.pdf, q);  // the complement of the next-event weight (bs.pdf > 0)
    if (weight > 0.0) {
      const double ft = m_coat.eval_walk(-w, wi, Transport::radiance, rng);
      if (ft > 0.0) f += beta * transmittance(w) * (ft * weight);
    }
    beta = beta * transmittance(w);  // up to the coat
    const auto internal = m_coat.sample_walk(-w, rng, Transport::radiance);
    if (!internal || internal->wi.z >= 0.0) break;  // out through the coat: counted by the two estimates
    beta = beta * internal->weight;
    w = internal->wi;  // travelling down again
  }
  return f;
}

LayeredSlab::Estimate LayeredSlab::estimate(const Vec3& wi, const Vec3& wo, int walks, Pcg32& rng) const {
  const bool multiple = m_p.coat_scattering == RoughDielectric::Scattering::multiple;
  Rgb sum;
  Rgb sum2;
  for (int s = 0; s < walks; ++s) {
    const Rgb x = multiple ? walk_multiple(wi, wo, rng) : walk(wi, wo, rng);
    sum += x;
    sum2 += x * x;
  }
  const double n = walks;
  const Rgb mean = sum / n;
  Estimate out;
  out.mean = multiple ? mean : Rgb::gray(m_coat.eval(wo, wi, Transport::radiance)) + mean;
  if (walks > 1) {
    for (int c = 0; c < 3; ++c) {
      const double var = std::max(0.0, (sum2[c] - n * mean[c] * mean[c]) / (n - 1.0));
      out.standard_error[c] = std::sqrt(var / n);
    }
  }
  return out;
}

Rgb LayeredSlab::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0.0 || wo.z <= 0.0) return {};
  if (m_p.coat_ior == 1.0) return transmittance(wo) * transmittance(wi) * m_base->eval(wi, wo);
  Pcg32 rng(pair_hash(wi, wo, m_p.seed));
  return estimate(wi, wo, m_p.walk_samples, rng).mean;
}

std::optional<Rgb> LayeredSlab::eval_standard_error(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0.0 || wo.z <= 0.0 || m_p.coat_ior == 1.0) return Rgb{};  // exact there
  if (m_p.walk_samples < 2) return std::nullopt;
  Pcg32 rng(pair_hash(wi, wo, m_p.seed));  // eval's own walks
  return estimate(wi, wo, m_p.walk_samples, rng).standard_error;
}

LayeredSlab::Estimate LayeredSlab::eval_estimate(const Vec3& wi, const Vec3& wo, int walks, std::uint64_t stream) const {
  if (wi.z <= 0.0 || wo.z <= 0.0 || walks < 1) return {};
  if (m_p.coat_ior == 1.0) return {eval(wi, wo), Rgb{}};
  Pcg32 rng(pair_hash(wi, wo, m_p.seed), 2 * stream + 1);
  return estimate(wi, wo, walks, rng);
}

double LayeredSlab::lobe_alpha() const {
  const double a = std::hypot(m_coat.alpha(), m_p.coat_ior * m_p.base_alpha);
  return std::clamp(a, 1e-3, 1.0);
}

LayeredSlab::Mixture LayeredSlab::mixture(const Vec3& wo) const {
  Mixture m{0.0, 0.0};
  if (m_p.coat_ior != 1.0) {
    // Estimates of the two parts' albedos: the coat's reflectance at wo and what the base returns through it.
    const double fr = kernel::F_dielectric(wo.z, m_p.coat_ior);
    const Rgb t = transmittance(Vec3{0.0, 0.0, 1.0});
    const Rgb base = m_p.base == Base::ggx ? m_p.base_color + Rgb::gray(m_p.base_f0) : m_p.base_color;
    const double below = (1.0 - fr) * (base * t * t).average();
    m.coat = std::clamp(fr + below > 0.0 ? fr / (fr + below) : 1.0, 0.1, 0.9);
  }
  if (m_p.base != Base::lambert) m.lobe = 0.75 * (1.0 - m.coat);
  return m;
}

double LayeredSlab::pdf(const Vec3& wi, const Vec3& wo) const {
  if (wo.z <= 0.0) return 0.0;
  const Mixture m = mixture(wo);
  double p = (1.0 - m.coat - m.lobe) * cosine_hemisphere_pdf(wi);
  if (m.coat > 0.0) p += m.coat * ggx_vndf_pdf(wi, wo, m_coat.alpha(), m_coat.alpha());
  if (m.lobe > 0.0) p += m.lobe * ggx_vndf_pdf(wi, wo, lobe_alpha(), lobe_alpha());
  return p;
}

BrdfSample LayeredSlab::sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  BrdfSample s;
  if (wo.z <= 0.0) return s;
  const Mixture m = mixture(wo);
  if (u_lobe < m.coat) {
    s.wi = reflect(wo, sample_ggx_vndf_heitz(wo, u, m_coat.alpha(), m_coat.alpha()));
  } else if (u_lobe < m.coat + m.lobe) {
    s.wi = reflect(wo, sample_ggx_vndf_heitz(wo, u, lobe_alpha(), lobe_alpha()));
  } else {
    s.wi = sample_cosine_hemisphere(u);
  }
  s.pdf = pdf(s.wi, wo);
  if (s.pdf > 0.0 && s.wi.z > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
  return s;
}

ModelInfo layered_model() {
  ModelInfo info;
  info.name = "layered";
  info.summary = "f_coat,r + E[position-free random walk: rough dielectric coat, absorbing slab, base lambert | conductor | ggx]";
  info.source = "Guo, Hasan & Zhao 2018 (random walk); Walter et al. 2007 (rough dielectric); Heitz 2014 (G2); "
                "Hoffman 2023 (F82 tint)";
  info.params = {
      {"coat_ior", ParamKind::scalar, "1.5", 1.0, 4.0, {}, "index of refraction of the coat (1: no interface)", 0, {}},
      {"coat_roughness", ParamKind::scalar, "0.1", 0.0, 1.0, {}, "perceptual roughness of the coat, alpha = r^2 (>= 1e-4)", 0, {}},
      {"coat_color", ParamKind::color, "1", 0.0, 1.0, {}, "transmittance through the slab at normal incidence (thickness 1)", 0, {}},
      {"coat_thickness", ParamKind::scalar, "1", 0.0, 100.0, {}, "optical thickness of the slab, in units where coat_color is its transmittance", 0, {}},
      {"coat_scattering", ParamKind::choice, "multiple", 0, 0, {"single", "multiple"}, "the coat's microsurface: scatters once (Walter 2007) or until the light leaves (Heitz 2016)", 0, {}},
      {"base", ParamKind::choice, "lambert", 0, 0, {"lambert", "conductor", "ggx"}, "the opaque base under the slab", 0, {}},
      {"base_color", ParamKind::color, "0.8", 0.0, 1.0, {}, "lambert: albedo; conductor: f0; ggx: kd", 0, {}},
      {"base_roughness", ParamKind::scalar, "0.3", 0.0, 1.0, {}, "perceptual roughness of a conductor or ggx base (alpha >= 1e-4)", 0, {}},
      {"base_f82", ParamKind::color, "1", 0.0, 1.0, {}, "conductor: F82 tint (1: Schlick)", 0, {}},
      {"base_f0", ParamKind::scalar, "0.04", 0.0, 1.0, {}, "ggx base: Schlick f0", 0, {}},
      {"walk_samples", ParamKind::scalar, "4", 1.0, 65536.0, {}, "random walks averaged per eval (a whole number)", 0, {}},
      {"seed", ParamKind::scalar, "0", 0.0, 4294967295.0, {}, "seed of the walks' random numbers (a whole number)", 0, {}},
  };
  info.create = [](const ParamValues& p) -> Result<BrdfPtr> {
    for (const char* name : {"walk_samples", "seed"}) {
      const double v = p.scalar(name);
      if (v != std::floor(v)) {
        char text[64];
        std::snprintf(text, sizeof text, "%.17g", v);
        return make_error(std::string("brdf layered: parameter '") + name + "' = " + text + " is not a whole number");
      }
    }
    LayeredSlab::Params q;
    q.coat_ior = p.scalar("coat_ior");
    q.coat_alpha = alpha_from_perceptual_roughness(p.scalar("coat_roughness"));
    q.coat_color = p.color("coat_color");
    q.coat_thickness = p.scalar("coat_thickness");
    q.coat_scattering = pick_choice<RoughDielectric::Scattering>(
        p.choice("coat_scattering"), {{"multiple", RoughDielectric::Scattering::multiple}, {"single", RoughDielectric::Scattering::single}});
    q.base = pick_choice<LayeredSlab::Base>(p.choice("base"), {{"lambert", LayeredSlab::Base::lambert},
                                                               {"conductor", LayeredSlab::Base::conductor},
                                                               {"ggx", LayeredSlab::Base::ggx}});
    q.base_color = p.color("base_color");
    q.base_alpha = alpha_from_perceptual_roughness(p.scalar("base_roughness"));
    q.base_f82 = p.color("base_f82");
    q.base_f0 = p.scalar("base_f0");
    q.walk_samples = static_cast<int>(p.scalar("walk_samples"));
    q.seed = static_cast<std::uint64_t>(p.scalar("seed"));
    return BrdfPtr(new LayeredSlab(q));
  };
  return info;
}

}  // namespace shadelab
