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
#pragma once

#include <optional>

#include "shadelab/core/vec.h"

namespace shadelab {

class RoughDielectric {
 public:
  enum class Transport { radiance, importance };
  enum class Lobes { both, reflection, transmission };

  struct Sample {
    Vec3 wi;
    double f = 0.0;       // the BSDF value at (wo, wi) in the transport asked for
    double pdf = 0.0;     // per unit solid angle of wi, for the lobes asked for
    double weight = 0.0;  // f |wi.z| / pdf
  };

  // alpha: GGX roughness, floored at min_alpha (a smooth interface is the limit, reached to O(alpha)).
  RoughDielectric(double eta, double alpha);
  static constexpr double min_alpha = 1e-4;

  double eval(const Vec3& wo, const Vec3& wi, Transport mode) const;
  double pdf(const Vec3& wo, const Vec3& wi, Lobes lobes) const;
  std::optional<Sample> sample(const Vec3& wo, double u_lobe, Vec2 u, Transport mode, Lobes lobes) const;

  double eta() const { return m_eta; }
  double alpha() const { return m_alpha; }

 private:
  // The microfacet normal of the pair (turned to +Z) and whether it is a reflection; false when the pair has
  // none (a microfacet seen from the wrong side, or a degenerate pair).
  bool half_vector(const Vec3& wo, const Vec3& wi, Vec3& m, bool& reflect) const;
  double lambda(const Vec3& w) const;
  double visible_normal_pdf(const Vec3& wo, const Vec3& m) const;  // D_wo(m), wo on either side

  double m_eta;
  double m_alpha;
};

}  // namespace shadelab
