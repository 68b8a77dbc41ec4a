// The shininess conversion: the published mappings against hand-computed values, and the best fit no worse than
// any of them (the optimizer finds a minimum they do not beat).
#include "shadelab/fit/shininess.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadelab {
namespace {

std::optional<double> mapping(double n, const std::string& name) {
  for (const auto& [k, v] : published_shininess_mappings(n)) {
    if (k == name) return v;
  }
  return std::nullopt;
}

TEST(Shininess, PublishedMappingsAtHandComputedPoints) {
  EXPECT_NEAR(*mapping(98.0, "walter"), 0.1414213562373095, 1e-15);            // sqrt(2/100)
  EXPECT_NEAR(*mapping(8.0, "godot"), std::pow(1.0 - std::sqrt(2.0 / 3.0), 2), 1e-15);  // log2 8 = 3: 1 - sqrt(6/9)
  EXPECT_FALSE(mapping(600.0, "godot").has_value());                           // sqrt of a negative
  EXPECT_NEAR(*mapping(512.0, "godot"), 1.0, 1e-15);                           // more shininess, rougher: its sign
  EXPECT_NEAR(*mapping(std::sqrt(8192.0), "cod"), 0.25, 1e-12);                // g = 1/2, roughness 1/2
  EXPECT_NEAR(*mapping(1.0, "babylon"), std::pow(0.1 + 0.9 * std::pow(1.0 - std::cbrt(1.0 / 1300.0), 3), 2), 1e-15);
  EXPECT_EQ(*mapping(5000.0, "babylon"), *mapping(1024.0, "babylon"));         // clamped at 1024
}

TEST(Shininess, BestFitBeatsEveryPublishedMapping) {
  FitGridOptions g;
  g.theta_d_stride = 6;
  g.phi_d_stride = 12;
  double last_alpha = 2.0;
  for (double n : {10.0, 100.0, 1000.0}) {
    const auto c = convert_shininess("blinn-phong", "ggx", n, FitMetric::cosine_l2, g);
    ASSERT_TRUE(c) << c.error().message;
    EXPECT_GT(c->residual, 0.0);
    EXPECT_LT(c->alpha, last_alpha) << n;  // sharper lobes, smaller alpha
    last_alpha = c->alpha;
    for (const auto& m : c->mappings) {
      if (m.alpha) {
        EXPECT_GE(m.excess, -1e-9) << m.name << " at n = " << n;
      }
    }
  }
  const auto b = convert_shininess("phong", "beckmann", 50.0, FitMetric::log, g);
  ASSERT_TRUE(b) << b.error().message;
  EXPECT_GT(b->alpha, 0.05);
  EXPECT_LT(b->alpha, 0.5);
  // Within one microfacet model (the same masking-shadowing), Blinn-Phong's D against Beckmann's: Walter et al.'s
  // mapping comes from matching the two D, so the fit lands near it for a sharp lobe.
  const auto w = convert_shininess("blinn-phong-microfacet", "beckmann", 1000.0, FitMetric::cosine_l2, g);
  ASSERT_TRUE(w) << w.error().message;
  EXPECT_NEAR(w->alpha / *mapping(1000.0, "walter"), 1.0, 0.02) << w->alpha;
  EXPECT_LT(w->relative_residual, 0.05);
  EXPECT_FALSE(convert_shininess("ward", "ggx", 50.0));
  EXPECT_FALSE(convert_shininess("phong", "ward", 50.0));
  EXPECT_FALSE(convert_shininess("phong", "ggx", 0.5));
}

}  // namespace
}  // namespace shadelab
