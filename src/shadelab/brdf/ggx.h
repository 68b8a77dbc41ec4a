// ggx: the GGX (Trowbridge-Reitz) microfacet model that engines ship, over a Lambertian base:
//
//   f_r = kd/pi + ks (F(L.H) D(h) G2(wi, wo) / (4 N.L N.V)   [ + f_ms with ms = kulla-conty ])
//
//   ks tints the specular lobe (default 1; Cycles' Glossy BSDF colour, with f = none).
//
//   D  = 1 / (pi ax ay (hx^2/ax^2 + hy^2/ay^2 + hz^2)^2)  (Trowbridge & Reitz 1975; Walter et al. 2007 eq. 33;
//        anisotropic as in Heitz 2014 eq. 85), alpha = perceptual roughness^2 (Burley 2012).
//   G2 = smith-correlated: 1 / (1 + Lambda(wi) + Lambda(wo)) (Heitz 2014 eq. 99) | smith-separable:
//        G1(wi) G1(wo) (eq. 98), Lambda = (sqrt(1 + (ax^2 x^2 + ay^2 y^2)/z^2) - 1)/2 (eq. 86).
//   F  = schlick (f0) | dielectric (ior) | conductor (ior, k) | none (F = 1), at L.H, as cook-torrance has them.
//   f_ms = F_ms (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - E_avg)), F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg))
//        (Kulla & Conty 2017, "Revisiting Physically Based Shading at Imageworks", slides 16-19), E and E_avg
//        from the tables of kernels/ggx_energy.sl (computed by quadrature, tables.cpp).
// eval is the kernel kernels/ggx.sl (the text shaders also use). Anisotropic when alpha_x != alpha_y
// (tangent +X, bitangent +Y); ms then reads the tables at sqrt(ax ay), an approximation.
//
// Samplers of the specular lobe (microfacet.h), each with its exact pdf:
//   ndf           h with density D cos(theta_h) (Walter et al. 2007 eqs. 35-36)
//   vndf          visible normals, Heitz 2018 (JCGT 7(4)), pdf G1(wo) D / (4 wo.z)
//   vndf-caps     the same density by spherical caps, Dupuy & Benyoub 2023 (HPG)
//   vndf-bounded  Eto & Tokuyoshi 2023 (SIGGRAPH Asia TC): caps cut to the half vectors that can reflect above
//                 the horizon; the default (lowest variance: tested)
// The diffuse base (and, with ms, the multiple-scattering lobe, which is diffuse-like) is sampled by the
// cosine lobe of LobeMixtureBrdf's one-sample MIS.
#pragma once

#include "shadelab/brdf/lobe_mixture.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class Ggx final : public LobeMixtureBrdf {
 public:
  enum class Sampler { ndf, vndf, vndf_caps, vndf_bounded };
  enum class Geometry { smith_separable, smith_correlated };  // the kernel's GGX_ENERGY_G_* numbering
  enum class FresnelKind { dielectric, conductor, schlick, none };  // the kernel's FRESNEL_* numbering
  enum class MultipleScattering { none, kulla_conty };

  struct Params {
    Rgb kd{0.2, 0.2, 0.2};
    Rgb ks{1.0, 1.0, 1.0};
    double alpha_x = 0.25;
    double alpha_y = 0.25;
    FresnelKind f = FresnelKind::schlick;
    Rgb f0{0.04, 0.04, 0.04};
    Rgb ior{1.5, 1.5, 1.5};
    Rgb k{0.0, 0.0, 0.0};
    Geometry g = Geometry::smith_correlated;
    MultipleScattering ms = MultipleScattering::none;
    Sampler sampler = Sampler::vndf_bounded;
  };

  explicit Ggx(const Params& p);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::ggx_eval(m_k, wi, wo); }
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::ggx_eval>(m_k, wi, wo, out, n, check_unit);
  }
  // The visible-normal samplers' densities jump at their support's edge below the horizon (brdf.h).
  bool pdf_smooth_below_horizon() const override { return false; }
  std::optional<KernelBinding> kernel_binding() const override;
  // GGX's alpha (the geometric mean of alpha_x and alpha_y) as a Beckmann m (microfacet.h).
  double game_phong_exponent() const override { return phong_exponent_from_ggx_alpha(std::sqrt(m_p.alpha_x * m_p.alpha_y)); }
  std::optional<SplitSumInputs> split_sum_inputs() const override;

  const Params& params() const { return m_p; }
  const kernel::GgxState& state() const { return m_k; }
  // The density of the specular sampler alone (wo above the horizon), for the variance analysis.
  double sampler_pdf(const Vec3& wi, const Vec3& wo) const { return specular_pdf(wi, wo); }

 protected:
  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  Params m_p;
  kernel::GgxState m_k;
};

}  // namespace shadelab
