// End-to-end tests of `shadelab render` (both modes) and `shadelab report`.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>
#include <sys/wait.h>

#include "cli_run.h"
#include "shadelab/image/image.h"
#include "shadelab/image/image_io.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

const std::string furnace = std::string(SHADELAB_SCENES_DIR) + "/furnace.json";

TEST(CliRender, ReferenceAndGameModesWriteImages) {
  for (const char* mode : {"reference", "game"}) {
    const fs::path out = temp_dir() / (std::string(mode) + ".exr");
    const auto j = json_of(run("render " + furnace + " --mode " + mode + " --spp 2 --out " + out.string() + " --aov --json"));
    EXPECT_EQ(j["mode"], mode);
    const auto img = shadelab::read_image(out);
    ASSERT_TRUE(img.has_value()) << img.error().message;
    EXPECT_GT(img->width, 0);
    EXPECT_TRUE(fs::exists(temp_dir() / (std::string(mode) + ".png")));
  }
  EXPECT_TRUE(fs::exists(temp_dir() / "reference.normal.exr"));
}

TEST(CliRender, SameImageForAnyThreadCount) {
  const fs::path a = temp_dir() / "t1.exr";
  const fs::path b = temp_dir() / "t2.exr";
  ASSERT_EQ(run("render " + furnace + " --spp 2 --threads 1 --no-png --out " + a.string()).code, 0);
  ASSERT_EQ(run("render " + furnace + " --spp 2 --threads 2 --no-png --out " + b.string()).code, 0);
  EXPECT_EQ(shadelab::read_image(a)->data, shadelab::read_image(b)->data);
}

TEST(CliRender, BadInput) {
  expect_usage_error("render /nonexistent/scene.json", "/nonexistent/scene.json");
  expect_usage_error("render " + furnace + " --mode cartoon", "--mode");
  expect_usage_error("render " + furnace + " --spp 0", "--spp");
  expect_usage_error("render " + furnace + " --out x.png", "--out");
  expect_usage_error("render " + furnace + " --sampling random", "--sampling");
  expect_usage_error("render " + furnace + " --sampler halton", "--sampler");
  const fs::path bad = temp_dir() / "bad.json";
  std::ofstream(bad) << R"({"shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": -2, "material": "x"}]})";
  expect_usage_error("render " + bad.string(), "/shapes/0/radius");
}

// A ggx sphere (kd 0, roughness 0.6) under a lat-long whose radiance varies with direction: game mode's
// --ggx-specular and --split-sum-lookup reach the renderer (each changes the image), the default is the split
// sum with the lobes lookup, --json names each material's specular ambient, and misplaced or unknown values are
// one line and exit 2.
TEST(CliRender, GgxSpecularSplitSumAndItsLookup) {
  const fs::path env = temp_dir() / "gradient_env.exr";
  shadelab::Image sky(32, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) sky.set(x, y, {0.2 + 3.0 * (16 - y) / 16.0, 0.5 + x / 32.0, 0.3});
  ASSERT_TRUE(shadelab::write_image(sky, env).has_value());
  const fs::path scene = temp_dir() / "ggx_sphere.json";
  std::ofstream(scene) << R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 32, "width": 24, "height": 24},
    "materials": {"m": {"model": "ggx", "params": {"kd": 0, "roughness": 0.6}}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
    "environment": {"file": ")" + env.string() + R"("}})";
  const auto render = [&](const std::string& flags, const std::string& name) {
    const fs::path out = temp_dir() / name;
    const auto r = run("render " + scene.string() + " --mode game --spp 1 --specular-size 16 --no-png --out " +
                       out.string() + flags);
    EXPECT_EQ(r.code, 0) << r.err;
    return shadelab::read_image(out).value().data;
  };
  const auto by_default = render("", "ggx_default.exr");
  const auto phong = render(" --ggx-specular phong", "ggx_phong.exr");
  const auto split = render(" --ggx-specular split-sum", "ggx_split.exr");
  const auto lobes = render(" --ggx-specular split-sum --split-sum-lookup lobes", "ggx_lobes.exr");
  const auto mirror = render(" --ggx-specular split-sum --split-sum-lookup mirror", "ggx_mirror.exr");
  const auto filtered = render(" --ggx-specular split-sum --split-sum-lookup filtered", "ggx_filtered.exr");
  const auto filtered64 = render(" --ggx-specular split-sum --split-sum-lookup filtered --split-sum-taps 64", "ggx_f64.exr");
  const auto filtered8 = render(" --ggx-specular split-sum --split-sum-lookup filtered --split-sum-taps 8", "ggx_f8.exr");
  EXPECT_NE(phong, split);
  EXPECT_EQ(by_default, lobes);  // the split sum with the lobes lookup is the default
  EXPECT_EQ(split, lobes);  // lobes is the default lookup
  EXPECT_NE(lobes, mirror);
  EXPECT_NE(lobes, filtered);
  EXPECT_EQ(filtered, filtered64);  // 64 taps by default
  EXPECT_NE(filtered, filtered8);
  expect_usage_error("render " + scene.string() + " --ggx-specular split-sum", "--ggx-specular applies to --mode game");
  expect_usage_error("render " + scene.string() + " --mode game --ggx-specular ggx", "--ggx-specular: 'ggx' is not one of");
  expect_usage_error("render " + scene.string() + " --mode game --ggx-specular phong --split-sum-lookup mirror",
                     "--split-sum-lookup applies to --ggx-specular split-sum");
  // --json: each material's specular ambient, and the lookup of a split-sum one.
  const std::vector<std::pair<std::string, std::string>> json_cases{{"", "split-sum"}, {" --ggx-specular phong", "phong-chain"}};
  for (const auto& [flags, want] : json_cases) {
    const auto r = run("render " + scene.string() + " --mode game --spp 1 --specular-size 16 --no-png --json --out " +
                       (temp_dir() / "ggx_json.exr").string() + flags);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j.at("materials").size(), 1u) << r.out;
    EXPECT_EQ(j["materials"][0].at("material"), "m");
    EXPECT_EQ(j["materials"][0].at("model"), "ggx");
    EXPECT_EQ(j["materials"][0].at("specular_ambient"), want) << flags;
    EXPECT_EQ(j["materials"][0].contains("split_sum_lookup"), want == "split-sum");
  }
  expect_usage_error("render " + scene.string() + " --mode game --ggx-specular split-sum --split-sum-lookup up",
                     "--split-sum-lookup: 'up' is not one of");
  expect_usage_error("render " + scene.string() + " --mode game --ggx-specular split-sum --split-sum-taps 8",
                     "--split-sum-taps applies to --split-sum-lookup filtered");
  expect_usage_error("render " + scene.string() + " --mode game --ggx-specular split-sum --split-sum-lookup filtered "
                     "--split-sum-taps 0", "--split-sum-taps: 0 is out of range [1, 1024]");
}

TEST(CliRender, InterruptWritesThePartialImage) {
  // SIGINT after 2 s of a render that would take far longer: exit code 130 and the accumulated image on disk.
  const fs::path out = temp_dir() / "interrupted.exr";
  const std::string cmd = "timeout --preserve-status -s INT 2 " + std::string(SHADELAB_EXE) + " render " + furnace +
                          " --spp 1000000 --out " + out.string() + " --json > " + (temp_dir() / "int.json").string() + " 2>/dev/null";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const auto img = shadelab::read_image(out);
  ASSERT_TRUE(img.has_value()) << img.error().message;
  std::ifstream f(temp_dir() / "int.json");
  const auto j = nlohmann::json::parse(f, nullptr, false);
  ASSERT_FALSE(j.is_discarded());
  EXPECT_TRUE(j["interrupted"].get<bool>());
  EXPECT_GT(j["spp"].get<int>(), 0);
  EXPECT_LT(j["spp"].get<int>(), 1000000);
}

TEST(CliReport, WritesAPageWithThreeLightings) {
  const fs::path dir = temp_dir() / "report";
  const auto j = json_of(run("report " + furnace + " --spp 2 --width 32 --out " + dir.string() + " --json"));
  ASSERT_EQ(j["sections"].size(), 3u);
  EXPECT_TRUE(fs::exists(dir / "index.html"));
  EXPECT_TRUE(fs::exists(dir / "full_heatmap.png"));
  std::ifstream f(dir / "index.html");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string html = ss.str();
  EXPECT_NE(html.find("<table>"), std::string::npos);
  EXPECT_NE(html.find("environment_game.png"), std::string::npos);
  // LDR-FLIP beside SSIM (image/flip.h): in [0, 1], per section and per material, and its map.
  EXPECT_TRUE(fs::exists(dir / "full_flip.png"));
  for (const auto& s : j["sections"]) {
    EXPECT_GE(s["flip"].get<double>(), 0.0);
    EXPECT_LE(s["flip"].get<double>(), 1.0);
    EXPECT_GT(s["heat_scale"].get<double>(), 0.0);
    for (const auto& m : s["materials"]) EXPECT_TRUE(m.contains("flip")) << m;
  }
}

TEST(CliReport, IblErrorAddsTheMapOfTheEnvironment) {
  // The furnace's uniform environment: the split sum is exact there but for its table, along R or the dominant
  // direction alike, and SH9 of a constant is exact, so the mean errors are the reference's noise (4 spp).
  const fs::path dir = temp_dir() / "report_ibl";
  const auto j = json_of(run("report " + furnace + " --spp 4 --width 32 --ibl-error --out " + dir.string() + " --json"));
  ASSERT_TRUE(j.contains("ibl_error")) << j;
  EXPECT_TRUE(fs::exists(dir / "ibl_error" / "index.html"));
  EXPECT_TRUE(fs::exists(dir / "ibl_error" / "corrected_error.png"));
  EXPECT_LT(j["ibl_error"]["split_sum"]["mean_abs_error"].get<double>(), 0.03) << j["ibl_error"];
  EXPECT_LT(j["ibl_error"]["corrected"]["mean_abs_error"].get<double>(), 0.03) << j["ibl_error"];
  EXPECT_LT(j["ibl_error"]["sh"]["mean_abs_error"].get<double>(), 0.03) << j["ibl_error"];
  std::ifstream f(dir / "index.html");
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_NE(ss.str().find("ibl_error/index.html"), std::string::npos);
  // The page's figures carry the JSON's values (report_page.h exact_number; the browser test checks the rest).
  for (const char* key : {"split_sum", "corrected", "sh"}) {
    const std::string ptr = std::string("/ibl_error/") + key + "/mean_abs_error";
    const std::string attr = "data-json=\"" + ptr + "\" data-value=\"";
    const std::size_t at = ss.str().find(attr);
    ASSERT_NE(at, std::string::npos) << ptr;
    const std::size_t from = at + attr.size();
    const double shown = std::stod(ss.str().substr(from, ss.str().find('"', from) - from));
    EXPECT_EQ(shown, j.at(nlohmann::json::json_pointer(ptr)).get<double>()) << ptr;
  }
  // A scene without an environment: one line, exit 2, nothing written.
  const std::string none = std::string(SHADELAB_SCENES_DIR) + "/cornell.json";  // no environment
  const fs::path bad = temp_dir() / "report_ibl_bad";
  const auto r = run("report " + none + " --ibl-error --out " + bad.string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--ibl-error: the scene"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(bad / "index.html"));
}

}  // namespace
