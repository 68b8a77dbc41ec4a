// End-to-end tests of bad input through the CLI (issue 16): bounded options without sentinels, options that
// do not apply, outputs that would overwrite inputs, signals during a write, KTX clamping, messages, and the
// new outputs (non-finite sample counts, photometric luminance, SH lights, the wrapped-diffuse statement).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "shadelab/envmap/base/ktx.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/image/image_io.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

const std::string furnace = std::string(SHADELAB_SCENES_DIR) + "/furnace.json";

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A small scene: the furnace at 16 x 16.
fs::path small_scene() {
  const fs::path p = temp_dir() / "small.json";
  if (!fs::exists(p)) {
    std::ofstream(p) << R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "width": 16, "height": 16},
      "materials": {"white": {"model": "lambert", "params": {"kd": 1}}},
      "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}],
      "environment": {"uniform": 1}})";
  }
  return p;
}

// A 16 x 8 lat-long with one texel at `peak` (EXR float keeps it exactly).
fs::path latlong(const std::string& name, float peak) {
  const fs::path p = temp_dir() / name;
  shadelab::Image img(16, 8);
  for (float& v : img.data) v = 0.25f;
  img.data[3 * (3 * 16 + 5)] = peak;
  EXPECT_TRUE(shadelab::write_image(img, p));
  return p;
}

// issue 16, 1: --threads 100000 crashed inside TBB; any count above the cores printed a TBB warning.
TEST(CliHarden, ThreadCountsAreBoundedAndNeverWarn) {
  const std::string s = small_scene().string();
  expect_usage_error("render " + s + " --threads 100000", "--threads: 100000 is out of range [0, 4096]");
  expect_usage_error("render " + s + " --mode game --threads 100000", "--threads");
  expect_usage_error("sheet lambert --threads 100000 --out " + (temp_dir() / "s.png").string(), "--threads");
  for (const char* mode : {"reference", "game"}) {
    const auto r = run("render " + s + " --mode " + mode + " --spp 1 --threads 4096 --no-png --out " +
                       (temp_dir() / "t.exr").string());
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "") << "a thread count above the cores must not warn";
  }
}

// issue 16, 3: the undocumented -1 sentinels and out-of-range counts were taken without a word.
TEST(CliHarden, CountOptionsHaveNoSentinels) {
  const std::string s = small_scene().string();
  expect_usage_error("render " + s + " --spp -1", "--spp");
  expect_usage_error("render " + s + " --max-depth -1", "--max-depth");
  expect_usage_error("render " + s + " --threads -1", "--threads");
  expect_usage_error("render " + s + " --max-depth 100000", "--max-depth: 100000 is out of range [1, 1000]");
  expect_usage_error("render " + s + " --spp 2000000", "--spp");
  expect_usage_error("render " + s + " --seed -5", "--seed: '-5' is not an integer");
  expect_usage_error("render " + s + " --seed 18446744073709551616", "--seed");
  expect_usage_error("render " + s + " --seed 1.5", "--seed");
  const auto top = run("render " + s + " --spp 1 --no-png --seed 18446744073709551615 --out " + (temp_dir() / "seed.exr").string());
  EXPECT_EQ(top.code, 0) << top.err;
  const std::string env = latlong("counts.exr", 1.0f).string();
  expect_usage_error("bake irradiance " + env + " --size -1", "--size: -1 is out of range");
  expect_usage_error("bake specular " + env + " --gloss-scale 1e308", "--gloss-scale");
  expect_usage_error("bake specular " + env + " --gloss-bias -100", "--gloss-bias");
  expect_usage_error("bake specular " + env + " --mips -3", "--mips");
}

// issue 16, 3: options that do not apply were ignored; bake sh wrote JSON into a .exr.
TEST(CliHarden, BakeOptionsThatDoNotApplyAreRefused) {
  const std::string env = latlong("apply.exr", 1.0f).string();
  expect_usage_error("bake sh " + env + " --size 7 --layout vcross", "--size does not apply to bake sh");
  expect_usage_error("bake sh " + env + " --layout vcross", "--layout does not apply to bake sh");
  expect_usage_error("bake specular " + env + " --layout star", "--layout does not apply to bake specular");
  expect_usage_error("bake specular " + env + " --units game", "--units does not apply to bake specular");
  expect_usage_error("bake convert " + env + " --units game --out " + (temp_dir() / "c.exr").string(), "--units does not apply");
  expect_usage_error("bake sh " + env + " --out " + (temp_dir() / "sh.exr").string(), "--out: the SH9 coefficients (JSON) must be written to a .json file");
  expect_usage_error("bake sh " + env + " --out " + (temp_dir() / "sh.txt").string(), ".json");
  expect_usage_error("bake irradiance " + env + " --layout vcross --out " + (temp_dir() / "i.ktx").string(), "--layout does not apply to a .ktx output");
  expect_usage_error("bake irradiance " + env + " --out " + (temp_dir() / "i.txt").string(), "--out");
  expect_usage_error("bake sh " + env + " --light-normalization delta", "no --light was given");
  EXPECT_FALSE(fs::exists(temp_dir() / "sh.exr"));
  // convert to KTX says what it wrote, not "as hcross".
  const auto r = run("bake convert " + env + " --out " + (temp_dir() / "c.ktx").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("as a KTX cube map"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("hcross"), std::string::npos) << r.out;
}

// issue 16, 4: an output equal to an input replaced it (bake sh in.hdr --out in.hdr, compare --heatmap a.png,
// render --out x.exr --png x.exr). Every such output is refused and the input is left as it was.
TEST(CliHarden, OutputsThatAreInputsAreRefused) {
  const fs::path env = latlong("input.exr", 1.0f);
  const std::string before = bytes_of(env);
  expect_usage_error("bake irradiance " + env.string() + " --out " + env.string(), "is the input INPUT");
  expect_usage_error("bake convert " + env.string() + " --out " + (temp_dir() / "." / "input.exr").string(), "is the input");
  expect_usage_error("bake sh " + env.string() + " --out " + env.string(), "--out");
  fs::create_symlink(env, temp_dir() / "link.exr");
  expect_usage_error("bake irradiance " + env.string() + " --out " + (temp_dir() / "link.exr").string(), "is the input");
  EXPECT_EQ(bytes_of(env), before);

  const fs::path a = temp_dir() / "a.png";
  const fs::path b = temp_dir() / "b.png";
  ASSERT_TRUE(shadelab::write_image(shadelab::Image(4, 4), a));
  ASSERT_TRUE(shadelab::write_image(shadelab::Image(4, 4), b));
  const std::string a_bytes = bytes_of(a);
  expect_usage_error("compare " + a.string() + " " + b.string() + " --heatmap " + a.string(), "--heatmap");
  expect_usage_error("compare " + a.string() + " " + b.string() + " --heatmap " + (temp_dir() / "h.png").string() +
                         " --side-by-side " + (temp_dir() / "h.png").string(),
                     "also the output of --heatmap");
  EXPECT_EQ(bytes_of(a), a_bytes);

  const std::string s = small_scene().string();
  expect_usage_error("render " + s + " --out " + (temp_dir() / "x.exr").string() + " --png " + (temp_dir() / "x.exr").string(),
                     "--png: the tone-mapped image must be written to a .png file");
  // The scene's own environment map as the output.
  const fs::path scene = temp_dir() / "env_scene.json";
  std::ofstream(scene) << R"({"camera": {"width": 8, "height": 8}, "environment": {"file": "input.exr"}})";
  expect_usage_error("render " + scene.string() + " --out " + env.string(), "is the input the scene's environment");
  expect_usage_error("render " + scene.string() + " --out " + scene.string(), "--out");
  EXPECT_EQ(bytes_of(env), before);
}

// issue 16, 3: KTX output turned values above 65504 into +inf with exit 0. They are clamped and counted.
TEST(CliHarden, KtxOutputClampsAndSaysSo) {
  const fs::path bright = temp_dir() / "bright.exr";
  shadelab::Image sun(16, 8);
  for (float& v : sun.data) v = 2e5f;  // every texel beyond the half range
  ASSERT_TRUE(shadelab::write_image(sun, bright));
  const fs::path out = temp_dir() / "bright.ktx";
  const auto r = run("bake convert " + bright.string() + " --input-size 4 --out " + out.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("clamped to +-65504"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["clamped_values"].get<int>(), 0);
  const std::string text = bytes_of(out);
  const std::vector<char> bytes(text.begin(), text.end());
  const auto levels = shadelab::decode_ktx_cubemap(bytes);
  ASSERT_TRUE(levels) << levels.error().message;
  float peak = 0.0f;
  for (const auto& face : (*levels)[0].faces) {
    for (float v : face.data) {
      EXPECT_TRUE(std::isfinite(v));
      peak = std::max(peak, v);
    }
  }
  EXPECT_EQ(peak, 65504.0f);
}

// issue 16, 4: Ctrl-C or SIGTERM while writing lost the image. SIGTERM is handled like SIGINT (exit 143),
// the handler stays through the write, and no temporary is left.
TEST(CliHarden, SigtermWritesThePartialImage) {
  const fs::path dir = temp_dir() / "term";
  fs::create_directories(dir);
  const fs::path out = dir / "term.exr";
  std::ofstream(dir / ".term.exr.tmp-4194999-0-1") << "stale";  // left by a dead process: removed
  const std::string cmd = "timeout --preserve-status -s TERM 2 " + std::string(SHADELAB_EXE) + " render " + furnace +
                          " --spp 1000000 --out " + out.string() + " --json > " + (dir / "term.json").string() + " 2>/dev/null";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 143);
  EXPECT_TRUE(shadelab::read_image(out).has_value());
  EXPECT_TRUE(shadelab::read_image(dir / "term.png").has_value());
  for (const auto& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  }
  std::ifstream f(dir / "term.json");
  const auto j = nlohmann::json::parse(f, nullptr, false);
  ASSERT_FALSE(j.is_discarded());
  EXPECT_TRUE(j["interrupted"].get<bool>());
}

// issue 16, 5: a glTF syntax error included the whole base64 buffer, an unknown 100 KB name was echoed
// whole, raw control bytes reached stderr. Every message is one printable line of bounded length.
TEST(CliHarden, MessagesAreOnePrintableBoundedLine) {
  const fs::path dir = temp_dir() / "messages";
  fs::create_directories(dir);
  std::ofstream(dir / "bad.gltf") << "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"uri\": "
                                     "\"data:application/octet-stream;base64," + std::string(1163, 'A') + "\"}]]";
  std::ofstream(dir / "gltf.json") << R"({"materials": {"m": {"model": "lambert"}}, "shapes": [{"type": "mesh", "file": "bad.gltf", "material": "m"}]})";
  std::ofstream(dir / "long.json") << R"({"materials": {"m": {"model": "lambert"}}, "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": ")"
                                   << std::string(100000, 'q') << R"("}]})";
  std::ofstream(dir / "control.json") << R"({"materials": {"m\u001b[31m\u0007": {"model": "lambert"}}, "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "x\u001b]0;title\u0007"}]})";
  for (const char* name : {"gltf.json", "long.json", "control.json"}) {
    const auto r = run("render " + (dir / name).string() + " --out " + (dir / "o.exr").string());
    EXPECT_EQ(r.code, 2) << name << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << name;
    EXPECT_LE(r.err.size(), 1100u) << name << ": " << r.err.size() << " bytes";
    for (std::size_t i = 0; i + 1 < r.err.size(); ++i) {
      const auto c = static_cast<unsigned char>(r.err[i]);
      EXPECT_FALSE(c < 0x20 || c == 0x7f) << name << ": raw byte " << static_cast<int>(c) << " at " << i;
    }
  }
  // An unknown command of 100 KB is cut too.
  const auto r = run(std::string(100000, 'z'));
  EXPECT_EQ(r.code, 2);
  EXPECT_LE(r.err.size(), 1100u);
}

// issue 16, 3: a render reports its non-finite samples in --json (0 for a sound scene).
TEST(CliHarden, RenderJsonCountsNonFiniteSamples) {
  for (const char* mode : {"reference", "game"}) {
    const auto j = json_of(run("render " + small_scene().string() + " --mode " + mode + " --spp 1 --no-png --json --out " +
                               (temp_dir() / "nf.exr").string()));
    ASSERT_TRUE(j.contains("nonfinite_samples")) << mode;
    EXPECT_EQ(j["nonfinite_samples"].get<int>(), 0) << mode;
  }
}

// issue 16, 7: an RGB photometric conversion printed only the per-channel vector (683, 0, 0 lux); the
// illuminance is 683 Y. Both are printed and named; the JSON keeps "value" and adds the luminance.
TEST(CliHarden, LightPrintsTheLuminanceBesideThePerChannelVector) {
  const auto j = json_of(run("light 1,0,0 --from W/m2 --to lux --json"));
  EXPECT_EQ(j["value"], nlohmann::json::array({683.0, 0.0, 0.0}));
  EXPECT_EQ(j["unit"], "lux");
  EXPECT_NEAR(j["luminance"].get<double>(), 683.0 * 0.2126, 1e-9);  // Rec.709 Y of the red primary
  EXPECT_NEAR(j["photometric"]["value"].get<double>(), 683.0 * 0.2126, 1e-9);
  EXPECT_EQ(j["photometric"]["quantity"], "illuminance");
  EXPECT_EQ(j["photometric"]["unit"], "lux");
  // From game units of a point light to candela: I = pi c, so 683 pi Y.
  const auto cd = json_of(run("light 0,1,0 --from game-point --to W/sr --json"));
  EXPECT_NEAR(cd["photometric"]["value"].get<double>(), 683.0 * 3.141592653589793 * 0.7152, 1e-6);
  EXPECT_EQ(cd["photometric"]["unit"], "cd");
  const auto text = run("light 1,0,0 --from W/m2 --to lux");
  EXPECT_EQ(text.code, 0);
  EXPECT_NE(text.out.find("per channel"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("illuminance: 145.2058 lux"), std::string::npos) << text.out;
}

// issue 16, 7: the D3DX-style SH lights reach the CLI: bake sh --light adds them to the coefficients (a
// light of colour c gives exactly c facing it, 17/16 c without the D3DX scale), render --sh-lights to game mode.
TEST(CliHarden, BakeShAddsDirectionalLights) {
  const fs::path black = temp_dir() / "black.exr";
  ASSERT_TRUE(shadelab::write_image(shadelab::Image(16, 8), black));
  auto evaluate = [](const nlohmann::json& j, const shadelab::Vec3& n) {
    shadelab::Sh9 sh;
    for (std::size_t i = 0; i < 9; ++i) {
      const auto& c = j["irradiance_coefficients"][i];
      sh.c[i] = {c[0].get<double>(), c[1].get<double>(), c[2].get<double>()};
    }
    return shadelab::sh9_evaluate(sh, n);
  };
  const auto j = json_of(run("bake sh " + black.string() + " --light 0,1,0:0.5,1,2 --json"));
  const shadelab::Rgb facing = evaluate(j, {0.0, 1.0, 0.0});
  EXPECT_NEAR(facing.r, 0.5, 1e-9);
  EXPECT_NEAR(facing.g, 1.0, 1e-9);
  EXPECT_NEAR(facing.b, 2.0, 1e-9);
  EXPECT_EQ(j["lights"].size(), 1u);
  const auto delta = json_of(run("bake sh " + black.string() + " --light 0,2,0 --light-normalization delta --json"));
  EXPECT_NEAR(evaluate(delta, {0.0, 1.0, 0.0}).g, 17.0 / 16.0, 1e-9);
  // Two lights add.
  const auto two = json_of(run("bake sh " + black.string() + " --light 0,1,0 --light 0,1,0:2 --json"));
  EXPECT_NEAR(evaluate(two, {0.0, 1.0, 0.0}).g, 3.0, 1e-9);
  expect_usage_error("bake sh " + black.string() + " --light 0,0,0", "--light");
  expect_usage_error("bake sh " + black.string() + " --light 0,1,0:-1", "--light");

  const fs::path scene = temp_dir() / "sun.json";
  std::ofstream(scene) << R"({"camera": {"position": [0, 3, 0.01], "look_at": [0, 0, 0], "width": 8, "height": 8},
    "materials": {"m": {"model": "lambert", "params": {"kd": 1}}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
    "lights": [{"type": "directional", "direction": [0, 1, 0], "intensity": 1, "game": "sh"}]})";
  EXPECT_EQ(run("render " + scene.string() + " --mode game --no-png --out " + (temp_dir() / "sun.exr").string()).code, 0);
  expect_usage_error("render " + scene.string() + " --mode game --ambient irradiance --out " + (temp_dir() / "sun.exr").string(),
                     "need --ambient sh9");
  expect_usage_error("render " + small_scene().string() + " --sh-lights --out " + (temp_dir() / "sun.exr").string(),
                     "--sh-lights applies to --mode game");
}

// issue 16, 7: the report states the wrapped-diffuse mismatch beside the measured one: under a uniform
// environment the reference is kd (1 + 2w)/(1 + w)^2, game shading kd: expected game/ref 1.125 at w = 0.5.
TEST(CliHarden, ReportShowsTheWrappedDiffuseStatement) {
  const fs::path scene = temp_dir() / "wrap.json";
  std::ofstream(scene) << R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 30, "width": 24, "height": 24},
    "materials": {"wrap": {"model": "wrapped-diffuse", "params": {"kd": 0.8, "w": 0.5}}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "wrap"}],
    "environment": {"uniform": 0.5}})";
  const fs::path dir = temp_dir() / "wrap_report";
  const auto r = run("report " + scene.string() + " --spp 16 --out " + dir.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("wrapped diffuse: 'wrap' (w = 0.5): under a uniform environment game kd, reference 0.8889 kd, "
                       "expected luminance game/ref 1.1250 (measured 1.1"),
            std::string::npos)
      << r.out;
  const std::string html = bytes_of(dir / "index.html");
  EXPECT_NE(html.find("(1+2w)/(1+w)^2"), std::string::npos);
  const auto j = json_of(run("report " + scene.string() + " --spp 16 --json --out " + dir.string()));
  for (const auto& section : j["sections"]) {
    if (section["lighting"] != "environment") continue;
    const auto& m = section["materials"][0];
    EXPECT_NEAR(m["wrap"]["uniform_reference_over_game"].get<double>(), 2.0 / 2.25, 1e-12);
    // The measured ratio agrees with the statement (the environment is uniform; 16 spp of noise).
    EXPECT_NEAR(m["luminance_ratio"].get<double>(), 2.25 / 2.0, 0.02);
  }
}

}  // namespace
