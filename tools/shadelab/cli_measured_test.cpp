// Issue 41's `measure`: the virtual gonioreflectometer writes a MERL file that the reader takes back, with the
// model's values at the bin centres; bad input is one line and exit 2, with no file left behind. The registry's
// `measured` model reads such a file everywhere a model is named: `brdf eval` / `albedo`, `brdf list`, scenes and
// the path tracer; `shader` refuses it in one line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/core/constants.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;
using testing::json_of;
using testing::run;
using testing::temp_dir;

TEST(CliMeasured, MeasureWritesAMerlFileTheReaderTakesBack) {
  const fs::path out = temp_dir() / "lambert.binary";
  const auto j = json_of(run("measure lambert --param kd=0.5,0.25,0.125 --out " + out.string() + " --json"));
  EXPECT_EQ(j["format"], "merl");
  EXPECT_EQ(j["model"], "lambert");
  EXPECT_EQ(j["params"]["kd"], "0.5,0.25,0.125");
  EXPECT_EQ(j["bins"], 1458000);
  EXPECT_EQ(j["bytes"], 34992012);
  EXPECT_EQ(fs::file_size(out), 34992012u);
  const auto t = read_merl(out);
  ASSERT_TRUE(t.has_value()) << t.error().message;
  std::size_t measured = 0;
  for (std::size_t i = 0; i < MerlTable::count; ++i) {
    if (t->value(0, i) < 0.0) continue;
    ++measured;
    ASSERT_NEAR(t->value(0, i), 0.5 * inv_pi, 1e-15) << i;
    ASSERT_NEAR(t->value(2, i), 0.125 * inv_pi, 1e-15) << i;
  }
  EXPECT_EQ(j["measured_bins"], measured);
  EXPECT_EQ(measured, 1458000u - 361784u);
}

TEST(CliMeasured, BadInputIsOneLineAndExitTwo) {
  const fs::path out = temp_dir() / "bad.binary";
  for (const std::string& args : {"measure no-such-model --out " + out.string(), "measure ggx --param roughness=7 --out " + out.string(),
                                  "measure ggx --format utia --out " + out.string(),
                                  "measure ggx --out " + (temp_dir() / "x.exr").string()}) {
    const auto r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
}

// The source model of the measured file the tests below read, and the file, written once per test process by
// `measure` (about 1 s).
const std::string source_params = "--param roughness=0.4 --param kd=0.3 --param f0=0.9,0.6,0.3";
const fs::path& measured_file() {
  static const fs::path path = [] {
    const fs::path p = temp_dir() / "ggx.binary";
    const auto r = run("measure ggx " + source_params + " --out " + p.string());
    EXPECT_EQ(r.code, 0) << r.err;
    return p;
  }();
  return path;
}

std::string vec_text(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", v.x, v.y, v.z);
  return buf;
}

TEST(CliMeasured, BrdfEvalOfAMeasuredFileIsTheSourceModelAtBinCentres) {
  const std::string file = " --param file=" + measured_file().string();
  int compared = 0;
  for (const auto& [i, j, k] : {std::array{3, 10, 20}, std::array{40, 30, 90}, std::array{70, 60, 150}, std::array{15, 5, 0},
                                std::array{60, 20, 45}, std::array{30, 45, 100}}) {
    const auto [wi, wo] = half_diff_directions(merl_bin_centre(i, j, k));
    if (!(wi.z > 0.01 && wo.z > 0.01)) continue;  // not measured: below the horizon
    const std::string dirs = " --wi " + vec_text(wi) + " --wo " + vec_text(wo) + " --json";
    const auto got = json_of(run("brdf eval measured" + file + dirs));
    const auto want = json_of(run("brdf eval ggx " + source_params + dirs));
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(got["f"][c].get<double>(), want["f"][c].get<double>(), 1e-9 * want["f"][c].get<double>()) << i << " " << j << " " << k;
    }
    ++compared;
  }
  EXPECT_GE(compared, 4);
  // The analysis commands take it as any model: its directional albedo at 30 degrees is the source's within the
  // interpolation between bin centres (measured: 0.4% in green).
  const auto a = json_of(run("brdf albedo measured" + file + " --theta 30 --json"));
  const auto b = json_of(run("brdf albedo ggx " + source_params + " --theta 30 --json"));
  EXPECT_NEAR(a["albedo"][0][1].get<double>(), b["albedo"][0][1].get<double>(), 0.02 * b["albedo"][0][1].get<double>());
}

TEST(CliMeasured, BadMeasuredFilesAreOneLineNamingTheFileAndExitTwo) {
  const fs::path small = temp_dir() / "small.binary";
  std::string head(100, '\0');  // MERL's header {90, 90, 180} (little-endian int32), then too few values
  head[0] = 90;
  head[4] = 90;
  head[8] = static_cast<char>(180);
  std::ofstream(small, std::ios::binary) << head;
  const fs::path missing = temp_dir() / "missing.binary";
  const std::string dirs = " --wi 0,0,1 --wo 0,0.5,1";
  for (const auto& [args, want] : std::vector<std::pair<std::string, std::string>>{
           {"brdf eval measured" + dirs, "parameter 'file' is required"},
           {"brdf eval measured --param file=" + missing.string() + dirs, missing.string() + ": cannot read"},
           {"brdf eval measured --param file=" + small.string() + dirs, small.string() + ": 100 bytes, expected 34992012"},
           {"brdf albedo measured --param file=" + small.string(), small.string() + ": 100 bytes"},
           {"brdf check measured --param file=" + missing.string(), missing.string() + ": cannot read"},
           {"brdf eval measured --param file=" + dirs, "parameter 'file' is an empty path"},
           {"brdf eval measured --param n=3" + dirs, "unknown parameter 'n'"}}) {
    const auto r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(want), std::string::npos) << args << ": " << r.err;
  }
}

TEST(CliMeasured, BrdfListShowsTheRequiredFileParameterAndShaderRefusesIt) {
  const auto j = json_of(run("brdf list --json"));
  bool found = false;
  for (const auto& m : j["models"]) {
    if (m["name"] != "measured") continue;
    found = true;
    ASSERT_EQ(m["params"].size(), 1u);
    EXPECT_EQ(m["params"][0]["name"], "file");
    EXPECT_EQ(m["params"][0]["kind"], "file");
    EXPECT_EQ(m["params"][0]["default"], "");
    EXPECT_EQ(m["params"][0]["required"], true);
  }
  EXPECT_TRUE(found);
  const auto text = run("brdf list");
  EXPECT_NE(text.out.find("  file           file    default (required)"), std::string::npos) << text.out;
  const auto r = run("shader measured --lang glsl --param file=" + (temp_dir() / "any.binary").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("model 'measured' has no shader: "), std::string::npos) << r.err;
}

// A scene of two spheres of the same measured file, named relative to the scene's folder (the test's working folder
// is another), renders; a scene naming a missing file is one line naming the scene, the field and the file.
TEST(CliMeasured, ASceneWithMeasuredSpheresRenders) {
  const fs::path dir = temp_dir() / "scene";
  fs::create_directories(dir);
  fs::copy_file(measured_file(), dir / "paint.binary", fs::copy_options::overwrite_existing);
  const std::string scene = R"({
    "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "fov": 40, "width": 24, "height": 16},
    "materials": {"paint": {"model": "measured", "params": {"file": "paint.binary"}},
                  "floor": {"model": "lambert", "params": {"kd": 0.5}}},
    "shapes": [{"type": "sphere", "center": [-0.6, 0.5, 0], "radius": 0.5, "material": "paint"},
               {"type": "sphere", "center": [0.6, 0.5, 0], "radius": 0.5, "material": "paint"},
               {"type": "quad", "corner": [-5, 0, 5], "u": [10, 0, 0], "v": [0, 0, -10], "material": "floor"}],
    "lights": [{"type": "point", "position": [2, 3, 2], "intensity": 20}],
    "environment": {"uniform": 0.3}
  })";
  std::ofstream(dir / "scene.json") << scene;
  const fs::path out = dir / "out.exr";
  const auto r = run("render " + (dir / "scene.json").string() + " --spp 4 --no-png --out " + out.string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out));
  std::string bad = scene;
  bad.replace(bad.find("paint.binary"), 12, "gone.binary");
  std::ofstream(dir / "bad.json") << bad;
  const auto b = run("render " + (dir / "bad.json").string() + " --spp 1 --no-png --out " + (dir / "bad.exr").string());
  EXPECT_EQ(b.code, 2);
  EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << b.err;
  EXPECT_NE(b.err.find("/materials/paint/params/file: file not found: '" + (dir / "gone.binary").string() + "'"), std::string::npos) << b.err;
  EXPECT_FALSE(fs::exists(dir / "bad.exr"));
}

}  // namespace
}  // namespace shadelab
