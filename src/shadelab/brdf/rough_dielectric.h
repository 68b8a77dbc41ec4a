// rough_dielectric: the rough interface between two dielectrics, a BSDF (reflection and transmission), the
// coat of the layered ground truth (brdf/layered.h). Isotropic GGX microfacets (Walter et al. 2007,
// "Microfacet Models for Refraction through Rough Surfaces", EGSR):
//
//   reflection   f_r = F(wo.m) D(m) G2(wo, wi) / (4 |wo.z| |wi.z|),  m = normalize(wo + wi)
//   transmission f_t = |wi.m| |wo.m| (1 - F(wo.m)) D(m) G2(wo, wi) / (|wi.z| |wo.z| (eta_i wi.m + eta_o wo.m)^2)
//                      (eq. 21, with eta_o = 1 the index on wo's side and eta_i the relative index on wi's
//                      side, m = -normalize(eta_o wo + eta_i wi) turned to +Z: eq. 16), the radiance form; the
//                      importance (adjoint) form is eta_i^2 times it (Veach 1997, section 5.2).
//   F  the exact dielectric Fresnel reflectance at wo.m (kernels/fresnel.sl F_dielectric).
//   G2 height-correlated Smith: reflection 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014 eq. 99); transmission
//      B(1 + Lambda(wo), 1 + Lambda(wi)), the Beta function: a microfacet at height h (height CDF C) is seen
//      from above with probability C^Lambda and from below with (1 - C)^Lambda, and integral_0^1 C^a (1 - C)^b dC
//      = B(1 + a, 1 + b) (Heitz 2014, section 6.2). Lambda of a direction below the surface is that of its
//      mirror image above.
//
// eta = index below / index above (> 0; 1 is no interface). Sampling: m from the visible normals of wo (turned
// above the surface when wo is below it; Heitz 2018), then reflection with probability F and transmission
// with 1 - F, or only the lobe asked for (total internal reflection then fails a transmission-only sample).
// Each pdf is the exact density of the sampler that was asked for, per unit solid angle of wi.
//
// Scattering::multiple (Heitz, Hanika, d'Eon & Dachsbacher 2016, "Multiple-Scattering Microfacet BSDFs with the
// Smith Model", SIGGRAPH): light may hit the microsurface many times, reflecting or refracting at each hit, until
// it leaves on either side: the interface then conserves energy (reflected + transmitted = 1). eval, pdf and
// sample above stay the single-scattering lobe; the rng-taking sample_walk and eval_walk give the whole BSDF:
//   sample_walk: the random walk itself, an exact sample. Heights are Smith's uncorrelated ones, tracked by their
//     CDF value c = C1(h) in (0, 1] (any height distribution gives the same walk); a ray going up from c escapes
//     with probability c^Lambda(w) (G1(w, h)), else it hits where C1 = c / (1 - u)^(1 / Lambda(w)); a ray going
//     down hits where C1 = c (1 - u)^(1 / (1 + Lambda(-w))). At a hit the normal is a visible normal of the
//     reversed ray (for rays going up too: Dupuy & Benyoub's spherical caps sample it), the ray reflects with
//     the exact Fresnel F and refracts with 1 - F. Below the surface the walk runs in the point-reflected frame
//     (heights c -> 1 - c, eta -> 1 / eta). At most max_walk_events hits: a longer walk is dropped (none of
//     the 480 000 walks of rough_dielectric_test.cpp's energy test, alpha 0 to 1, was; the longest had 16 hits).
//     Its density is the importance form's f |wi.z|, so the weight is 1 (importance) or 1 / eta_i^2 for a
//     transmission (radiance).
//   eval_walk: an unbiased estimate from one walk: the single-scattering value (the walk's first hit, in
//     expectation: the height-correlated G2 and the Beta-function transmission above) plus, at each later hit,
//     next-event estimation: the phase function toward wi times the probability of escaping along wi from that
//     height (Heitz et al. 2016, section 5's estimator, with the first order in closed form).
// Scattering::single makes sample_walk and eval_walk the single-scattering sample (both lobes) and eval.
#pragma once

#include <optional>

#include "shadelab/core/vec.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {

class RoughDielectric {
 public:
  enum class Transport { radiance, importance };
  enum class Lobes { both, reflection, transmission };
  enum class Scattering { single, multiple };

  struct Sample {
    Vec3 wi;
    double f = 0.0;       // the BSDF value at (wo, wi) in the transport asked for
    double pdf = 0.0;     // per unit solid angle of wi, for the lobes asked for
    double weight = 0.0;  // f |wi.z| / pdf
  };

  // alpha: GGX roughness, floored at min_alpha (a smooth interface is the limit, reached to O(alpha)).
  RoughDielectric(double eta, double alpha, Scattering scattering = Scattering::single);
  static constexpr double min_alpha = 1e-4;
  static constexpr int max_walk_events = 256;  // the most microsurface hits of one walk (multiple scattering)

  struct WalkSample {
    Vec3 wi;
    double weight = 0.0;  // f |wi.z| / pdf of the whole BSDF
  };

  double eval(const Vec3& wo, const Vec3& wi, Transport mode) const;
  double pdf(const Vec3& wo, const Vec3& wi, Lobes lobes) const;
  std::optional<Sample> sample(const Vec3& wo, double u_lobe, Vec2 u, Transport mode, Lobes lobes) const;

  // The whole BSDF (the walk for Scattering::multiple): a sample of wi from wo (nullopt: none, or a walk cut at
  // max_walk_events), and an unbiased estimate of f(wo, wi) from one walk; both draw from rng.
  std::optional<WalkSample> sample_walk(const Vec3& wo, Pcg32& rng, Transport mode) const;
  double eval_walk(const Vec3& wo, const Vec3& wi, Transport mode, Pcg32& rng) const;
  // One walk from wo: the direction it leaves along (nullopt when cut), and, with `target`, the sum over its hits
  // after the first of phase(target) * escape probability along target, added to *nee. `events` counts its hits.
  std::optional<Vec3> random_walk(const Vec3& wo, Pcg32& rng, const Vec3* target, double* nee, int* events) const;

  Scattering scattering() const { return m_scattering; }
  double eta() const { return m_eta; }
  double alpha() const { return m_alpha; }

 private:
  // The microfacet normal of the pair (turned to +Z) and whether it is a reflection; false when the pair has
  // none (a microfacet seen from the wrong side, or a degenerate pair).
  bool half_vector(const Vec3& wo, const Vec3& wi, Vec3& m, bool& reflect) const;
  double lambda(const Vec3& w) const;
  double visible_normal_pdf(const Vec3& wo, const Vec3& m) const;  // D_wo(m), wo on either side
  // The walk's pieces, in the frame of the side the ray is on (the surface above, eta the relative index across):
  // the density of visible normals of v, v on either side of the mean surface (normals m.z > 0, v.m > 0).
  double walk_visible_normal_pdf(const Vec3& v, const Vec3& m) const;
  // The phase function: the density of leaving along t after a hit by a ray travelling -v.
  double phase_reflection(const Vec3& v, const Vec3& t, double eta) const;
  double phase_transmission(const Vec3& v, const Vec3& t, double eta) const;

  double m_eta;
  double m_alpha;
  Scattering m_scattering;
};

}  // namespace shadelab
