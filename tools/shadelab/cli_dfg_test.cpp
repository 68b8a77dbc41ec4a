// End-to-end tests of `shadelab bake dfg`: the table in EXR and as a C header, its stated conventions, the
// error it reports, and bad options.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/image/image_io.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

TEST(CliDfg, ExrHoldsScaleBiasAndAlbedoAtTexelCentresWithRowZeroTheSmoothest) {
  const fs::path out = temp_dir() / "dfg.exr";
  const auto j = json_of(run("bake dfg --size 8 --multiscatter --out " + out.string() + " --json"));
  EXPECT_EQ(j["size"], 8);
  EXPECT_EQ(j["method"], "quadrature");
  EXPECT_LT(j["error"].get<double>(), 1e-6);
  EXPECT_EQ(j["channels"].size(), 3u);
  const auto img = shadelab::read_image(out);
  ASSERT_TRUE(img.has_value()) << img.error().message;
  ASSERT_EQ(img->width, 8);
  ASSERT_EQ(img->height, 8);
  // Column 5, row 2: N.V = 5.5/8, roughness 2.5/8, against the library's value there (float32 file).
  const double mu = 5.5 / 8.0;
  const double r = 2.5 / 8.0;
  const auto v = shadelab::dfg_quadrature(mu, r * r);
  EXPECT_NEAR(img->at(5, 2).r, v.a, 1e-6);
  EXPECT_NEAR(img->at(5, 2).g, v.b, 1e-6);
  EXPECT_NEAR(img->at(5, 2).b, v.a + v.b, 1e-6);
  // Row 0 is the smallest roughness: nearly a mirror, so A + B is near 1 there and lowest in the last row.
  EXPECT_GT(img->at(7, 0).b, 0.99);
  EXPECT_LT(img->at(7, 7).b, img->at(7, 0).b - 0.05);
}

TEST(CliDfg, HeaderHoldsTheSameFloats) {
  const fs::path exr = temp_dir() / "dfg2.exr";
  const fs::path h = temp_dir() / "dfg2.h";
  ASSERT_EQ(run("bake dfg --size 4 --out " + exr.string()).code, 0);
  ASSERT_EQ(run("bake dfg --size 4 --out " + h.string()).code, 0);
  std::ifstream f(h);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  EXPECT_NE(text.find("shadelab_dfg_channels = 2"), std::string::npos);
  const auto body = text.substr(text.find('{') + 1);
  std::istringstream in(body);
  const auto img = shadelab::read_image(exr).value();
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      for (int c = 0; c < 2; ++c) {
        std::string tok;
        in >> tok;  // "0.123f,"
        const double value = std::stod(tok);
        const float expected = c == 0 ? static_cast<float>(img.at(i, j).r) : static_cast<float>(img.at(i, j).g);
        EXPECT_EQ(static_cast<float>(value), expected) << i << " " << j << " " << c;
      }
    }
  }
}

TEST(CliDfg, SamplingReportsItsMeasuredError) {
  const fs::path out = temp_dir() / "dfg3.exr";
  const auto j = json_of(run("bake dfg --size 8 --samples 64 --out " + out.string() + " --json"));
  EXPECT_EQ(j["method"], "hammersley");
  EXPECT_GT(j["error"].get<double>(), 1e-6);  // 64 points are far from exact
  EXPECT_LT(j["error"].get<double>(), 0.2);
}

TEST(CliDfg, AdaptiveIsTheReferenceQuadratureAndTheDefaultIsWithinAMillionthOfIt) {
  const fs::path fixed = temp_dir() / "dfg_fixed.exr", adaptive = temp_dir() / "dfg_adaptive.exr";
  const auto jf = json_of(run("bake dfg --size 4 --out " + fixed.string() + " --json"));
  const auto ja = json_of(run("bake dfg --size 4 --adaptive --out " + adaptive.string() + " --json"));
  EXPECT_EQ(jf["method"], "quadrature");
  EXPECT_EQ(ja["method"], "adaptive quadrature");
  EXPECT_NE(jf["error_meaning"], ja["error_meaning"]);
  EXPECT_LT(ja["error"].get<double>(), 2e-6);
  const auto a = shadelab::read_image(fixed).value(), b = shadelab::read_image(adaptive).value();
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      EXPECT_NEAR(a.at(i, j).r, b.at(i, j).r, 1e-6) << i << " " << j;
      EXPECT_NEAR(a.at(i, j).g, b.at(i, j).g, 1e-6) << i << " " << j;
    }
  }
}

TEST(CliDfg, BadOptionsAreUsageErrors) {
  expect_usage_error("bake dfg --size 0 --out " + (temp_dir() / "x.exr").string(), "--size");
  expect_usage_error("bake dfg --size 8 --samples -3 --out " + (temp_dir() / "x.exr").string(), "--samples");
  expect_usage_error("bake dfg --size 8 --out " + (temp_dir() / "x.png").string(), "--out");
  expect_usage_error("bake dfg --size 8 --adaptive --samples 4 --out " + (temp_dir() / "x.exr").string(), "--adaptive");
  EXPECT_FALSE(fs::exists(temp_dir() / "x.exr"));
  EXPECT_FALSE(fs::exists(temp_dir() / "x.png"));
}

}  // namespace
