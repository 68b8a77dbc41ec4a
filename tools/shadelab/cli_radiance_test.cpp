// Environments with no light or with impossible light (issue 40, task 1; docs/testing.md "Classes of bad
// input"): an all-black map, a map with a black half, and a map with one negative or non-finite texel, through
// every command that reads an environment: ibl-error, bake irradiance | sh | specular | convert | ibl, and render
// with a scene's environment file.
// - A negative, NaN or Inf texel is bad input: one line naming the file, the texel and its channel, exit 2,
//   nothing written.
// - ibl-error: a black map is an error (no cell has signal); a half-black one is measured, its cells' errors
//   finite (a cell with no signal would be flagged, never scored 0).
// - The bakes and render take black and half-black maps: black light is light.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_run.h"
#include "shadelab/image/image_io.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

// A 32 x 16 lat-long EXR: `value` everywhere, the bottom half (the lower hemisphere) `lower`.
fs::path latlong(const std::string& name, double value, double lower) {
  shadelab::Image img(32, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) img.set(x, y, shadelab::Rgb::gray(y < 8 ? value : lower));
  const fs::path p = temp_dir() / name;
  EXPECT_TRUE(shadelab::write_image(img, p).has_value());
  return p;
}

// 0.5 everywhere but texel (5, 3), channel G.
fs::path one_bad_texel(const std::string& name, float bad) {
  shadelab::Image img(32, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) img.set(x, y, shadelab::Rgb::gray(0.5));
  img.data[3 * (3 * 32 + 5) + 1] = bad;
  const fs::path p = temp_dir() / name;
  EXPECT_TRUE(shadelab::write_image(img, p).has_value());
  return p;
}

fs::path scene_with_environment(const fs::path& env, const std::string& name) {
  const fs::path scene = temp_dir() / name;
  std::ofstream(scene) << R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 32, "width": 8, "height": 8},
    "materials": {"m": {"model": "lambert"}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
    "environment": {"file": ")" + env.string() + R"("}})";
  return scene;
}

const std::string quick = " --roughness 0.5 --bins 4 --size 32 --spp 4 --threads 2 --specular-size 8";

// Every command that reads an environment, for an input map: the argument lists (output names by `tag`).
std::vector<std::string> environment_commands(const fs::path& in, const std::string& tag) {
  const std::string d = (temp_dir() / tag).string();
  return {"ibl-error " + in.string() + quick + " --out " + d + "_ibl_error",
          "bake irradiance " + in.string() + " --size 4 --out " + d + "_irr.exr",
          "bake sh " + in.string() + " --out " + d + "_sh.json",
          "bake specular " + in.string() + " --lobe ggx --size 4 --out " + d + "_spec.ktx2",
          "bake specular " + in.string() + " --size 4 --out " + d + "_phong.ktx2",
          "bake convert " + in.string() + " --out " + d + "_cross.exr",
          "bake ibl " + in.string() + " --out-dir " + d + "_ibl --size 4 --levels 2 --irradiance-size 2 --dfg-size 2",
          "render " + scene_with_environment(in, tag + "_scene.json").string() + " --spp 1 --no-png --out " + d +
              "_render.exr",
          "render " + scene_with_environment(in, tag + "_scene.json").string() + " --mode game --no-png --out " + d +
              "_game.exr"};
}

TEST(CliRadiance, NegativeOrNonFiniteTexelsAreErrorsNamingTheTexel) {
  const fs::path negative = one_bad_texel("negative.exr", -0.25f);
  for (const std::string& args : environment_commands(negative, "neg")) {
    SCOPED_TRACE(args);
    expect_usage_error(args, "negative.exr': texel (5, 3) channel G is -0.25");
  }
  for (const fs::path& p : fs::directory_iterator(temp_dir())) {
    const std::string f = p.filename().string();
    if (f.rfind("neg_", 0) == 0 && f != "neg_scene.json") ADD_FAILURE() << "written: " << p;
  }
  const fs::path nan = one_bad_texel("nan.exr", std::nanf(""));
  expect_usage_error("bake sh " + nan.string(), "nan.exr': texel (5, 3) channel G is NaN");
  expect_usage_error("ibl-error " + nan.string() + quick + " --out " + (temp_dir() / "nan_ibl").string(),
                     "texel (5, 3) channel G is NaN");
  const fs::path inf = one_bad_texel("inf.exr", INFINITY);
  expect_usage_error("bake irradiance " + inf.string() + " --size 4 --out " + (temp_dir() / "inf_irr.exr").string(),
                     "texel (5, 3) channel G is +Inf");
  expect_usage_error("render " + scene_with_environment(inf, "inf_scene.json").string() + " --spp 1 --out " +
                         (temp_dir() / "inf_render.exr").string(),
                     "texel (5, 3) channel G is +Inf");
}

// Before issue 40: exit 0, "mean |error| 0.00%" (every cell scored as perfect).
TEST(CliRadiance, IblErrorOfABlackMapIsAnError) {
  const fs::path black = latlong("black.exr", 0.0, 0.0);
  const fs::path dir = temp_dir() / "black_ibl";
  expect_usage_error("ibl-error " + black.string() + quick + " --out " + dir.string(), "black.exr': every texel is 0");
  EXPECT_FALSE(fs::exists(dir));
}

TEST(CliRadiance, IblErrorMeasuresAHalfBlackMap) {
  const fs::path half = latlong("half_black.exr", 1.0, 0.0);
  const auto j = json_of(run("ibl-error " + half.string() + quick + " --out " + (temp_dir() / "half_ibl").string() +
                             " --json"));
  ASSERT_TRUE(j.is_object());
  int cells = 0;
  for (const auto* rows : {&j["split_sum"]["rows"], &j["corrected"]["rows"]}) {
    for (const auto& row : *rows) {
      for (const auto& c : row["cells"]) {
        if (c["pixels"] == 0) continue;
        ASSERT_TRUE(c.contains("no_signal")) << c;
        if (c["no_signal"].get<bool>()) {
          EXPECT_TRUE(c["error"].is_null()) << c;
        } else {
          EXPECT_GT(c["reference"].get<double>(), 0.0) << c;
          EXPECT_TRUE(std::isfinite(c["error"].get<double>())) << c;
          ++cells;
        }
      }
    }
  }
  EXPECT_GT(cells, 0);
  for (const char* map : {"split_sum", "corrected", "sh"}) {
    EXPECT_TRUE(j[map]["summary"].contains("no_signal_cells")) << map;
    EXPECT_TRUE(j[map]["summary"].contains("mean_abs_error")) << map;
  }
  for (const auto& c : j["sh"]["cells"]) {
    if (c["pixels"] == 0) continue;
    EXPECT_GT(c["reference"].get<double>(), 0.0) << c;  // a Lambert sphere seen from the horizon sees the lit half
  }
}

// Black light is light: the bakes and render take black and half-black maps (exit 0, finite results).
TEST(CliRadiance, BakesAndRenderTakeBlackAndHalfBlackMaps) {
  for (const auto& [name, upper] : {std::pair<std::string, double>{"black", 0.0}, {"half", 1.0}}) {
    const fs::path in = latlong(name + "_in.exr", upper, 0.0);
    const std::vector<std::string> commands = environment_commands(in, name + "_ok");
    for (std::size_t i = 1; i < commands.size(); ++i) {  // all but ibl-error
      SCOPED_TRACE(commands[i]);
      const auto r = run(commands[i]);
      EXPECT_EQ(r.code, 0) << r.err;
    }
    const auto irr = shadelab::read_image(temp_dir() / (name + "_ok_irr.exr"));
    ASSERT_TRUE(irr.has_value());
    for (const float v : irr->data) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f) << v;
  }
}

}  // namespace
