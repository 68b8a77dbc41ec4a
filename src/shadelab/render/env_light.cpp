#include "shadelab/render/env_light.h"

#include <algorithm>
#include <cmath>

#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

namespace {

// The built-in sky's gradient: zenith -> horizon with a smooth blend, ground below.
Rgb sky_gradient(const SkyModel& s, const Vec3& w) {
  if (w.y < 0.0) return s.ground;
  const double h = (1.0 - w.y) * (1.0 - w.y);
  const double t = h * h;  // (1 - y)^4: horizon brightening toward the horizon
  return s.zenith * (1.0 - t) + s.horizon * t;
}

}  // namespace

EnvironmentLight::EnvironmentLight(const Scene& scene) : m_scene(scene) {
  const Environment& env = scene.environment;
  bool hemi = false;
  for (const auto& l : scene.lights) hemi = hemi || std::holds_alternative<HemisphereLight>(l);
  m_active = env.kind != Environment::Kind::none || hemi;
  if (!m_active) return;
  m_rotation = Mat3::rotation({0.0, 1.0, 0.0}, deg_to_rad(env.rotation_deg));
  m_inverse_rotation = m_rotation.transposed();

  if (env.kind == Environment::Kind::sky) {
    const double alpha = deg_to_rad(env.sky.sun_angular_radius_deg);
    m_sun_cos = std::cos(alpha);
    const double s = std::sin(alpha);
    // A uniform disk of radiance L subtending alpha gives E_perp = pi L sin^2(alpha) (zoo article comments).
    m_sun_radiance = env.sky.sun_irradiance / (pi * s * s);
    m_has_sun = env.sky.sun_irradiance.max_component() > 0.0;
  }

  // The proposal: the image itself, or the analytic radiance baked at 256 x 128 (in map space).
  Image proposal;
  if (env.kind == Environment::Kind::image) {
    proposal = env.latlong;
  } else {
    proposal = Image(256, 128);
    for (int y = 0; y < proposal.height; ++y)
      for (int x = 0; x < proposal.width; ++x) {
        const Vec3 w_map = latlong_direction((x + 0.5) / proposal.width, (y + 0.5) / proposal.height);
        proposal.set(x, y, base_radiance(m_rotation.apply(w_map)));
      }
  }
  m_width = proposal.width;
  m_height = proposal.height;
  // A constant proposal (a uniform environment) is sampled uniformly over the sphere: the same density the
  // table would give, without the table look-ups.
  m_constant = true;
  for (std::size_t i = 3; i < proposal.data.size(); ++i) m_constant = m_constant && proposal.data[i] == proposal.data[i % 3];
  // Each cell's weight is the mean over the cell of what the radiance lookup returns (bilinear between texel
  // centres, sample_latlong: x wraps, y clamps), times sin(theta). The mean of a bilinear interpolant over a cell is
  // the separable filter (1, 6, 1) / 8 of the texel values in each axis (each half-cell averages a linear ramp:
  // (c_-1 + 3 c_0) / 4 and (3 c_0 + c_+1) / 4). A table of the texels alone gave the half-texel rim that the
  // lookup spreads around a one-texel sun only the floor's probability: fireflies (issue 42).
  std::vector<double> lum(static_cast<std::size_t>(m_width) * static_cast<std::size_t>(m_height));
  for (int y = 0; y < m_height; ++y)
    for (int x = 0; x < m_width; ++x)
      lum[static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) + static_cast<std::size_t>(x)] =
          std::max(0.0, luminance(proposal.at(x, y)));
  const auto texel = [&](int x, int y) {
    x = ((x % m_width) + m_width) % m_width;
    y = std::clamp(y, 0, m_height - 1);
    return lum[static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) + static_cast<std::size_t>(x)];
  };
  static constexpr double k[3] = {1.0 / 8.0, 6.0 / 8.0, 1.0 / 8.0};
  std::vector<double> weights(lum.size());
  double mean = 0.0;
  for (int y = 0; y < m_height; ++y) {
    const double sin_theta = std::sin(pi * (y + 0.5) / m_height);
    for (int x = 0; x < m_width; ++x) {
      double v = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) v += k[dy + 1] * k[dx + 1] * texel(x + dx, y + dy);
      v *= sin_theta;
      weights[static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) + static_cast<std::size_t>(x)] = v;
      mean += v;
    }
  }
  mean /= static_cast<double>(weights.size());
  // Floor: every texel keeps some probability, so directions the proposal underrates are still drawn.
  for (std::size_t y = 0; y < static_cast<std::size_t>(m_height); ++y) {
    const double sin_theta = std::sin(pi * (static_cast<double>(y) + 0.5) / m_height);
    for (std::size_t x = 0; x < static_cast<std::size_t>(m_width); ++x) {
      weights[y * static_cast<std::size_t>(m_width) + x] += 1e-3 * std::max(mean, 1e-12) * sin_theta;
    }
  }
  m_distribution = Distribution2D::create(weights, static_cast<std::size_t>(m_width), static_cast<std::size_t>(m_height)).value();

  if (m_has_sun) {
    // Sun power E_perp against the sky's (pi x mean luminance over the sphere, roughly): pick the sun that often.
    const double sun = luminance(env.sky.sun_irradiance);
    const double sky = pi * std::max(1e-12, luminance(env.sky.zenith) + luminance(env.sky.horizon)) * 0.5;
    m_sun_probability = std::clamp(sun / (sun + sky), 0.1, 0.9);
  }
}

Rgb EnvironmentLight::base_radiance(const Vec3& w) const {
  const Environment& env = m_scene.environment;
  Rgb l;
  switch (env.kind) {
    case Environment::Kind::none: break;
    case Environment::Kind::uniform: l = env.uniform; break;
    case Environment::Kind::image: l = sample_latlong(env.latlong, m_inverse_rotation.apply(w)) * env.scale; break;
    case Environment::Kind::sky: l = sky_gradient(env.sky, w); break;
  }
  for (const auto& light : m_scene.lights) {
    if (const auto* h = std::get_if<HemisphereLight>(&light)) l += dot(w, h->up) > 0.0 ? h->sky : h->ground;
  }
  return l;
}

Rgb EnvironmentLight::radiance(const Vec3& w) const {
  if (!m_active) return {};
  Rgb l = base_radiance(w);
  if (m_has_sun && dot(w, m_scene.environment.sky.sun_direction) >= m_sun_cos) l += m_sun_radiance;
  return l;
}

double EnvironmentLight::pdf(const Vec3& w) const {
  if (!m_active) return 0.0;
  if (m_constant) return m_has_sun ? mix_sun(w, inv_four_pi) : inv_four_pi;
  const Vec3 w_map = m_inverse_rotation.apply(w);
  const Vec2 uv = latlong_uv(w_map);
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - w_map.y * w_map.y));
  double p = 0.0;
  if (sin_theta > 0.0) {
    const double u = uv.x >= 1.0 ? 0.0 : uv.x;
    p = m_distribution->pdf({u, std::min(uv.y, std::nextafter(1.0, 0.0))}) / (2.0 * pi * pi * sin_theta);
  }
  return m_has_sun ? mix_sun(w, p) : p;
}

double EnvironmentLight::mix_sun(const Vec3& w, double p_map) const {
  return (1.0 - m_sun_probability) * p_map +
         m_sun_probability * (dot(w, m_scene.environment.sky.sun_direction) >= m_sun_cos ? 1.0 / (two_pi * (1.0 - m_sun_cos)) : 0.0);
}

EnvironmentLight::Sample EnvironmentLight::sample(Vec2 u, double u_select) const {
  Sample s;
  if (!m_active) return s;
  if (m_has_sun && u_select < m_sun_probability) {
    const Frame f = Frame::from_normal(m_scene.environment.sky.sun_direction);
    s.wi = f.to_world(sample_spherical_cap(u, m_sun_cos));
  } else if (m_constant) {
    s.wi = sample_uniform_sphere(u);
  } else {
    const auto d = m_distribution->sample(u);
    s.wi = m_rotation.apply(latlong_direction(d.p.x, d.p.y));
  }
  s.pdf = pdf(s.wi);
  s.radiance = radiance(s.wi);
  return s;
}

}  // namespace shadelab
