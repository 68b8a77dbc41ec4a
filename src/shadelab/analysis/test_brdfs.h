// Test-only BRDFs for the analysis tests: deliberately broken or hand-made models that the checks must catch.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab::testing {

inline BrdfPtr make(const std::string& model, const ParamAssignments& params = {}) {
  auto r = make_brdf(model, params);
  if (!r) {
    ADD_FAILURE() << r.error().message;
    return nullptr;
  }
  return std::move(r).value();
}

inline Vec3 view(double theta_deg) {
  const double t = deg_to_rad(theta_deg);
  return {std::sin(t), 0.0, std::cos(t)};
}

// Wraps a model and breaks one thing about it.
class Broken final : public Brdf {
 public:
  enum class Fault {
    none,
    uniform_pdf,          // pdf() is the uniform hemisphere density, whatever the sampler does
    scaled_pdf,           // pdf() is 0.9 times the true one (integrates to 0.9)
    wrong_sample_pdf,     // sample().pdf is 1.5 times pdf()
    wrong_weight,         // sample().weight is 1.01 times f cos / pdf
    weight_below_horizon, // samples reflected below the horizon keep a non-zero weight
    samples_below,        // every 10th sampled direction is mirrored below the horizon, where pdf() is 0
    claims_non_reciprocal,
    non_reciprocal,       // f(wi, wo) scaled by (1 + wi.z), which breaks symmetry
    resampled,            // draws wi with u.x squared but reports pdf() and f cos / pdf for it: consistent
                          // per sample (as LobeMixtureBrdf is by construction), biased on average
  };
  Broken(BrdfPtr inner, Fault fault) : m_inner(std::move(inner)), m_fault(fault) {}

  Rgb eval(const Vec3& wi, const Vec3& wo) const override {
    const Rgb f = m_inner->eval(wi, wo);
    return m_fault == Fault::non_reciprocal ? f * (1.0 + wi.z) : f;
  }
  double pdf(const Vec3& wi, const Vec3& wo) const override {
    switch (m_fault) {
      case Fault::uniform_pdf: return wo.z > 0.0 ? uniform_hemisphere_pdf(wi) : 0.0;
      case Fault::scaled_pdf: return 0.9 * m_inner->pdf(wi, wo);
      default: return m_inner->pdf(wi, wo);
    }
  }
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override {
    BrdfSample s = m_inner->sample(wo, u, u_lobe);
    switch (m_fault) {
      case Fault::wrong_sample_pdf: s.pdf *= 1.5; break;
      case Fault::wrong_weight: s.weight = s.weight * 1.01; break;
      case Fault::weight_below_horizon:
        if (s.wi.z <= 0.0) s.weight = Rgb::gray(0.5);
        break;
      case Fault::samples_below:
        if (static_cast<int>(u.x * 1e6) % 10 == 0) s.wi.z = -s.wi.z;
        break;
      case Fault::resampled:
        s = m_inner->sample(wo, {u.x * u.x, u.y}, u_lobe);
        s.pdf = m_inner->pdf(s.wi, wo);
        s.weight = s.pdf > 0.0 && s.wi.z > 0.0 ? m_inner->eval(s.wi, wo) * (s.wi.z / s.pdf) : Rgb{};
        break;
      default: break;
    }
    return s;
  }
  bool is_reciprocal() const override {
    return m_fault == Fault::claims_non_reciprocal || m_fault == Fault::non_reciprocal ? false
                                                                                       : m_inner->is_reciprocal();
  }

 private:
  BrdfPtr m_inner;
  Fault m_fault;
};

// Lambertian in wi with an albedo that depends on the view angle: rho(theta_o) = peak - k (theta_o - theta_peak)^2.
// Not reciprocal; its albedo has a known interior maximum.
class ViewDependentLambert final : public Brdf {
 public:
  ViewDependentLambert(double peak, double theta_peak_deg, double k) : m_peak(peak), m_theta(deg_to_rad(theta_peak_deg)), m_k(k) {}
  double albedo(double theta_o) const { return m_peak - m_k * (theta_o - m_theta) * (theta_o - m_theta); }
  Rgb eval(const Vec3& wi, const Vec3& wo) const override {
    if (wi.z <= 0.0 || wo.z <= 0.0) return {};
    return Rgb::gray(albedo(std::acos(std::min(1.0, wo.z))) * inv_pi);
  }
  double pdf(const Vec3& wi, const Vec3& wo) const override { return wo.z > 0.0 ? cosine_hemisphere_pdf(wi) : 0.0; }
  BrdfSample sample(const Vec3& wo, Vec2 u, double) const override {
    BrdfSample s;
    if (wo.z <= 0.0) return s;
    s.wi = sample_cosine_hemisphere(u);
    s.pdf = cosine_hemisphere_pdf(s.wi);
    if (s.pdf > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
    return s;
  }
  bool is_reciprocal() const override { return false; }

 private:
  double m_peak;
  double m_theta;
  double m_k;
};

inline BrdfPtr broken(const std::string& model, const ParamAssignments& params, Broken::Fault fault) {
  return BrdfPtr(new Broken(make(model, params), fault));
}

}  // namespace shadelab::testing
