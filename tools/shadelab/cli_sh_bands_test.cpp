// End-to-end tests of `shadelab bake sh --bands N`, `--zh3` and `--error-report`.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>

#include "cli_run.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/image/image_io.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;

fs::path temp_dir() {
  static const fs::path dir = shadelab::testing::process_temp_dir("shadelab_cli_sh_bands");
  return dir;
}

// A 64 x 32 Radiance HDR written byte by byte: 0.5 everywhere (RGBE 128,128,128,128) but a 3 x 2 patch of
// 128 (RGBE 128,128,128,136) high in the sky, so the map has real L1..L4 content.
fs::path sun_hdr() {
  const fs::path p = temp_dir() / "sun.hdr";
  std::ofstream f(p, std::ios::binary);
  f << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32 +X 64\n";
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool sun = (y == 6 || y == 7) && x >= 20 && x < 23;
      f << static_cast<char>(128) << static_cast<char>(128) << static_cast<char>(128) << static_cast<char>(sun ? 136 : 128);
    }
  return p;
}

TEST(CliShBands, BandsThreeIsTodaysOutputExactly) {
  const std::string in = sun_hdr().string();
  for (const std::string extra : {" --json", "", " --units radiometric --json", " --window hanning --json"}) {
    const auto a = run("bake sh " + in + extra);
    const auto b = run("bake sh " + in + " --bands 3" + extra);
    EXPECT_EQ(a.code, 0) << a.err;
    EXPECT_EQ(a.out, b.out) << extra;
  }
  // Today's output, not only the same as without the flag: today's keys and none more, today's text, and
  // the coefficients of project_sh9 (sh.cpp) bit for bit.
  const auto j = json_of(run("bake sh " + in + " --bands 3 --json"));
  std::set<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.insert(key);
  EXPECT_EQ(keys, (std::set<std::string>{"order", "basis", "units", "convention", "band_factors", "window", "lights",
                                         "light_normalization", "radiance_coefficients", "irradiance_coefficients"}));
  const std::string text = run("bake sh " + in + " --bands 3").out;
  EXPECT_EQ(text.rfind("SH9 irradiance coefficients (game units: E/pi):", 0), 0u);
  // The text names its basis order and normalization (issue 39).
  EXPECT_NE(text.find("basis: real SH, Condon-Shortley phase, z polar axis, Sloan 2008 order: Y00, Y1-1, Y10"), std::string::npos) << text;
  EXPECT_NE(text.find("normalization: irradiance_coefficients give E/pi"), std::string::npos) << text;
  const shadelab::Sh9 sh = shadelab::project_sh9(shadelab::read_image(in).value());
  for (std::size_t i = 0; i < 9; ++i) EXPECT_EQ(j["radiance_coefficients"][i][1].get<double>(), sh.c[i].g) << i;
}

TEST(CliShBands, FiveBandsHaveTwentyFiveCoefficientsAndTheCosineFactors) {
  const std::string in = sun_hdr().string();
  const auto j3 = json_of(run("bake sh " + in + " --json"));
  const auto j = json_of(run("bake sh " + in + " --bands 5 --json"));
  EXPECT_EQ(j["bands"], 5);
  EXPECT_EQ(j["order"], 5);
  ASSERT_EQ(j["radiance_coefficients"].size(), 25u);
  ASSERT_EQ(j["irradiance_coefficients"].size(), 25u);
  // Game units: A_l / pi = 1, 2/3, 1/4, 0, -1/24.
  const double want[5] = {1.0, 2.0 / 3.0, 0.25, 0.0, -1.0 / 24.0};
  for (std::size_t l = 0; l < 5; ++l) EXPECT_NEAR(j["band_factors"][l].get<double>(), want[l], 1e-15) << l;
  // Bands 0..2 are today's coefficients; bands 3 and 4 carry the sun.
  for (std::size_t i = 0; i < 9; ++i) EXPECT_EQ(j["radiance_coefficients"][i], j3["radiance_coefficients"][i]) << i;
  double high = 0.0;
  for (std::size_t i = 9; i < 25; ++i) high += std::abs(j["radiance_coefficients"][i][0].get<double>());
  EXPECT_GT(high, 0.01);
  // Every key of today's JSON is still there.
  for (const auto& [key, value] : j3.items()) EXPECT_TRUE(j.contains(key)) << key;
  const auto j2 = json_of(run("bake sh " + in + " --bands 2 --window lanczos --json"));
  EXPECT_EQ(j2["irradiance_coefficients"].size(), 4u);
  EXPECT_NEAR(j2["band_factors"][1].get<double>(), 2.0 / 3.0 * 2.0 / std::numbers::pi, 1e-15);  // lanczos top band 2/pi
  // Text output names the coefficients.
  const auto t = run("bake sh " + in + " --bands 4");
  EXPECT_EQ(t.code, 0);
  EXPECT_NE(t.out.find("L3-3"), std::string::npos) << t.out;
}

TEST(CliShBands, Zh3AddsAKeyAndChangesNothingElse) {
  const std::string in = sun_hdr().string();
  const auto base = json_of(run("bake sh " + in + " --json"));
  for (const std::string mode : {"stored", "hallucinated"}) {
    auto j = json_of(run("bake sh " + in + " --zh3 " + mode + " --json"));
    ASSERT_TRUE(j.contains("zh3")) << mode;
    const auto z = j["zh3"];
    EXPECT_EQ(z["mode"], mode);
    ASSERT_EQ(z["radiance_coefficients"].size(), 5u);
    // The sun is high in the sky (+Y up): the luminance L1 axis points up.
    EXPECT_GT(z["axis"][1].get<double>(), 0.5) << z.dump();
    // The linear part is today's L1.
    for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(z["radiance_coefficients"][i], base["radiance_coefficients"][i]);
    j.erase("zh3");
    EXPECT_EQ(j, base) << mode;
  }
}

TEST(CliShBands, BadValuesAreRefused) {
  const std::string in = sun_hdr().string();
  const fs::path out = temp_dir() / "never.json";
  for (const std::string bad : {"6", "1", "0", "-3", "x", "2.5"}) {
    expect_usage_error("bake sh " + in + " --bands " + bad + " --out " + out.string(), "--bands");
  }
  expect_usage_error("bake sh " + in + " --zh3 sideways --out " + out.string(), "--zh3");
  expect_usage_error("bake sh " + in + " --zh3 '' --out " + out.string(), "--zh3");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliShBands, ErrorReportOnABlenderWorld) {
  const fs::path map = fs::path(SHADELAB_BLENDER_WORLDS) / "sunrise.exr";
  if (!fs::exists(map)) GTEST_FAIL() << map << " is missing (scripts/setup.sh installs blender-data)";
  const auto j = json_of(run("bake sh " + map.string() + " --error-report --json"));
  ASSERT_TRUE(j.contains("error_report"));
  const auto& rows = j["error_report"]["encodings"];
  ASSERT_EQ(rows.size(), 14u);
  std::map<std::string, nlohmann::json> by;
  for (const auto& r : rows) by[r["encoding"].get<std::string>()] = r;
  // sunrise rings at L2 without a window (measured: 0.27 sr at 16^2), not with one.
  EXPECT_GT(by["L2"]["negative_solid_angle_sr"].get<double>(), 0.05);
  EXPECT_EQ(by["L2 hanning"]["negative_solid_angle_sr"].get<double>(), 0.0);
  EXPECT_EQ(by["L2 lanczos"]["negative_solid_angle_sr"].get<double>(), 0.0);
  EXPECT_LT(by["L4"]["mean_relative_error"].get<double>(), by["L2"]["mean_relative_error"].get<double>());
  EXPECT_EQ(by["ZH3 stored"]["coefficients_per_channel"], 5);
  // The SH keys are today's.
  EXPECT_EQ(j["irradiance_coefficients"].size(), 9u);
}

}  // namespace
