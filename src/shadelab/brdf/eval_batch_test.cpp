// Brdf::eval_batch and eval_batch_checked against per-pair eval, bit for bit, for every registered model
// (defaults and one non-default parameter set per model where its kernel has branches), on directions over
// the whole sphere, on and below the horizon, at grazing angles and at the mirror direction; the checked
// batch stops at the first direction that is not unit length; is_unit_direction's 4-ulp threshold.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/brdf/test_measured_file.h"
#include "shadelab/brdf/test_util.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {
namespace {

// Parameter sets beyond the defaults: the kernels' other branches (choices) and non-grey colours.
const std::map<std::string, std::vector<ParamAssignments>>& extra_params() {
  static const std::map<std::string, std::vector<ParamAssignments>> sets = {
      {"phong", {{{"n", "7"}, {"kd", "0.1,0.2,0.3"}}}},
      {"blinn-phong", {{{"n", "300"}, {"ks", "0.9,0.5,0.1"}}}},
      {"cook-torrance",
       {{{"d", "blinn-phong"}, {"g", "kelemen"}, {"f", "conductor"}, {"ior", "0.2,0.9,1.1"}, {"k", "3,2.5,2"}},
        {{"g", "cook-torrance"}, {"f", "dielectric"}, {"form", "1981"}, {"m", "0.05"}},
        {{"f", "none"}, {"m", "0.8"}}}},
      {"ward-anisotropic", {{{"alpha_x", "0.3"}, {"alpha_y", "0.05"}}}},
      {"wrapped-diffuse", {{{"w", "0.5"}}}},
  };
  return sets;
}

// Directions the loop may treat differently from one call: uniform over the sphere (half below the
// horizon), exactly on the horizon, near grazing, the normal, and mirror pairs.
void make_pairs(std::vector<Vec3>& wi, std::vector<Vec3>& wo) {
  Pcg32 rng(99);
  for (int i = 0; i < 997; ++i) {  // not a multiple of any vector width
    wi.push_back(sample_uniform_sphere({rng.next_double(), rng.next_double()}));
    wo.push_back(sample_uniform_sphere({rng.next_double(), rng.next_double()}));
  }
  for (double theta : {0.0, 30.0, 89.0, 89.999, 90.0, 120.0}) {
    for (double phi : {0.0, 45.0, 200.0}) {
      wi.push_back(testing::dir(theta, phi));
      wo.push_back(testing::dir(theta, phi + 180.0));  // the mirror direction
      wi.push_back(testing::dir(theta, phi));
      wo.push_back(testing::dir(10.0, phi + 90.0));
    }
  }
}

void expect_batch_equals_per_pair(const std::string& label, const Brdf& f) {
  std::vector<Vec3> wi;
  std::vector<Vec3> wo;
  make_pairs(wi, wo);
  const std::size_t n = wi.size();
  std::vector<Rgb> batch(n, Rgb{-1.0, -1.0, -1.0});
  f.eval_batch(wi.data(), wo.data(), batch.data(), n);
  std::size_t nonzero = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Rgb one = f.eval(wi[i], wo[i]);
    ASSERT_EQ(std::memcmp(&one, &batch[i], sizeof(Rgb)), 0)
        << label << " pair " << i << ": eval (" << one.r << ", " << one.g << ", " << one.b << "), eval_batch ("
        << batch[i].r << ", " << batch[i].g << ", " << batch[i].b << ")";
    nonzero += one.is_black() ? 0 : 1;
  }
  EXPECT_GT(nonzero, n / 5) << label << ": too few pairs above the horizon to mean anything";
  // A batch starting part-way and a batch of one give the same values as their pairs.
  std::vector<Rgb> part(n - 3);
  f.eval_batch(wi.data() + 3, wo.data() + 3, part.data(), n - 3);
  EXPECT_EQ(std::memcmp(part.data(), batch.data() + 3, part.size() * sizeof(Rgb)), 0) << label;
  f.eval_batch(wi.data(), wo.data(), part.data(), 0);  // n = 0 writes nothing
  EXPECT_EQ(std::memcmp(part.data(), batch.data() + 3, sizeof(Rgb)), 0) << label;

  // The checked batch on unit directions (each divided by its length and kept where the test accepts it):
  // the same bits; then with a direction scaled by 2 at pair 500 (wi) or made NaN at pair 700 (wo), it
  // stops there, leaving the rest of out as it was.
  std::vector<Vec3> ui;
  std::vector<Vec3> uo;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = wi[i] / std::sqrt(dot(wi[i], wi[i]));
    const Vec3 b = wo[i] / std::sqrt(dot(wo[i], wo[i]));
    if (is_unit_direction(a) && is_unit_direction(b)) {
      ui.push_back(a);
      uo.push_back(b);
    }
  }
  const std::size_t u = ui.size();
  ASSERT_GT(u, 900u) << label;
  std::vector<Rgb> checked(u, Rgb{-1.0, -1.0, -1.0});
  ASSERT_EQ(f.eval_batch_checked(ui.data(), uo.data(), checked.data(), u), u) << label;
  for (std::size_t i = 0; i < u; ++i) {
    const Rgb one = f.eval(ui[i], uo[i]);
    ASSERT_EQ(std::memcmp(&one, &checked[i], sizeof(Rgb)), 0) << label << " checked pair " << i;
  }
  ui[500] = ui[500] * 2.0;
  uo[700].y = std::numeric_limits<double>::quiet_NaN();
  std::vector<Rgb> stopped(u, Rgb{-1.0, -1.0, -1.0});
  EXPECT_EQ(f.eval_batch_checked(ui.data(), uo.data(), stopped.data(), u), 500u) << label;
  EXPECT_EQ(std::memcmp(stopped.data(), checked.data(), 500 * sizeof(Rgb)), 0) << label;
  EXPECT_EQ(stopped[500].r, -1.0) << label << ": the pair it stopped at was written";
  EXPECT_EQ(f.eval_batch_checked(ui.data() + 501, uo.data() + 501, stopped.data(), u - 501), 199u) << label;
}

TEST(EvalBatch, EqualsPerPairEvalBitForBitForEveryRegisteredModel) {
  std::size_t models = 0;
  for (const ModelInfo& m : brdf_models()) {
    std::vector<ParamAssignments> sets = {testing::registry_params(m)};  // measured: this binary's test file
    if (auto it = extra_params().find(m.name); it != extra_params().end()) {
      sets.insert(sets.end(), it->second.begin(), it->second.end());
    }
    for (const auto& params : sets) {
      BrdfPtr f = testing::make(m.name, params);
      ASSERT_NE(f, nullptr) << m.name;
      std::string label = m.name;
      for (const auto& [k, v] : params) label += " " + k + "=" + v;
      expect_batch_equals_per_pair(label, *f);
    }
    ++models;
  }
  EXPECT_GE(models, 11u);  // the registry's eleven models at the time of writing
}

// The threshold: a squared length within 4 ulp of 1 is a unit direction; zero, NaN and infinity are not.
TEST(EvalBatch, UnitDirectionTestIsFourUlpOfTheSquaredLength) {
  const double eps = std::numeric_limits<double>::epsilon();
  EXPECT_TRUE(is_unit_direction({0.0, 0.0, 1.0}));
  EXPECT_TRUE(is_unit_direction({0.0, 0.0, 1.0 + eps}));          // |v|^2 = 1 + 2 eps
  EXPECT_TRUE(is_unit_direction({0.0, 0.0, 1.0 - eps}));          // 1 - 2 eps
  EXPECT_FALSE(is_unit_direction({0.0, 0.0, 1.0 + 3.0 * eps}));   // 1 + 6 eps
  EXPECT_FALSE(is_unit_direction({0.0, 0.0, 1.0 - 3.0 * eps}));
  EXPECT_TRUE(is_unit_direction({0.6, 0.0, 0.8}));
  EXPECT_FALSE(is_unit_direction({0.6, 0.1, 0.8}));
  EXPECT_FALSE(is_unit_direction({0.0, 0.0, 0.0}));
  EXPECT_FALSE(is_unit_direction({std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0}));
  EXPECT_FALSE(is_unit_direction({std::numeric_limits<double>::infinity(), 0.0, 0.0}));
}

// A Brdf without its own loop (a test double) gets the default: eval per pair, the same check.
TEST(EvalBatch, DefaultLoopForModelsWithoutTheirOwn) {
  class Dot final : public Brdf {
   public:
    Rgb eval(const Vec3& wi, const Vec3& wo) const override { return Rgb::gray(dot(wi, wo)); }
    double pdf(const Vec3&, const Vec3&) const override { return 0.0; }
    BrdfSample sample(const Vec3&, Vec2, double) const override { return {}; }
  } f;
  const std::vector<Vec3> wi = {{0.0, 0.0, 1.0}, {0.6, 0.0, 0.8}, {0.0, 0.0, 2.0}};
  const std::vector<Vec3> wo = {{0.0, 0.0, 1.0}, {0.0, 0.6, 0.8}, {0.0, 0.0, 1.0}};
  std::vector<Rgb> out(3, Rgb::gray(-1.0));
  f.eval_batch(wi.data(), wo.data(), out.data(), 3);
  EXPECT_EQ(out[0].g, 1.0);
  EXPECT_EQ(out[1].g, 0.8 * 0.8);
  EXPECT_EQ(out[2].g, 2.0);
  out.assign(3, Rgb::gray(-1.0));
  EXPECT_EQ(f.eval_batch_checked(wi.data(), wo.data(), out.data(), 3), 2u);
  EXPECT_EQ(out[1].b, 0.8 * 0.8);
  EXPECT_EQ(out[2].b, -1.0);
}

}  // namespace
}  // namespace shadelab
