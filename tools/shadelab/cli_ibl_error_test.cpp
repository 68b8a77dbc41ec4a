// End-to-end tests of `shadelab ibl-error` (docs/cli.md): the files, the JSON shape and figures under a
// constant environment (where both shortcuts are exact up to the DFG table and the reference's noise), and
// bad input: one line, exit 2, nothing written.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::constant_hdr;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

const std::string quick = " --roughness 0.3,0.8 --bins 4 --size 48 --spp 32 --threads 2";

TEST(CliIblError, WritesTheMapsAndAConstantEnvironmentHasNoError) {
  const fs::path dir = temp_dir() / "ibl_error";
  const auto j = json_of(run("ibl-error " + constant_hdr().string() + quick + " --out " + dir.string() + " --json"));
  for (const char* name : {"ibl_error.json", "split_sum_error.png", "split_sum_error.svg", "index.html",
                           "corrected_error.png"}) {
    EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;
  }
  std::ifstream f(dir / "ibl_error.json");
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(nlohmann::json::parse(ss.str()), j);  // the file is what --json prints
  EXPECT_EQ(j["model"], "ggx");
  EXPECT_EQ(j["nv_bins"], 4);
  EXPECT_EQ(j["specular_size"], 64);
  ASSERT_EQ(j["split_sum"]["rows"].size(), 2u);
  EXPECT_EQ(j["split_sum"]["rows"][1]["roughness"], 0.8);
  // 0.5 everywhere: the split sum is L (f0 A + B) exactly but for the table (0.5%); the reference's noise.
  const auto expect_exact = [](const nlohmann::json& rows) {
    for (const auto& row : rows) {
      ASSERT_EQ(row["cells"].size(), 4u);
      for (const auto& c : row["cells"]) {
        EXPECT_EQ(c.size(), 8u);  // with no_signal (issue 40)
        if (c["pixels"] == 0) continue;
        EXPECT_LE(std::abs(c["error"].get<double>()),
                  4.0 * c["reference_standard_error"].get<double>() / c["reference"].get<double>() + 6e-3)
            << c;
      }
    }
  };
  expect_exact(j["split_sum"]["rows"]);
  // The default correction (the lobe-matched reads) under a constant environment: the same exactness (where
  // and how wide the chain is read cannot matter).
  ASSERT_EQ(j["corrected"]["rows"].size(), 2u);
  EXPECT_TRUE(j["corrected"].contains("grazing_reduction"));
  EXPECT_EQ(j["corrected"]["direction"].get<std::string>().rfind("lobes:", 0), 0u);
  expect_exact(j["corrected"]["rows"]);
  for (const auto& c : j["sh"]["cells"]) {
    if (c["pixels"] == 0) continue;
    EXPECT_NEAR(c["reference"].get<double>(), 0.5, 0.01) << c;  // the white furnace
    EXPECT_NEAR(c["shortcut"].get<double>(), 0.5, 0.005) << c;
  }
  EXPECT_TRUE(j["split_sum"]["summary"].contains("grazing_mean_abs_error"));
  EXPECT_EQ(j["corrected"]["taps"], 0);  // taps only with --correction filtered
  // The filtered taps: each part a weighted mean of chain reads, exact for a constant too.
  const auto jf = json_of(run("ibl-error " + constant_hdr().string() + quick + " --correction filtered --taps 16 --out " +
                              (temp_dir() / "ibl_error_filtered").string() + " --json"));
  EXPECT_EQ(jf["corrected"]["direction"].get<std::string>().rfind("filtered:", 0), 0u);
  EXPECT_EQ(jf["corrected"]["taps"], 16);
  ASSERT_EQ(jf["corrected"]["rows"].size(), 2u);
  expect_exact(jf["corrected"]["rows"]);
  std::ifstream page(dir / "index.html");
  std::stringstream ps;
  ps << page.rdbuf();
  EXPECT_NE(ps.str().find("split_sum_error.png"), std::string::npos);
  EXPECT_NE(ps.str().find("corrected_error.png"), std::string::npos);
  EXPECT_NE(ps.str().find("SH9 irradiance"), std::string::npos);
}

TEST(CliIblError, BadInputIsOneLineAndWritesNothing) {
  const fs::path dir = temp_dir() / "ibl_bad";
  const std::string in = constant_hdr().string();
  const std::string out = " --out " + dir.string();
  expect_usage_error("ibl-error " + in + " --model lambert" + out, "--model: 'lambert'");
  expect_usage_error("ibl-error " + in + " --roughness 0" + out, "--roughness: 0 is not in (0, 1]");
  expect_usage_error("ibl-error " + in + " --roughness 0.5,nan" + out, "--roughness");
  expect_usage_error("ibl-error " + in + " --bins 0" + out, "--bins");
  expect_usage_error("ibl-error " + in + " --correction mirror" + out, "--correction: 'mirror' is not lobes, dominant or filtered");
  // The one name of the concept, --split-sum-lookup (render's flag), is the same option.
  expect_usage_error("ibl-error " + in + " --split-sum-lookup mirror" + out, "'mirror' is not lobes, dominant or filtered");
  expect_usage_error("ibl-error " + in + " --correction filtered --taps 0" + out, "--taps");
  expect_usage_error("ibl-error " + in + " --correction filtered --taps 1025" + out, "--taps");
  expect_usage_error("ibl-error " + in + " --specular-size 48" + out, "--specular-size: 48 is not a power of two");
  expect_usage_error("ibl-error " + in + " --specular-size 2048" + out, "--specular-size");
  expect_usage_error("ibl-error " + in + " --size 8" + out, "--size");
  expect_usage_error("ibl-error " + in + " --spp 0" + out, "--spp");
  expect_usage_error("ibl-error " + in + " --seed -1" + out, "--seed");
  expect_usage_error("ibl-error " + in + " --param roughness=0.5" + quick + out, "set per row");
  expect_usage_error("ibl-error " + in + " --param kd=0.5" + quick + out, "kd is 0");
  expect_usage_error("ibl-error " + in + " --param nonsense=1" + quick + out, "nonsense");
  expect_usage_error("ibl-error " + (temp_dir() / "missing.exr").string() + out, "missing.exr");
  // A 2:1 input is required.
  const fs::path square = temp_dir() / "square.hdr";
  {
    std::ofstream f(square, std::ios::binary);
    f << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 8\n";
    for (int i = 0; i < 8 * 8 * 4; ++i) f << static_cast<char>(128);
  }
  expect_usage_error("ibl-error " + square.string() + out, "not a 2:1 lat-long");
  // An output that is the input.
  expect_usage_error("ibl-error " + in + " --out " + in, "--out");
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
