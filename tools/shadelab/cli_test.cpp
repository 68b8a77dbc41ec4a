// End-to-end tests of the shadelab CLI: run the built binary, check stdout JSON, stderr and exit codes.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "cli_run.h"

namespace {

using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::CliRun;
using shadelab::testing::run;

constexpr double pi = std::numbers::pi;

TEST(Cli, HelpForEveryCommand) {
  for (const char* c : {"--help", "zoo --help", "brdf --help", "brdf list --help", "brdf eval --help",
                        "brdf albedo --help", "brdf check --help", "fresnel --help", "light --help", "bake --help", "bake irradiance --help", "render --help", "report --help", "compare --help", "plot --help", "plot lobe --help", "sheet --help"}) {
    const CliRun r = run(c);
    EXPECT_EQ(r.code, 0) << c;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << c;
  }
}

TEST(Cli, BrdfListHasEveryModelWithParameters) {
  const auto j = json_of(run("brdf list --json"));
  std::vector<std::string> names;
  for (const auto& m : j["models"]) names.push_back(m["name"]);
  for (const char* want : {"lambert", "phong", "phong-modified", "blinn-phong", "blinn-phong-modified", "cook-torrance",
                           "minimalist-cook-torrance", "ward", "ward-anisotropic", "lafortune", "wrapped-diffuse",
                           "ggx", "burley", "filament", "gltf", "principled-v1", "layered", "openpbr", "measured"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  }
  for (const auto& m : j["models"]) {
    for (const auto& p : m["params"]) {
      EXPECT_TRUE(p.contains("default")) << m["name"];
      // a file parameter (measured's) is a path: no range, whether it is required instead
      EXPECT_TRUE(p.contains("choices") || (p.contains("min") && p.contains("max")) || (p["kind"] == "file" && p.contains("required")))
          << m["name"];
    }
  }
  EXPECT_EQ(run("brdf list").code, 0);
}

TEST(Cli, BrdfEvalLambert) {
  const auto j = json_of(run("brdf eval lambert --param kd=0.5,0.25,1 --wi 0,0,1 --wo 0.3,0,2 --json"));
  ASSERT_EQ(j["f"].size(), 3u);
  EXPECT_NEAR(j["f"][0].get<double>(), 0.5 / pi, 1e-15);
  EXPECT_NEAR(j["f"][1].get<double>(), 0.25 / pi, 1e-15);
  EXPECT_NEAR(j["f"][2].get<double>(), 1.0 / pi, 1e-15);
}

// The layered ground truth's eval is a Monte Carlo estimate: the CLI states its standard error (JSON and text);
// an exact model has no such key.
TEST(Cli, BrdfEvalOfAStochasticModelStatesItsStandardError) {
  const auto j = json_of(run("brdf eval layered --param walk_samples=16 --wi 0.3,0,1 --wo -0.2,0.1,1 --json"));
  ASSERT_EQ(j["standard_error"].size(), 3u);
  EXPECT_GT(j["standard_error"][1].get<double>(), 0.0);
  EXPECT_LT(j["standard_error"][1].get<double>(), j["f"][1].get<double>());
  EXPECT_TRUE(json_of(run("brdf eval layered --param walk_samples=1 --wi 0.3,0,1 --wo -0.2,0.1,1 --json"))["standard_error"].is_null());
  EXPECT_FALSE(json_of(run("brdf eval lambert --wi 0,0,1 --wo 0,0,1 --json")).contains("standard_error"));
  const CliRun text = run("brdf eval layered --wi 0.3,0,1 --wo -0.2,0.1,1");
  EXPECT_NE(text.out.find("standard error"), std::string::npos) << text.out;
}

TEST(Cli, BrdfEvalBelowHorizonIsZero) {
  const auto j = json_of(run("brdf eval phong --wi 0,0.2,-1 --wo 0,0,1 --json"));
  EXPECT_EQ(j["f"][0].get<double>(), 0.0);
}

TEST(Cli, BrdfEvalBadInput) {
  expect_usage_error("brdf eval nosuchmodel --wi 0,0,1 --wo 0,0,1", "unknown BRDF model 'nosuchmodel'");
  expect_usage_error("brdf eval phong --param shininess=3 --wi 0,0,1 --wo 0,0,1", "unknown parameter 'shininess'");
  expect_usage_error("brdf eval phong --param n=-1 --wi 0,0,1 --wo 0,0,1", "parameter 'n' = -1 is out of range");
  expect_usage_error("brdf eval phong --param kd=2000 --wi 0,0,1 --wo 0,0,1", "parameter 'kd'");
  expect_usage_error("brdf eval phong --param kd=nan --wi 0,0,1 --wo 0,0,1", "not finite");
  expect_usage_error("brdf eval phong --param normalization=half --wi 0,0,1 --wo 0,0,1", "normalization");
  expect_usage_error("brdf eval phong --param n --wi 0,0,1 --wo 0,0,1", "NAME=VALUE");
  expect_usage_error("brdf eval lambert --wi 0,0,0 --wo 0,0,1", "--wi");
  expect_usage_error("brdf eval lambert --wi 0,0,1 --wo nan,0,1", "--wo");
  expect_usage_error("brdf eval lambert --wi 0,0,1 --wo inf,0,1", "--wo");
  expect_usage_error("brdf eval lambert --wi 0,1 --wo 0,0,1", "--wi");
  expect_usage_error("brdf eval lambert --wo 0,0,1", "--wi");
  expect_usage_error("brdf eval cook-torrance --param m=0.2 --param n=10 --wi 0,0,1 --wo 0,0,1", "not both");
  expect_usage_error("brdf", "subcommand is required");
  expect_usage_error("nosuchcommand", "nosuchcommand");
}

TEST(Cli, BrdfAlbedoNormalizedPhongIsOne) {
  const auto j = json_of(run("brdf albedo phong --param kd=0 --param ks=1 --param n=100 --theta 0 --theta 45 --json"));
  ASSERT_EQ(j["theta"].size(), 2u);
  ASSERT_EQ(j["albedo"].size(), 2u);
  EXPECT_NEAR(j["albedo"][0][0].get<double>(), 1.0, 1e-9);
  EXPECT_LT(j["albedo"][1][0].get<double>(), 1.0);
  expect_usage_error("brdf albedo lambert --theta 95", "--theta");
  expect_usage_error("brdf albedo lambert --theta -1", "--theta");
}

TEST(Cli, BrdfCheckLambertPasses) {
  const auto j = json_of(run("brdf check lambert --json"));
  ASSERT_TRUE(j.contains("checks"));
  EXPECT_TRUE(j["passed"].get<bool>());
  EXPECT_GE(j["checks"].size(), 4u);
  for (const auto& c : j["checks"]) {
    EXPECT_TRUE(c.contains("name") && c.contains("passed") && c.contains("figure")) << c.dump();
  }
  expect_usage_error("brdf check ward --param alpha=0", "alpha");
}

TEST(Cli, BrdfCheckReportsAFailureWithExitCode1) {
  // The 1981 Cook-Torrance form is four times the microfacet form: with F = 1 it reflects more than it gets.
  const CliRun r = run("brdf check cook-torrance --param kd=0 --param f=none --param form=1981 --json");
  EXPECT_EQ(r.code, 1) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["passed"].get<bool>());
  bool energy_failed = false;
  for (const auto& c : j["checks"]) energy_failed = energy_failed || (c["name"] == "energy" && !c["passed"].get<bool>());
  EXPECT_TRUE(energy_failed);
}

// Issue 10 section 3: the check prints the white furnace (asserted with Kulla-Conty, 1e-3) and every sampler's
// variance for ggx.
TEST(Cli, BrdfCheckGgxPrintsFurnaceAndVariance) {
  const CliRun r = run("brdf check ggx --param ms=kulla-conty --json");
  EXPECT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["model"], "ggx");
  EXPECT_TRUE(j["passed"].get<bool>());
  const auto find = [&](const std::string& name) {
    for (const auto& c : j["checks"]) {
      if (c["name"] == name) return c;
    }
    ADD_FAILURE() << "no check " << name << " in " << r.out;
    return nlohmann::json::object();
  };
  const auto furnace = find("furnace");
  ASSERT_TRUE(furnace.contains("figure") && furnace.contains("threshold") && furnace.contains("detail"));
  EXPECT_TRUE(furnace["passed"].get<bool>());
  EXPECT_EQ(furnace["threshold"].get<double>(), 1e-3);
  EXPECT_GE(furnace["figure"].get<double>(), 0.0);
  EXPECT_LE(furnace["figure"].get<double>(), 1e-3);
  EXPECT_NE(furnace["detail"].get<std::string>().find("variant f=none kd=0 ks=1"), std::string::npos);
  const auto variance = find("variance");
  ASSERT_TRUE(variance.contains("figure") && variance.contains("threshold") && variance.contains("detail"));
  EXPECT_TRUE(variance["passed"].get<bool>());
  EXPECT_TRUE(variance["threshold"].is_null());  // reported only
  EXPECT_GT(variance["figure"].get<double>(), 0.0);
  const std::string detail = variance["detail"];
  for (const char* s : {"; ndf: ", "; vndf: ", "; vndf-caps: ", "; vndf-bounded (configured): "}) {
    EXPECT_NE(detail.find(s), std::string::npos) << s << " in " << detail;
  }
}

TEST(Cli, FresnelKnownValues) {
  auto j = json_of(run("fresnel --ior 1.5 --theta 0 --json"));
  EXPECT_NEAR(j["F"].get<double>(), 0.04, 1e-15);  // ((1.5 - 1)/(1.5 + 1))^2
  j = json_of(run("fresnel --ior 1.33 --theta 90 --json"));
  EXPECT_NEAR(j["F"].get<double>(), 1.0, 1e-12);
  j = json_of(run("fresnel --ior 0.2,3.6 --theta 0 --json"));
  EXPECT_NEAR(j["F"].get<double>(), (0.8 * 0.8 + 3.6 * 3.6) / (1.2 * 1.2 + 3.6 * 3.6), 1e-12);
  j = json_of(run("fresnel --material gold --theta 0 --json"));
  ASSERT_EQ(j["F"].size(), 3u);
  EXPECT_GT(j["F"][0].get<double>(), j["F"][2].get<double>());  // gold reflects red more than blue
  EXPECT_EQ(run("fresnel --list").code, 0);
}

TEST(Cli, FresnelBadInput) {
  expect_usage_error("fresnel --ior 1.5 --theta 100", "--theta");
  expect_usage_error("fresnel --ior -1.5 --theta 0", "--ior");
  expect_usage_error("fresnel --ior 1.5,-2 --theta 0", "--ior");
  expect_usage_error("fresnel --ior abc", "--ior");
  expect_usage_error("fresnel --material unobtainium", "unobtainium");
  expect_usage_error("fresnel --theta 10", "--ior");
  expect_usage_error("fresnel --ior 1.5 --material gold", "excludes");
}

TEST(Cli, ZooTableMatchesClosedForms) {
  const auto j = json_of(run("zoo --n 1 --n 100 --json"));
  ASSERT_TRUE(j.contains("rows"));
  EXPECT_EQ(j["rows"].size(), 12u);  // six rows x two exponents
  for (const auto& row : j["rows"]) {
    EXPECT_LT(std::abs(row["relative_error"].get<double>()), 1e-9) << row.dump();
    EXPECT_TRUE(row.contains("literature"));
  }
  const CliRun text = run("zoo");
  EXPECT_EQ(text.code, 0);
  EXPECT_NE(text.out.find("blinn-phong-modified"), std::string::npos);
  expect_usage_error("zoo --n -1", "--n");
  expect_usage_error("zoo --n nan", "--n");
}

}  // namespace
