// shadelab environment light: the radiance arriving from infinitely far away, as a function of direction,
// and an importance sampler for it.
//
// A constant proposal (a uniform environment) is sampled uniformly over the sphere instead (pdf 1 / (4 pi)).
//
// radiance(w) = environment (lat-long image with rotation and scale, a uniform value, or the built-in sky's
// gradient) + the sun disk of the sky + every hemisphere light. The image is looked up bilinearly.
// Sampling is a mixture: the sun cap (uniform in its solid angle, probability proportional to its power),
// and a piecewise-constant 2D distribution over a lat-long proposal (the image's luminance, or the analytic
// radiance baked at 256 x 128), each cell weighted by the mean over it of the bilinear lookup (the texels filtered
// by (1, 6, 1) / 8 in each axis), times sin(theta), with a floor of 1e-3 of the mean so that every direction
// with radiance can be drawn. pdf(w) is the exact density of that mixture, so MIS weights and estimates are
// unbiased whatever the proposal (PBR 4th ed. 12.5 for the lat-long Jacobian: d omega = 2 pi^2 sin(theta) du dv).
#pragma once

#include <optional>

#include "shadelab/core/mat3.h"
#include "shadelab/sampling/distribution.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

class EnvironmentLight {
 public:
  // Empty (has_light() false) when the scene has neither an environment nor hemisphere lights.
  explicit EnvironmentLight(const Scene& scene);

  bool has_light() const { return m_active; }
  // The radiance is the same from every direction (a uniform environment, no sun, no hemisphere light): BRDF
  // sampling then draws f cos exactly as a cosine-weighted or VNDF sampler does, and light sampling only adds
  // variance (half its directions lie below the surface).
  bool is_constant() const { return m_active && m_constant && !m_has_sun; }
  Rgb radiance(const Vec3& w) const;
  // Everything but the sky's sun disk (a game renders the sun as a directional light).
  Rgb radiance_without_sun(const Vec3& w) const { return m_active ? base_radiance(w) : Rgb{}; }

  struct Sample {
    Vec3 wi;
    double pdf = 0.0;  // per unit solid angle
    Rgb radiance;
  };
  Sample sample(Vec2 u, double u_select) const;
  double pdf(const Vec3& w) const;

 private:
  Rgb base_radiance(const Vec3& w) const;  // without the sun
  double mix_sun(const Vec3& w, double p_map) const;  // the mixture density, given the map's
  const Scene& m_scene;
  bool m_active = false;
  Mat3 m_rotation;          // map -> world
  Mat3 m_inverse_rotation;  // world -> map
  std::optional<Distribution2D> m_distribution;
  int m_width = 0, m_height = 0;
  bool m_constant = false;  // the proposal is constant: uniform sphere sampling, pdf 1 / (4 pi)
  bool m_has_sun = false;
  double m_sun_cos = 1.0;        // cosine of the sun's angular radius
  Rgb m_sun_radiance;            // E / (pi sin^2(alpha)), uniform over the cap
  double m_sun_probability = 0;  // chance of sampling the sun cap
};

}  // namespace shadelab
