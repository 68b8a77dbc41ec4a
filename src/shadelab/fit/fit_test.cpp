// The fitter: its metrics against their definitions, the configuration grid's measure against the measure of the
// configuration space, and fits of data of known parameters back to those parameters.
#include "shadelab/fit/fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <tbb/task_arena.h>

#include "shadelab/brdf/merl.h"

namespace shadelab {
namespace {

constexpr double pi = std::numbers::pi;

TEST(FitMetric, TransformsAreTheirDefinitions) {
  for (double x : {0.0, 1e-6, 0.25, 1.0, 37.5}) {
    EXPECT_EQ(fit_metric_transform(FitMetric::cosine_l2, x), x);
    EXPECT_NEAR(fit_metric_transform(FitMetric::cube_root, x), std::pow(x, 1.0 / 3.0), 1e-14 * (1.0 + x));
    EXPECT_NEAR(fit_metric_transform(FitMetric::log, x), std::log(1.0 + x), 1e-15 * (1.0 + x));
  }
  EXPECT_EQ(fit_metric_name(*parse_fit_metric("cube-root")), std::string("cube-root"));
  const auto bad = parse_fit_metric("l1");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("cosine-l2, cube-root, log"), std::string::npos) << bad.error().message;
}

TEST(FitGrid, WeightsSumToTheMeasureOfPairsOfUpperDirections) {
  // Both directions over the upper hemisphere: (2 pi)^2 of dw_i dw_o. Bins whose centre is below the horizon are
  // dropped whole, so the sum is a midpoint rule with an O(bin width) boundary error.
  FitGridOptions o;
  o.theta_d_stride = 2;
  o.phi_d_stride = 2;
  o.max_theta_deg = 90.0;
  const FitData g = fit_grid(o);
  double w = 0.0;
  for (double x : g.weight) w += x;
  EXPECT_NEAR(w / (4.0 * pi * pi), 1.0, 0.01) << w;
  // Within a cone of half-angle 60 degrees for each: (2 pi (1 - cos 60))^2 = pi^2.
  o.max_theta_deg = 60.0;
  const FitData c = fit_grid(o);
  double wc = 0.0;
  for (double x : c.weight) wc += x;
  EXPECT_NEAR(wc / (pi * pi), 1.0, 0.02) << wc;
  // Azimuths of the half vector share the weight: the total does not change.
  o.n_phi_h = 4;
  const FitData r = fit_grid(o);
  double wr = 0.0;
  for (double x : r.weight) wr += x;
  EXPECT_EQ(r.weight.size(), 4 * c.weight.size());
  EXPECT_NEAR(wr, wc, 1e-9 * wc);
}

TEST(FitModelSpec, ColoursKeepTheirCommas) {
  const auto s = parse_model_spec("model:ggx,alpha=0.3,kd=0.8,0.6,0.2,f0=0.04");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->first, "ggx");
  ASSERT_EQ(s->second.size(), 3u);
  EXPECT_EQ(s->second[1].second, "0.8,0.6,0.2");
  EXPECT_FALSE(parse_model_spec("ggx,alpha=0.3"));
  EXPECT_FALSE(parse_model_spec("model:,alpha=0.3"));
  EXPECT_FALSE(parse_model_spec("model:ggx,0.3"));
}

// Coarse grids keep each fit near a second on one core.
FitGridOptions coarse() {
  FitGridOptions o;
  o.theta_d_stride = 6;
  o.phi_d_stride = 12;
  return o;
}

const FitParamValue& param(const FitResult& r, const std::string& name) {
  for (const auto& p : r.params) {
    if (p.name == name) return p;
  }
  throw std::logic_error("no parameter " + name);
}

void expect_recovered(const FitResult& r, const std::string& name, const std::vector<double>& expected) {
  const auto& p = param(r, name);
  EXPECT_TRUE(p.fitted) << name;
  ASSERT_EQ(p.numbers.size(), expected.size()) << name;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(p.numbers[i], expected[i], 1e-3 * std::abs(expected[i])) << name << "[" << i << "]";
  }
}

TEST(Fit, GgxFromAMerlFileOfKnownParametersIsRecovered) {
  // Data: ggx (alpha 0.3, f0 0.04, kd 0.1) measured into the MERL layout; the defaults (alpha 0.25, kd 0.2) start.
  auto truth = make_brdf("ggx", {{"alpha", "0.3"}, {"f0", "0.04"}, {"kd", "0.1"}});
  ASSERT_TRUE(truth);
  const MerlTable table = measure_merl(**truth);
  const FitData data = fit_data_from_merl(table, coarse());
  ASSERT_GT(data.wi.size(), 5000u);
  const auto r = fit_model("ggx", data);
  ASSERT_TRUE(r) << r.error().message;
  expect_recovered(*r, "alpha", {0.3});
  expect_recovered(*r, "f0", {0.04, 0.04, 0.04});
  expect_recovered(*r, "kd", {0.1, 0.1, 0.1});
  EXPECT_EQ(r->fitted, (std::vector<std::string>{"kd", "alpha", "f0"}));
  EXPECT_LT(r->residual, 1e-6);
  // The assignments rebuild the fit.
  auto rebuilt = make_brdf("ggx", r->assignments);
  ASSERT_TRUE(rebuilt);
  EXPECT_NEAR(fit_residual(**rebuilt, data, FitMetric::cosine_l2), r->residual, 1e-12);
}

TEST(Fit, CookTorranceOfKnownParametersIsRecoveredUnderEachMetric) {
  auto truth = make_brdf("cook-torrance", {{"kd", "0.3"}, {"m", "0.2"}, {"f0", "0.08"}});
  ASSERT_TRUE(truth);
  const FitData data = fit_data_from_brdf(**truth, coarse());
  for (FitMetric m : {FitMetric::cosine_l2, FitMetric::cube_root, FitMetric::log}) {
    FitOptions o;
    o.metric = m;
    o.starts = 2;
    const auto r = fit_model("cook-torrance", data, o);
    ASSERT_TRUE(r) << r.error().message;
    SCOPED_TRACE(fit_metric_name(m));
    expect_recovered(*r, "m", {0.2});
    expect_recovered(*r, "f0", {0.08, 0.08, 0.08});
    expect_recovered(*r, "kd", {0.3, 0.3, 0.3});
  }
}

TEST(Fit, AnisotropicWardOfKnownParametersIsRecovered) {
  auto truth = make_brdf("ward-anisotropic", {{"kd", "0.15"}, {"ks", "0.25"}, {"alpha_x", "0.3"}, {"alpha_y", "0.08"}});
  ASSERT_TRUE(truth);
  EXPECT_FALSE(looks_isotropic(**truth));
  FitGridOptions g = coarse();
  g.n_phi_h = 6;
  const FitData data = fit_data_from_brdf(**truth, g);
  const auto r = fit_model("ward-anisotropic", data);
  ASSERT_TRUE(r) << r.error().message;
  expect_recovered(*r, "alpha_x", {0.3});
  expect_recovered(*r, "alpha_y", {0.08});
  expect_recovered(*r, "ks", {0.25, 0.25, 0.25});
  expect_recovered(*r, "kd", {0.15, 0.15, 0.15});
}

TEST(Fit, LafortuneOfKnownLobeIsRecovered) {
  auto truth = make_brdf("lafortune", {{"kd", "0.2"}, {"lobes", "-0.9,-0.9,1.1,12"}});
  ASSERT_TRUE(truth);
  EXPECT_TRUE(looks_isotropic(**truth));
  const FitData data = fit_data_from_brdf(**truth, coarse());
  const auto r = fit_model("lafortune", data);
  ASSERT_TRUE(r) << r.error().message;
  expect_recovered(*r, "lobes", {-0.9, -0.9, 1.1, 12.0});
  expect_recovered(*r, "kd", {0.2, 0.2, 0.2});
}

TEST(Fit, AModelThatCannotRepresentTheDataReportsItsResidual) {
  auto truth = make_brdf("ggx", {{"alpha", "0.2"}, {"kd", "0.3"}});
  ASSERT_TRUE(truth);
  const FitData data = fit_data_from_brdf(**truth, coarse());
  const auto r = fit_model("lambert", data);
  ASSERT_TRUE(r) << r.error().message;
  // The data's own size in the metric: E of a black BRDF.
  auto black = make_brdf("lambert", {{"kd", "0"}});
  const double scale = fit_residual(**black, data, FitMetric::cosine_l2);
  EXPECT_GT(r->residual, 0.05 * scale) << r->residual << " vs " << scale;
  EXPECT_LT(r->residual, scale);
  // Fixing and freeing by name.
  FitOptions o;
  o.fixed = {{"kd", "0.5"}};
  const auto fixed = fit_model("lambert", data, o);
  ASSERT_TRUE(fixed);
  EXPECT_TRUE(fixed->fitted.empty());
  EXPECT_GT(fixed->residual, r->residual);
  o = {};
  o.free = {"nope"};
  const auto bad = fit_model("lambert", data, o);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("'nope'"), std::string::npos) << bad.error().message;
}

TEST(Fit, ColouredDataAreFittedPerChannel) {
  auto truth = make_brdf("ward", {{"kd", "0.6,0.3,0.1"}, {"ks", "0.2"}, {"alpha", "0.15"}});
  ASSERT_TRUE(truth);
  const FitData data = fit_data_from_brdf(**truth, coarse());
  EXPECT_FALSE(fit_data_is_grey(data));
  FitOptions o;
  o.starts = 1;
  const auto r = fit_model("ward", data, o);
  ASSERT_TRUE(r) << r.error().message;
  expect_recovered(*r, "kd", {0.6, 0.3, 0.1});
  expect_recovered(*r, "alpha", {0.15});
}

TEST(Fit, TheResultDoesNotDependOnTheThreadCount) {
  // The objective's chunks are added in order: a fit under one thread gives the same bits.
  auto truth = make_brdf("ward", {{"kd", "0.25"}, {"ks", "0.2"}, {"alpha", "0.15"}});
  const FitData data = fit_data_from_brdf(**truth, coarse());
  FitOptions o;
  o.starts = 1;
  const auto many = fit_model("ward", data, o);
  FitResult one;
  {
    tbb::task_arena arena(1);
    arena.execute([&] { one = *fit_model("ward", data, o); });
  }
  ASSERT_TRUE(many);
  EXPECT_EQ(many->residual, one.residual);
  EXPECT_EQ(many->assignments, one.assignments);
}

}  // namespace
}  // namespace shadelab
