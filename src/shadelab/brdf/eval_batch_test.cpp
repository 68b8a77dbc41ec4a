// Brdf::eval_batch against per-pair eval, bit for bit, for every registered model (defaults and one
// non-default parameter set per model where its kernel has branches), on directions over the whole sphere,
// on and below the horizon, at grazing angles and at the mirror direction.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "shadelab/brdf/registry.h"
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
}

TEST(EvalBatch, EqualsPerPairEvalBitForBitForEveryRegisteredModel) {
  std::size_t models = 0;
  for (const ModelInfo& m : brdf_models()) {
    std::vector<ParamAssignments> sets = {{}};
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

}  // namespace
}  // namespace shadelab
