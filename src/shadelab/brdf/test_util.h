// Helpers shared by the BRDF tests (test code only).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"

namespace shadelab::testing {

inline BrdfPtr make(const std::string& model, const ParamAssignments& params = {}) {
  auto r = make_brdf(model, params);
  if (!r) ADD_FAILURE() << r.error().message;
  return r ? std::move(r).value() : nullptr;
}

inline Vec3 dir(double theta_deg, double phi_deg) {
  const double t = deg_to_rad(theta_deg);
  const double p = deg_to_rad(phi_deg);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

inline void expect_rgb_near(const Rgb& a, const Rgb& b, double rel) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(a[c], b[c], rel * std::max(1e-300, std::abs(b[c]))) << "channel " << c;
  }
}

}  // namespace shadelab::testing
