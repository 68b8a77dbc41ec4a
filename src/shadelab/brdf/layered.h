// layered: the layered ground truth. A slab of an absorbing, non-scattering medium under a rough dielectric
// interface (the coat), over an opaque base; its BRDF is estimated by a position-free Monte Carlo random walk
// through the slab (Guo, Hasan & Zhao 2018, "Position-Free Monte Carlo Simulation for Arbitrary Layered
// BSDFs", SIGGRAPH Asia; the estimator of pbrt-v4's LayeredBxDF, Pharr, Jakob & Humphreys 2023, section 14.3):
//
//   f(wi, wo) = f_coat,r(wo, wi) + E[ walk(wo -> wi) ]
//
//   The walk enters through the coat from wo (its transmission, sampled), crosses the slab (transmittance
//   T(w) = coat_color^(coat_thickness / |w.z|), Beer-Lambert: coat_color is the colour seen through the slab at
//   normal incidence when coat_thickness = 1), scatters at the base (its BRDF, sampled) and at the coat's
//   underside (its internal reflection, sampled), and at each base vertex adds the two ways of leaving toward
//   wi, weighted by the power heuristic (Veach 1997): next-event estimation through a transmission direction e
//   sampled once per walk from wi with the coat's adjoint transmission, and the coat's transmission evaluated
//   along the base's sampled direction. Russian roulette after 3 bounces (survival = the largest channel of
//   the throughput when below 0.25) keeps it unbiased; at most max_depth base bounces.
//   coat: RoughDielectric (brdf/rough_dielectric.h), eta = coat_ior, alpha = coat_roughness^2 (>= 1e-4).
//   base: lambert (base_color / pi) | conductor (GGX, height-correlated G2, F82-tint Fresnel with f0 = base_color
//   and tint base_f82, kernels/fresnel.sl) | ggx (the registry's ggx: kd = base_color, Schlick f0 = base_f0,
//   Kulla-Conty multiple scattering). The base sees the directions inside the slab.
//   coat_ior = 1 is no interface: f = T(wo) f_base(wi, wo) T(wi) exactly (no walk).
//   coat_scattering = multiple (the default): the coat scatters many times on its microsurface (Heitz et al.
//   2016; rough_dielectric.h sample_walk, eval_walk), so a clear coat over a white base conserves energy. Then
//   every coat crossing is a walk on the microsurface: the entry, the exit direction e and each internal
//   reflection are walk samples (a walk that leaves on the other side ends that branch: its light is counted by
//   the estimates), the coat's reflection f_coat,r(wo, wi) and its transmission along the base's sampled
//   direction are one-walk estimates (eval_walk), and the power heuristic weighs the two ways out with the
//   single-scattering pdf standing in for the walk's (unknown) one: any weights that sum to 1 keep it unbiased
//   (where both densities are 0 the next-event path takes all). coat_scattering = single: one scattering per
//   crossing (Walter et al. 2007), which loses energy at rough coats (docs/models/layering.md).
//
// eval is an unbiased estimate, the mean of walk_samples walks, and a deterministic function of (wi, wo, seed):
// its random numbers come from PCG32 seeded by a hash of the six coordinates and the seed, so any thread or
// shard layout gives the same bits. eval_estimate gives the mean with its standard error. It is reciprocal in
// expectation only (is_reciprocal() is false; brdf/layered_test.cpp measures the defect).
// sample draws from a fixed mixture with an exact pdf: the coat's reflection (visible normals), for glossy
// bases a GGX lobe about the mirror direction at sqrt(alpha_coat^2 + (eta alpha_base)^2), and the cosine lobe;
// the weight is eval * cos / pdf, so it is unbiased whatever the mixture.
#pragma once

#include <cstdint>
#include <memory>

#include "shadelab/brdf/brdf.h"
#include "shadelab/brdf/rough_dielectric.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {

class LayeredSlab final : public Brdf {
 public:
  enum class Base { lambert, conductor, ggx };
  struct Params {
    double coat_ior = 1.5;
    double coat_alpha = 0.01;
    Rgb coat_color{1.0, 1.0, 1.0};
    double coat_thickness = 1.0;
    RoughDielectric::Scattering coat_scattering = RoughDielectric::Scattering::multiple;
    Base base = Base::lambert;
    Rgb base_color{0.8, 0.8, 0.8};
    double base_alpha = 0.09;
    Rgb base_f82{1.0, 1.0, 1.0};
    double base_f0 = 0.04;
    int walk_samples = 4;
    std::uint64_t seed = 0;
  };
  static constexpr int max_depth = 256;

  explicit LayeredSlab(const Params& p);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override;
  bool is_reciprocal() const override { return false; }
  bool is_stochastic() const override { return true; }
  std::optional<Rgb> eval_standard_error(const Vec3& wi, const Vec3& wo) const override;
  bool pdf_smooth_below_horizon() const override { return false; }

  struct Estimate {
    Rgb mean;
    Rgb standard_error;  // of the mean, from the walks' sample variance
  };
  // f(wi, wo) from `walks` independent walks of random stream `stream`, with its standard error.
  Estimate eval_estimate(const Vec3& wi, const Vec3& wo, int walks, std::uint64_t stream) const;

  const Params& params() const { return m_p; }
  Rgb transmittance(const Vec3& w) const;  // through the slab along w

 private:
  struct Mixture {
    double coat;
    double lobe;  // the glossy-base lobe; 0 for lambert
  };
  Mixture mixture(const Vec3& wo) const;
  double lobe_alpha() const;
  template <typename Rng>
  Rgb walk(const Vec3& wi, const Vec3& wo, Rng& rng) const;
  // coat_scattering = multiple: one walk's estimate of the whole f(wi, wo), the coat's reflection included.
  Rgb walk_multiple(const Vec3& wi, const Vec3& wo, Pcg32& rng) const;
  // The mean of `walks` walks from rng, plus the coat's reflection; with the walks' standard error.
  Estimate estimate(const Vec3& wi, const Vec3& wo, int walks, Pcg32& rng) const;

  Params m_p;
  RoughDielectric m_coat;
  std::shared_ptr<const Brdf> m_base;
};

}  // namespace shadelab
