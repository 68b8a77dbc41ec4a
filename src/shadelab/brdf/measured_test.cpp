// The measured model (brdf/measured.h) on tables the virtual gonioreflectometer wrote: a constant stays constant
// through the interpolation and its edge rules everywhere above the horizon (the renormalization over missing
// neighbours included); at bin centres it is the table; it is reciprocal; between centres it is within a stated
// interpolation error of the model that was measured.
#include "shadelab/brdf/measured.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {
namespace {

std::shared_ptr<const MerlTable> measured(const char* model, const ParamAssignments& p) {
  const auto f = make_brdf(model, p);
  EXPECT_TRUE(f.has_value());
  return std::make_shared<const MerlTable>(measure_merl(**f));
}

// Pairs over the whole upper hemisphere, grazing included (z down to 1e-6).
std::vector<std::pair<Vec3, Vec3>> pairs(int n) {
  Pcg32 rng(11);
  std::vector<std::pair<Vec3, Vec3>> v;
  for (int k = 0; k < n; ++k) {
    Vec3 a = sample_uniform_hemisphere({rng.next_double(), rng.next_double()});
    Vec3 b = sample_uniform_hemisphere({rng.next_double(), rng.next_double()});
    if (k % 10 == 0) a = normalize(Vec3{a.x, a.y, 1e-6});
    if (k % 10 == 1) b = normalize(Vec3{b.x, b.y, 1e-6});
    v.emplace_back(a, b);
  }
  return v;
}

TEST(Measured, AConstantTableIsConstantEverywhereAboveTheHorizon) {
  const MeasuredBrdf m(measured("lambert", {{"kd", "0.5,0.25,0.125"}}));
  for (const auto& [wi, wo] : pairs(20000)) {
    const Rgb f = m.eval(wi, wo);
    EXPECT_NEAR(f.r, 0.5 * inv_pi, 1e-15);
    EXPECT_NEAR(f.g, 0.25 * inv_pi, 1e-15);
    EXPECT_NEAR(f.b, 0.125 * inv_pi, 1e-15);
  }
  EXPECT_EQ(m.eval({0.0, 0.6, -0.8}, {0.0, 0.0, 1.0}).r, 0.0);
  EXPECT_EQ(m.eval({0.0, 0.0, 1.0}, {0.6, 0.0, 0.0 * 0.8}).r, 0.0);
}

TEST(Measured, AtBinCentresItIsTheTableAndItIsReciprocal) {
  const auto table = measured("ggx", {{"roughness", "0.4"}, {"kd", "0.3"}, {"f0", "0.9,0.6,0.3"}});
  const MeasuredBrdf m(table);
  double worst = 0.0;
  for (int i : {0, 5, 30, 60, 89}) {
    for (int j : {0, 20, 45, 70}) {
      for (int k : {0, 1, 90, 179}) {
        const auto [wi, wo] = half_diff_directions(merl_bin_centre(i, j, k));
        if (!(wi.z > 1e-3 && wo.z > 1e-3)) continue;
        const std::size_t idx = MerlTable::index(i, j, k);
        const Rgb f = m.eval(normalize(wi), normalize(wo));
        worst = std::max(worst, std::abs(f.g - table->value(1, idx)) / table->value(1, idx));
      }
    }
  }
  EXPECT_LE(worst, 1e-9);
  double defect = 0.0;
  for (const auto& [wi, wo] : pairs(5000)) {
    const Rgb a = m.eval(wi, wo), b = m.eval(wo, wi);
    if (a.g > 0.0) defect = std::max(defect, std::abs(a.g - b.g) / a.g);
  }
  EXPECT_LE(defect, 1e-9);
  std::printf("[ measured ] at bin centres max relative difference %.3g; reciprocity defect %.3g\n", worst, defect);
}

// The interpolation error against the measured model itself at random pairs (theta up to 80 degrees): the
// relative error's median and 99th percentile are stated in docs/models/measured.md; held here with margin.
TEST(Measured, BetweenCentresItIsWithinTheInterpolationErrorOfTheModel) {
  const auto ggx = make_brdf("ggx", {{"roughness", "0.5"}, {"kd", "0.2"}, {"f0", "0.04"}});
  ASSERT_TRUE(ggx.has_value());
  const MeasuredBrdf m(std::make_shared<const MerlTable>(measure_merl(**ggx)));
  std::vector<double> rel;
  for (const auto& [wi, wo] : pairs(20000)) {
    if (wi.z < std::cos(deg_to_rad(80.0)) || wo.z < std::cos(deg_to_rad(80.0))) continue;
    const double e = (*ggx)->eval(wi, wo).g;
    rel.push_back(std::abs(m.eval(wi, wo).g - e) / e);
  }
  std::sort(rel.begin(), rel.end());
  const double median = rel[rel.size() / 2], p99 = rel[rel.size() * 99 / 100], max = rel.back();
  std::printf("[ measured ] ggx r 0.5 between centres: relative error median %.3g, 99th percentile %.3g, max %.3g\n", median,
              p99, max);
  EXPECT_LE(median, 2e-3);
  EXPECT_LE(p99, 2e-2);
}

}  // namespace
}  // namespace shadelab
