// shadelab lobe mixture: the common shape f = diffuse + specular(wi, wo) of most models,
// with one-sample MIS between a cosine-weighted diffuse lobe and the model's own specular sampler.
// eval (the whole f, diffuse included) is each model's kernel (src/shadelab/kernels/*.sl); this class
// supplies the sampling density, the sampler and the diffuse albedo.
//
// The sampling density is the mixture p(wi) = p_d cos(theta_i)/pi + (1 - p_d) p_s(wi), so the weight
// f cos / p is an unbiased one-sample estimator whichever lobe was picked (Veach 1997, section 9.2.4).
#pragma once

#include "shadelab/brdf/brdf.h"
#include "shadelab/core/constants.h"

namespace shadelab {

class LobeMixtureBrdf : public Brdf {
 public:
  double pdf(const Vec3& wi, const Vec3& wo) const final;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const final;
  Rgb diffuse_albedo() const final { return m_diffuse * pi; }  // pi x the constant diffuse f

 protected:
  // diffuse: the constant diffuse BRDF value (kd/pi for normalized models). diffuse_probability: p_d.
  LobeMixtureBrdf(Rgb diffuse, double diffuse_probability) : m_diffuse(diffuse), m_p_diffuse(diffuse_probability) {}

  // Density of specular_sample over the sphere (wo above the horizon).
  virtual double specular_pdf(const Vec3& wi, const Vec3& wo) const = 0;
  // u picks the direction; u_lobe in [0, 1) is left for models with several specular lobes.
  virtual Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const = 0;

  // p_d from the two lobes' albedo estimates: a_d / (a_d + a_s), 1 when both are zero.
  static double lobe_probability(double diffuse_albedo, double specular_albedo);

  Rgb m_diffuse;
  double m_p_diffuse;
};

}  // namespace shadelab
