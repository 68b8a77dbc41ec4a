// End-to-end tests of `shadelab render --shard` and `shadelab merge` (docs/scale-out.md).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_run.h"
#include "shadelab/render/shard_file.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

// 40 x 24, 16 spp (tests/scale-out/scene.json).
const std::string scene = std::string(SHADELAB_SCENES_DIR) + "/../tests/scale-out/scene.json";

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Renders shard i of n into dir/part-i.exr; returns the path.
fs::path shard(const fs::path& dir, int i, int n, const std::string& split, int threads) {
  const fs::path p = dir / ("part-" + std::to_string(i) + ".exr");
  const auto r = run("render " + scene + " --shard " + std::to_string(i) + "/" + std::to_string(n) + " --split " + split +
                     " --threads " + std::to_string(threads) + " --out " + p.string());
  EXPECT_EQ(r.code, 0) << r.err;
  return p;
}

std::string list(const std::vector<fs::path>& v) {
  std::string s;
  for (const auto& p : v) s += " " + p.string();
  return s;
}

// The merged EXR has the bytes of the one-machine render, whatever the split, the shard count and the thread
// count of each shard; both with and without threads given to the single render.
TEST(CliMerge, MergedFileIsTheSingleRenderFileByteForByte) {
  const fs::path ref = temp_dir() / "ref.exr";
  ASSERT_EQ(run("render " + scene + " --threads 2 --no-png --out " + ref.string()).code, 0);
  const std::string want = bytes(ref);
  ASSERT_GT(want.size(), 1000u);
  for (const auto& [split, n] : {std::pair{std::string("samples"), 3}, std::pair{std::string("tiles"), 7}}) {
    const fs::path dir = temp_dir() / (split + std::to_string(n));
    fs::create_directories(dir);
    std::vector<fs::path> parts;
    for (int i = 0; i < n; ++i) parts.push_back(shard(dir, i, n, split, 1 + i % 2));
    const fs::path out = dir / "merged.exr";
    const fs::path png = dir / "merged.png";
    const auto j = json_of(run("merge" + list(parts) + " --out " + out.string() + " --png " + png.string() + " --json"));
    EXPECT_EQ(j["count"], n);
    EXPECT_EQ(j["split"], split);
    EXPECT_EQ(j["spp"], 16);
    EXPECT_EQ(j["nonfinite_samples"], 0);
    EXPECT_TRUE(bytes(out) == want) << split << " " << n;
    EXPECT_TRUE(fs::exists(png));
  }
}

// A missing, duplicated or foreign part: one line naming the file, exit 2, nothing written.
TEST(CliMerge, BadPartSetsAreUsageErrorsAndWriteNothing) {
  const fs::path dir = temp_dir() / "bad";
  fs::create_directories(dir);
  std::vector<fs::path> parts;
  for (int i = 0; i < 3; ++i) parts.push_back(shard(dir, i, 3, "samples", 1));
  const fs::path foreign = dir / "foreign.exr";
  ASSERT_EQ(run("render " + scene + " --shard 1/3 --seed 8 --out " + foreign.string()).code, 0);
  const fs::path out = dir / "merged.exr";
  const std::string o = " --out " + out.string() + " --png " + (dir / "merged.png").string();
  expect_usage_error("merge " + parts[0].string() + " " + parts[2].string() + o, "1 of 3 shards missing (index 1)");
  expect_usage_error("merge" + list(parts) + " " + parts[1].string() + o, "'" + parts[1].string() + "': shard 1/3 again");
  expect_usage_error("merge " + parts[0].string() + " " + foreign.string() + " " + parts[2].string() + o,
                     "'" + foreign.string() + "': from another render: seed 8, but 7");
  expect_usage_error("merge " + parts[0].string() + " " + (dir / "nothing.exr").string() + o, "nothing.exr': no such file");
  expect_usage_error("merge" + list(parts) + " --out " + parts[0].string(), "--out");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir / "merged.png"));
  // --check reports progress: exit 1 while shards are missing, 0 when all are there.
  const auto partial = run("merge --check " + parts[0].string() + " " + parts[2].string() + " --json");
  EXPECT_EQ(partial.code, 1);
  const auto j = nlohmann::json::parse(partial.out);
  EXPECT_EQ(j["present"], nlohmann::json::array({0, 2}));
  EXPECT_EQ(j["missing"], nlohmann::json::array({1}));
  EXPECT_EQ(j["complete"], false);
  EXPECT_EQ(json_of(run("merge --check" + list(parts) + " --json"))["complete"], true);
  // Bad --shard and --split values.
  expect_usage_error("render " + scene + " --shard 3/3 --out " + (dir / "x.exr").string(), "--shard: I = 3 must be below N = 3");
  expect_usage_error("render " + scene + " --shard 1 --out " + (dir / "x.exr").string(), "--shard: '1' is not I/N");
  expect_usage_error("render " + scene + " --shard -1/3 --out " + (dir / "x.exr").string(), "--shard: '-1/3' is not I/N");
  expect_usage_error("render " + scene + " --shard 0/0 --out " + (dir / "x.exr").string(), "--shard: N = 0 must be in [1, 100000]");
  expect_usage_error("render " + scene + " --shard 0/2 --split rows --out " + (dir / "x.exr").string(), "--split: 'rows'");
  expect_usage_error("render " + scene + " --split tiles --out " + (dir / "x.exr").string(), "--split applies to --shard");
  expect_usage_error("render " + scene + " --shard 0/2 --aov --out " + (dir / "x.exr").string(), "--shard: AOVs");
  expect_usage_error("render " + scene + " --shard 0/2 --mode game --out " + (dir / "x.exr").string(), "--shard: only the path tracer");
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

// Resume: a part that exists and is this very shard is skipped; another shard's file there is rendered again.
TEST(CliMerge, ExistingValidPartsAreSkipped) {
  const fs::path dir = temp_dir() / "resume";
  fs::create_directories(dir);
  const fs::path p = shard(dir, 0, 2, "tiles", 1);
  const auto before = fs::last_write_time(p);
  const auto again = json_of(run("render " + scene + " --shard 0/2 --split tiles --out " + p.string() + " --json"));
  EXPECT_EQ(again["skipped"], true);
  EXPECT_EQ(fs::last_write_time(p), before);
  // The same file name asked to hold shard 1: not skipped, replaced by shard 1.
  const auto other = run("render " + scene + " --shard 1/2 --split tiles --out " + p.string() + " --json");
  EXPECT_EQ(other.code, 0) << other.err;
  EXPECT_EQ(nlohmann::json::parse(other.out)["skipped"], false);
  EXPECT_NE(other.err.find("rendering it again"), std::string::npos) << other.err;
  const auto check = run("merge --check " + p.string() + " --json");
  EXPECT_EQ(check.code, 1);  // shard 0 is missing now
  EXPECT_EQ(nlohmann::json::parse(check.out)["present"], nlohmann::json::array({1}));
}

// A part that holds non-finite samples (NaN or infinite radiance, left out of the sums) makes a wrong image:
// merge still writes it but says so on stderr and in --json and exits 1, and a resumed shard that finds such
// a part in place says the same (exit 1) instead of a silent skip. No scene file renders NaN today (issue 16
// refuses every known way), so the test writes the part itself: shard 0's own sums and header with pixel 7
// counting 2 non-finite samples (the library's writer, so the header and the channel agree).
TEST(CliMerge, NonFiniteSamplesInAPartAreReportedAndExitOne) {
  const fs::path dir = temp_dir() / "nonfinite";
  fs::create_directories(dir);
  const fs::path p0 = shard(dir, 0, 2, "samples", 1);
  const fs::path p1 = shard(dir, 1, 2, "samples", 1);
  auto info = shadelab::read_shard_info(p0);
  ASSERT_TRUE(info) << info.error().message;
  auto sums = shadelab::read_shard_sums(p0, *info);
  ASSERT_TRUE(sums) << sums.error().message;
  shadelab::RenderResult r;
  r.sums = sums->sums;
  r.nonfinite = sums->nonfinite;
  r.nonfinite[7] += 2;
  r.beauty = shadelab::image_from_sums(r.sums, r.nonfinite, info->width, info->height,
                                       static_cast<std::uint64_t>(info->spp));
  info->nonfinite_samples = 2;
  ASSERT_TRUE(shadelab::write_shard(p0, *info, r));
  const fs::path out = dir / "merged.exr";
  const auto m = run("merge " + p0.string() + " " + p1.string() + " --out " + out.string() + " --json");
  EXPECT_EQ(m.code, 1) << m.err;
  EXPECT_EQ(nlohmann::json::parse(m.out)["nonfinite_samples"], 2);
  EXPECT_NE(m.err.find("2 samples were NaN or infinite"), std::string::npos) << m.err;
  EXPECT_TRUE(fs::exists(out));
  const auto plain = run("merge " + p0.string() + " " + p1.string() + " --out " + out.string());
  EXPECT_EQ(plain.code, 1);
  EXPECT_NE(plain.err.find("2 samples were NaN or infinite"), std::string::npos) << plain.err;
  // Resume finds the part in place: skipped, but not silently.
  const auto again = run("render " + scene + " --shard 0/2 --split samples --out " + p0.string() + " --json");
  EXPECT_EQ(again.code, 1) << again.err;
  EXPECT_EQ(nlohmann::json::parse(again.out)["skipped"], true);
  EXPECT_EQ(nlohmann::json::parse(again.out)["nonfinite_samples"], 2);
  EXPECT_NE(again.err.find("holds 2 samples that were NaN or infinite"), std::string::npos) << again.err;
  const auto quiet = run("render " + scene + " --shard 0/2 --split samples --out " + p0.string());
  EXPECT_EQ(quiet.code, 1);
  EXPECT_NE(quiet.err.find("holds 2 samples that were NaN or infinite"), std::string::npos) << quiet.err;
}

}  // namespace
