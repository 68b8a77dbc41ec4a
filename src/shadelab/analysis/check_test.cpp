#include "shadelab/analysis/check.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/analysis/test_brdfs.h"

namespace shadelab {
namespace {

using testing::Broken;
using testing::broken;

// A lighter chi-square than the CLI's default keeps the test quick; the items are the same.
CheckOptions quick() {
  CheckOptions o;
  o.chi_square.samples = 200'000;
  return o;
}

const CheckItem& item(const CheckReport& r, std::string_view name) {
  const CheckItem* i = r.find(name);
  EXPECT_NE(i, nullptr) << name;
  static const CheckItem missing{"missing", false, 0.0, 0.0, ""};
  return i ? *i : missing;
}

TEST(Check, LambertPassesEverything) {
  const auto r = check_brdf("lambert", {{"kd", "0.8"}}, quick());
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->passed());
  EXPECT_EQ(r->model, "lambert");
  EXPECT_EQ(r->params, "kd=0.8");
  const std::vector<std::string> names = {"normalization",      "energy",           "reciprocity",
                                          "pdf integral",       "sample weights",   "chi-square theta=0",
                                          "chi-square theta=30", "chi-square theta=60", "chi-square theta=80",
                                          "furnace",            "variance"};
  ASSERT_EQ(r->items.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(r->items[i].name, names[i]);
  // No normalization parameter: the albedo at normal incidence is reported, with no threshold.
  EXPECT_NEAR(item(*r, "normalization").figure, 0.8, 1e-12);
  EXPECT_TRUE(std::isnan(item(*r, "normalization").threshold));
  EXPECT_NEAR(item(*r, "energy").figure, 0.8, 1e-8);
  EXPECT_EQ(item(*r, "reciprocity").figure, 0.0);
  EXPECT_NEAR(item(*r, "chi-square theta=30").threshold, sidak_significance(0.01, 4), 1e-15);
}

// normalization = exact: the kd = 0 variant's albedo at normal incidence equals ks, per channel.
TEST(Check, NormalizationOfTheZooModels) {
  for (const char* model : {"phong", "phong-modified", "blinn-phong", "blinn-phong-modified"}) {
    const auto r = check_brdf(model, {{"kd", "0.3"}, {"ks", "0.6,0.4,0.2"}, {"n", "200"}}, quick());
    ASSERT_TRUE(r);
    const CheckItem& n = item(*r, "normalization");
    EXPECT_TRUE(n.passed) << model << ": " << n.detail;
    EXPECT_LE(n.figure, 1e-9) << model;
    EXPECT_EQ(n.threshold, 1e-9);
    EXPECT_TRUE(r->passed()) << model;
  }
  // The original Phong is non-reciprocal by design, and the check says so and passes.
  const auto phong = check_brdf("phong", {}, quick());
  const CheckItem& rec = item(*phong, "reciprocity");
  EXPECT_TRUE(rec.passed);
  EXPECT_GT(rec.figure, 1e-6);
  EXPECT_NE(rec.detail.find("non-reciprocal by design"), std::string::npos) << rec.detail;
}

TEST(Check, UpperBoundNormalizationFailsTheEnergyCheck) {
  // ks (n+4)/(8 pi) > ks times the exact factor: with kd + ks = 1 the albedo at normal incidence exceeds 1.
  const auto r = check_brdf("blinn-phong", {{"normalization", "upper"}, {"n", "10"}}, quick());
  ASSERT_TRUE(r);
  EXPECT_FALSE(r->passed());
  EXPECT_FALSE(item(*r, "energy").passed);
  EXPECT_GT(item(*r, "energy").figure, 1.01);
  EXPECT_TRUE(item(*r, "normalization").passed);  // reported only
  EXPECT_NE(item(*r, "normalization").detail.find("normalization=upper"), std::string::npos);
  EXPECT_TRUE(item(*r, "chi-square theta=60").passed);
}

TEST(Check, BrokenModelsFail) {
  const CheckReport wrong_pdf = check_brdf(*broken("phong", {{"n", "20"}}, Broken::Fault::scaled_pdf), quick());
  EXPECT_FALSE(wrong_pdf.passed());
  EXPECT_FALSE(item(wrong_pdf, "pdf integral").passed);
  EXPECT_NEAR(item(wrong_pdf, "pdf integral").figure, 0.1, 1e-8);
  EXPECT_FALSE(item(wrong_pdf, "chi-square theta=30").passed);
  EXPECT_TRUE(item(wrong_pdf, "reciprocity").passed);  // eval is untouched (and Phong is non-reciprocal)

  const CheckReport wrong_weight = check_brdf(*broken("lambert", {}, Broken::Fault::wrong_weight), quick());
  EXPECT_FALSE(item(wrong_weight, "sample weights").passed);
  EXPECT_TRUE(item(wrong_weight, "chi-square theta=0").passed);

  // A sampler that draws from another distribution but reports a consistent pdf and weight for each sample
  // (as LayeredBrdf does by construction): only the independent mean of the weights (and chi-square) see it.
  const CheckReport resampled = check_brdf(*broken("phong-modified", {{"n", "20"}, {"kd", "0"}}, Broken::Fault::resampled), quick());
  EXPECT_FALSE(item(resampled, "sample weights").passed) << item(resampled, "sample weights").detail;
  EXPECT_GT(item(resampled, "sample weights").figure, 5.0);
  const CheckReport fine = check_brdf(*testing::make("phong-modified", {{"n", "20"}, {"kd", "0"}}), quick());
  EXPECT_TRUE(item(fine, "sample weights").passed) << item(fine, "sample weights").detail;

  const CheckReport below = check_brdf(*broken("phong", {{"n", "5"}}, Broken::Fault::weight_below_horizon), quick());
  EXPECT_FALSE(item(below, "sample weights").passed);

  // Claims to be non-reciprocal but is symmetric: reported as a failure.
  const CheckReport claims = check_brdf(*broken("lambert", {}, Broken::Fault::claims_non_reciprocal), quick());
  EXPECT_FALSE(item(claims, "reciprocity").passed);
  // Claims reciprocity (by inheriting it) but is not.
  class Asymmetric final : public Brdf {
   public:
    Rgb eval(const Vec3& wi, const Vec3& wo) const override { return m_f->eval(wi, wo) * (1.0 + 1e-9 * wi.z); }
    double pdf(const Vec3& wi, const Vec3& wo) const override { return m_f->pdf(wi, wo); }
    BrdfSample sample(const Vec3& wo, Vec2 u, double ul) const override { return m_f->sample(wo, u, ul); }

   private:
    BrdfPtr m_f = testing::make("lambert");
  };
  const CheckReport asym = check_brdf(Asymmetric(), quick());
  EXPECT_FALSE(item(asym, "reciprocity").passed);
  EXPECT_GT(item(asym, "reciprocity").figure, 1e-10);
}

TEST(Check, Errors) {
  const auto unknown = check_brdf("no-such-model");
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("no-such-model"), std::string::npos);
  const auto bad = check_brdf("phong", {{"n", "-3"}});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("'n'"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace shadelab
