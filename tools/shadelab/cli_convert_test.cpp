// Issue 41's `convert shininess`: the best fit and the published mappings in JSON, the best fit no worse than any
// mapping; bad input is one line and exit 2.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_run.h"

namespace shadelab {
namespace {

using testing::json_of;
using testing::run;

TEST(CliConvert, ShininessPrintsTheBestFitBesideThePublishedMappings) {
  const auto j = json_of(run("convert shininess --from blinn-phong --to ggx --n 100 --json"));
  EXPECT_EQ(j["from"], "blinn-phong");
  EXPECT_EQ(j["to"], "ggx");
  EXPECT_EQ(j["metric"], "cosine-l2");
  const double alpha = j["alpha"].get<double>();
  EXPECT_GT(alpha, 0.05);
  EXPECT_LT(alpha, 0.5);
  EXPECT_NEAR(j["roughness"].get<double>(), std::sqrt(alpha), 1e-12);
  ASSERT_EQ(j["mappings"].size(), 4u);
  EXPECT_EQ(j["mappings"][0]["name"], "walter");
  EXPECT_NEAR(j["mappings"][0]["alpha"].get<double>(), std::sqrt(2.0 / 102.0), 1e-12);
  for (const auto& m : j["mappings"]) EXPECT_GE(m["excess"].get<double>(), -1e-9) << m;
  // Godot's mapping is undefined beyond n = 512: null, not a number.
  const auto k = json_of(run("convert shininess --from phong --to beckmann --n 2000 --json"));
  EXPECT_TRUE(k["mappings"][2]["alpha"].is_null()) << k["mappings"][2];
  const auto t = run("convert shininess --from phong --n 30");
  EXPECT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("walter"), std::string::npos) << t.out;
}

TEST(CliConvert, BadInputIsOneLineAndExitTwo) {
  for (const char* args : {"convert shininess --from ward --n 10", "convert shininess --from phong --to ward --n 10",
                                  "convert shininess --from phong --n 0", "convert shininess --from phong --n nan",
                                  "convert shininess --from phong --n 10 --metric l1", "convert"}) {
    const auto r = run(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

}  // namespace
}  // namespace shadelab
