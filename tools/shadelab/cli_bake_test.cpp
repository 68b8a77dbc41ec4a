// End-to-end tests of `shadelab bake` and `shadelab light`: real files in, files and JSON out.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "cli_run.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/base/ktx.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/image/image_io.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;
using shadelab::testing::constant_hdr;

TEST(CliBake, ConstantHalfBakesToHalfInGameUnits) {
  const fs::path in = constant_hdr();
  const fs::path out = temp_dir() / "irr.exr";
  const auto j = json_of(run("bake irradiance " + in.string() + " --size 8 --out " + out.string() + " --json"));
  EXPECT_EQ(j["units"], "game");
  const auto img = shadelab::read_image(out);
  ASSERT_TRUE(img.has_value()) << img.error().message;
  EXPECT_EQ(img->width, 32);  // horizontal cross of 8 x 8 faces
  EXPECT_EQ(img->height, 24);
  const auto cube = shadelab::cube_from_cross(*img);
  ASSERT_TRUE(cube.has_value());
  // Exactly 0.5 in every stored float: the bake divides by the discrete cosine weights (docs/envmap.md; the
  // plain discrete sum was off by up to 1.2e-4 relative).
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(cube->texel(f, x, y)[c], 0.5) << f << " " << x << " " << y;
  // Radiometric: pi x 0.5, to the float storage's rounding.
  const fs::path out2 = temp_dir() / "irr_rad.exr";
  EXPECT_EQ(run("bake irradiance " + in.string() + " --size 4 --units radiometric --out " + out2.string()).code, 0);
  const auto cube2 = shadelab::cube_from_cross(shadelab::read_image(out2).value());
  for (int f = 0; f < 6; ++f) EXPECT_NEAR(cube2->texel(f, 1, 1).r, 0.5 * std::numbers::pi, 3e-8 * 0.5 * std::numbers::pi) << f;
}

TEST(CliBake, ShSaysItsConvention) {
  const fs::path in = constant_hdr();
  const auto j = json_of(run("bake sh " + in.string() + " --json"));
  ASSERT_EQ(j["irradiance_coefficients"].size(), 9u);
  EXPECT_EQ(j["units"], "game");
  EXPECT_TRUE(j.contains("convention") && j.contains("basis"));
  // E/pi = c0 Y0 = 0.5 for a constant 0.5.
  EXPECT_NEAR(j["irradiance_coefficients"][0][1].get<double>() * shadelab::sh_c0, 0.5, 1e-3);
  const auto r = json_of(run("bake sh " + in.string() + " --units radiometric --json"));
  EXPECT_NEAR(r["irradiance_coefficients"][0][1].get<double>() * shadelab::sh_c0, 0.5 * std::numbers::pi, 3e-3);
  const fs::path out = temp_dir() / "sh.json";
  EXPECT_EQ(run("bake sh " + in.string() + " --out " + out.string()).code, 0);
  std::ifstream f(out);
  const auto file = nlohmann::json::parse(f, nullptr, false);
  EXPECT_FALSE(file.is_discarded());
  EXPECT_EQ(file["irradiance_coefficients"].size(), 9u);
}

TEST(CliBake, SpecularWritesKtxAndExrFaces) {
  const fs::path in = constant_hdr();
  const fs::path out = temp_dir() / "spec.ktx";
  // By default the one requested file (issue 39); --exr-faces adds each level's six faces.
  const auto plain = json_of(run("bake specular " + in.string() + " --size 8 --out " + out.string() + " --json"));
  EXPECT_EQ(plain["exr_faces"].size(), 0u);
  EXPECT_FALSE(fs::exists(temp_dir() / "spec_m0_px.exr"));
  const auto j = json_of(run("bake specular " + in.string() + " --size 8 --exr-faces --out " + out.string() + " --json"));
  EXPECT_EQ(j["exponents"].size(), 4u);
  EXPECT_EQ(j["exr_faces"].size(), 24u);
  std::ifstream f(out, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto levels = shadelab::decode_ktx_cubemap(bytes);
  ASSERT_TRUE(levels.has_value()) << levels.error().message;
  ASSERT_EQ(levels->size(), 4u);
  EXPECT_NEAR((*levels)[0].texel(0, 3, 3).r, 0.5, 1e-3);
  EXPECT_NEAR((*levels)[3].texel(5, 0, 0).b, 0.5, 1e-3);
  EXPECT_TRUE(fs::exists(temp_dir() / "spec_m0_px.exr"));
  EXPECT_TRUE(fs::exists(temp_dir() / "spec_m3_nz.exr"));
}

TEST(CliBake, ConvertsABlenderWorld) {
  const fs::path in = fs::path(SHADELAB_BLENDER_WORLDS) / "forest.exr";
  const fs::path cross = temp_dir() / "forest_cross.exr";
  EXPECT_EQ(run("bake convert " + in.string() + " --size 32 --out " + cross.string()).code, 0);
  const auto img = shadelab::read_image(cross);
  ASSERT_TRUE(img.has_value());
  EXPECT_EQ(img->width * 3, img->height * 4);
  const fs::path ll = temp_dir() / "forest_back.hdr";
  EXPECT_EQ(run("bake convert " + cross.string() + " --layout latlong --out " + ll.string()).code, 0);
  EXPECT_EQ(shadelab::read_image(ll)->width, 128);
}

TEST(CliBake, BadInput) {
  expect_usage_error("bake irradiance /nonexistent/env.exr", "/nonexistent/env.exr");
  const fs::path empty = temp_dir() / "empty.exr";
  std::ofstream(empty).close();
  expect_usage_error("bake sh " + empty.string(), "empty.exr");
  const fs::path junk = temp_dir() / "junk.hdr";
  std::ofstream(junk) << "this is not an image";
  expect_usage_error("bake sh " + junk.string(), "junk.hdr");
  // A truncated EXR: the first half of a real one.
  const fs::path real = fs::path(SHADELAB_BLENDER_WORLDS) / "studio.exr";
  std::ifstream src(real, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(src)), std::istreambuf_iterator<char>());
  const fs::path cut = temp_dir() / "cut.exr";
  std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  expect_usage_error("bake irradiance " + cut.string(), "cut.exr");
  // Neither lat-long nor cross.
  shadelab::Image odd(100, 60);
  const fs::path odd_path = temp_dir() / "odd.exr";
  ASSERT_TRUE(shadelab::write_image(odd, odd_path).has_value());
  expect_usage_error("bake sh " + odd_path.string(), "100 x 60");
  const fs::path in = constant_hdr();
  expect_usage_error("bake irradiance " + in.string() + " --size 0", "--size");
  expect_usage_error("bake irradiance " + in.string() + " --units watts", "--units");
  expect_usage_error("bake specular " + in.string() + " --size 12", "--size");
  expect_usage_error("bake specular " + in.string() + " --out spec.exr", "--out");
  expect_usage_error("bake sh " + in.string() + " --window box", "--window");
  expect_usage_error("bake convert " + in.string() + " --out " + (temp_dir() / "x.exr").string() + " --layout star", "--layout");
  expect_usage_error("bake irradiance " + in.string() + " --out /nonexistent/dir/x.exr", "/nonexistent/dir/x.exr");
  EXPECT_FALSE(fs::exists("/nonexistent/dir/x.exr"));
}

// Radiance is finite: a NaN or Inf texel of an environment is bad input naming the first one (it was repaired
// to 0 with a warning before issue 40; cli_radiance_test.cpp has the other commands).
TEST(CliBake, NonFiniteTexelsAreErrorsNamingTheFirst) {
  shadelab::Image img(16, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) img.set(x, y, shadelab::Rgb::gray(0.5));
  img.data[3 * 20] = std::nanf("");
  img.data[3 * 21 + 1] = INFINITY;
  const fs::path p = temp_dir() / "nan.exr";
  ASSERT_TRUE(shadelab::write_image(img, p).has_value());
  expect_usage_error("bake sh " + p.string() + " --json", "nan.exr': texel (4, 1) channel R is NaN (2 non-finite values)");
}

TEST(CliLight, Conversions) {
  auto j = json_of(run("light 1 --from game --to lux --json"));
  EXPECT_NEAR(j["value"][0].get<double>(), 683.0 * std::numbers::pi, 1e-9);
  j = json_of(run("light 4 --from W/sr --to W --json"));
  EXPECT_NEAR(j["value"][1].get<double>(), 16.0 * std::numbers::pi, 1e-12);
  j = json_of(run("light 1,0.5,0.25 --from blender-W --to W/sr --json"));
  EXPECT_NEAR(j["value"][2].get<double>(), 0.25 / (4.0 * std::numbers::pi), 1e-15);
  EXPECT_EQ(run("light --list").code, 0);
  expect_usage_error("light 1 --from game --to cd", "different quantities");
  expect_usage_error("light 1 --from candles --to cd", "candles");
  expect_usage_error("light -1 --from cd --to W/sr", "negative");
  expect_usage_error("light 1 --from cd --to W --cone 0", "--cone");
  expect_usage_error("light abc --from cd --to W", "VALUE");
}

}  // namespace
