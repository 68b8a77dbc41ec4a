// cook-torrance: a microfacet specular lobe over a Lambertian base, f_r = kd/pi + ks F D G / (c (N.L)(N.V)).
//
//   form = microfacet: c = 4 and D normalized, integral of D cos(theta_h) d(omega_h) = 1
//                      (Walter et al., "Microfacet Models for Refraction", EGSR 2007, eq. 20).
//   form = 1981:       c = pi and the paper's D without the 1/pi (Cook & Torrance, "A Reflectance Model for
//                      Computer Graphics", ACM TOG 1982 / SIGGRAPH 1981, eq. 4; lecture 5 "Cook-Torrance").
// Since D_1981 = pi D, the 1981 form is exactly 4 times the microfacet form (docs/models/cook-torrance.md).
//
// d = beckmann (roughness m) | blinn-phong (exponent n, heightfield normalization (n+2)/(2pi)) | ggx (GGX with
// alpha = m, Walter et al. 2007 eq. 33, so the 1981 form can be compared term by term with ggx); m and n are
// converted by n = 2/m^2 - 2 when the other is given. With d = ggx, g = smith is GGX's height-correlated Smith. g = cook-torrance (the min(1, ...) term) | kelemen
// (G/(N.L N.V) ~ 1/(L.H)^2) | smith (height-correlated Smith for Beckmann). f = dielectric (ior) |
// conductor (ior, k) | schlick (f0) | none (F = 1). F is evaluated at L.H.
// eval is the kernel kernels/cook_torrance.sl (the text shaders also use).
// Sampling: H with density D(h) cos(theta_h) (for GGX, microfacet.h's sample_ggx_ndf), L = reflect(V, H),
// pdf = D cos(theta_h) / (4 V.H).
#pragma once

#include "shadelab/brdf/gloss.h"
#include "shadelab/brdf/lobe_mixture.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class CookTorrance final : public LobeMixtureBrdf {
 public:
  enum class Distribution { beckmann, blinn_phong, ggx };
  enum class Geometry { cook_torrance, kelemen, smith };
  enum class FresnelKind { dielectric, conductor, schlick, none };
  enum class Form { microfacet, cook_torrance_1981 };

  struct Params {
    Rgb kd{0.2, 0.2, 0.2};
    Rgb ks{1.0, 1.0, 1.0};
    double m = 0.3;  // Beckmann RMS slope
    double n = exponent_from_m(0.3);
    Distribution d = Distribution::beckmann;
    Geometry g = Geometry::smith;
    FresnelKind f = FresnelKind::schlick;
    Rgb ior{1.5, 1.5, 1.5};
    Rgb k{0.0, 0.0, 0.0};
    Rgb f0{0.04, 0.04, 0.04};
    Form form = Form::microfacet;
    static double exponent_from_m(double m_) { return 2.0 / (m_ * m_) - 2.0; }
  };

  explicit CookTorrance(const Params& p);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::cook_torrance_eval(m_k, wi, wo); }
  std::optional<KernelBinding> kernel_binding() const override;
  // The Blinn-Phong exponent n (given, or 2/m^2 - 2 of the Beckmann m) as a Phong lobe of n/4 (brdf/gloss.h);
  // a gloss map's exponent is a Blinn-Phong one.
  double game_phong_exponent() const override { return phong_exponent_from_blinn_phong(m_p.n); }
  bool gloss_exponent_is_blinn_phong() const override { return true; }

  Rgb fresnel(double cos_i) const;
  double distribution(double cos_h) const;

 protected:
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::cook_torrance_eval>(m_k, wi, wo, out, n, check_unit);
  }

  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  Params m_p;
  kernel::CookTorranceState m_k;
};

}  // namespace shadelab
