// End-to-end tests of `shadelab compare`: images written by the test, known figures in JSON and text, the
// heat-map and side-by-side PNGs, and every kind of bad input (exit code 2, one line naming the files).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/metrics.h"
#include "shadelab/image/srgb.h"

namespace {

namespace fs = std::filesystem;
using shadelab::Image;
using shadelab::Rgb;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

Image constant_image(int w, int h, double v) {
  Image img(w, h);
  for (float& f : img.data) f = static_cast<float>(v);
  return img;
}

std::string write_exr(const Image& img, const std::string& name) {
  const fs::path p = temp_dir() / name;
  const auto ok = shadelab::write_image(img, p);
  EXPECT_TRUE(ok.has_value()) << ok.error().message;
  return p.string();
}

// A minimal 8-bit PNG of 1 to 4 channels (grey, grey + alpha, RGB, RGBA), every sample `value`, stored
// deflate blocks: written here byte by byte, so the test controls the channel count.
void put_be32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<unsigned char>(v >> s));
}
std::uint32_t crc32(const unsigned char* data, std::size_t n) {
  std::uint32_t crc = 0xFFFFFFFFu;  // CRC-32 of the PNG specification, annex D
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc & 1u) != 0 ? 0xEDB88320u ^ (crc >> 1) : crc >> 1;
  }
  return crc ^ 0xFFFFFFFFu;
}
void put_chunk(std::vector<unsigned char>& out, const char* type, const std::vector<unsigned char>& data) {
  put_be32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put_be32(out, crc32(out.data() + start, out.size() - start));
}
std::string write_png(int w, int h, int channels, unsigned char value, const std::string& name) {
  std::vector<unsigned char> raw;
  for (int y = 0; y < h; ++y) {
    raw.push_back(0);  // filter: none
    for (int i = 0; i < w * channels; ++i) raw.push_back(value);
  }
  std::vector<unsigned char> zlib = {0x78, 0x01};
  zlib.push_back(1);  // BFINAL, stored (RFC 1951, 3.2.4); raw is below 65536 bytes
  const auto len = static_cast<std::uint16_t>(raw.size());
  zlib.push_back(static_cast<unsigned char>(len & 0xFF));
  zlib.push_back(static_cast<unsigned char>(len >> 8));
  zlib.push_back(static_cast<unsigned char>(~len & 0xFF));
  zlib.push_back(static_cast<unsigned char>((~len >> 8) & 0xFF));
  zlib.insert(zlib.end(), raw.begin(), raw.end());
  std::uint32_t s1 = 1, s2 = 0;  // Adler-32, RFC 1950
  for (unsigned char c : raw) {
    s1 = (s1 + c) % 65521u;
    s2 = (s2 + s1) % 65521u;
  }
  put_be32(zlib, (s2 << 16) | s1);
  const unsigned char colour_type = channels == 1 ? 0 : channels == 2 ? 4 : channels == 3 ? 2 : 6;
  std::vector<unsigned char> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<unsigned char> ihdr;
  put_be32(ihdr, static_cast<std::uint32_t>(w));
  put_be32(ihdr, static_cast<std::uint32_t>(h));
  ihdr.insert(ihdr.end(), {8, colour_type, 0, 0, 0});
  put_chunk(out, "IHDR", ihdr);
  put_chunk(out, "IDAT", zlib);
  put_chunk(out, "IEND", {});
  const fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
  return p.string();
}

// 16 x 12 constant 0.5, and the same with +0.25 on the green channel of pixel (7, 3).
struct Pair {
  std::string base;
  std::string bumped;
};
const Pair& perturbed_pair() {
  static const Pair pair = [] {
    Image bumped = constant_image(16, 12, 0.5);
    bumped.set(7, 3, Rgb{0.5, 0.75, 0.5});
    return Pair{write_exr(constant_image(16, 12, 0.5), "base.exr"), write_exr(bumped, "bumped.exr")};
  }();
  return pair;
}

TEST(CliCompare, IdenticalImagesGiveZero) {
  Image img(20, 14);
  for (int y = 0; y < 14; ++y)
    for (int x = 0; x < 20; ++x) img.set(x, y, Rgb{0.05 * x, 0.07 * y, 0.5});
  const std::string p = write_exr(img, "gradient.exr");
  const auto j = json_of(run("compare " + p + " " + p + " --json"));
  EXPECT_EQ(j["a"], p);
  EXPECT_EQ(j["b"], p);
  EXPECT_EQ(j["width"], 20);
  EXPECT_EQ(j["height"], 14);
  EXPECT_EQ(j["rmse"].get<double>(), 0.0);
  EXPECT_EQ(j["relative_mse"].get<double>(), 0.0);
  EXPECT_EQ(j["max_error"].get<double>(), 0.0);
  EXPECT_EQ(j["mean_luminance_ratio"].get<double>(), 1.0);
  EXPECT_EQ(j["ssim"].get<double>(), 1.0);
  EXPECT_FALSE(j.contains("heatmap"));
  EXPECT_FALSE(j.contains("side_by_side"));
}

TEST(CliCompare, AKnownPerturbationGivesTheKnownFigures) {
  const Pair& p = perturbed_pair();
  const double n = 16.0 * 12.0;
  const auto j = json_of(run("compare " + p.bumped + " " + p.base + " --json"));
  EXPECT_NEAR(j["rmse"].get<double>(), 0.25 / std::sqrt(3.0 * n), 1e-15);
  EXPECT_NEAR(j["mse"].get<double>(), 0.0625 / (3.0 * n), 1e-15);
  EXPECT_NEAR(j["relative_mse"].get<double>(), 0.0625 / 0.26 / (3.0 * n), 1e-15);
  EXPECT_EQ(j["relative_mse_epsilon"].get<double>(), 0.01);
  EXPECT_EQ(j["max_error"].get<double>(), 0.25);
  EXPECT_EQ(j["max_error_at"], nlohmann::json::array({7, 3}));
  EXPECT_EQ(j["max_error_channel"], "G");
  EXPECT_NEAR(j["mean_luminance_ratio"].get<double>(), 1.0 + 0.7152 * 0.5 / n, 1e-15);
  EXPECT_NEAR(j["mean_luminance_b"].get<double>(), 0.5, 1e-15);
  EXPECT_EQ(j["ssim_windows"], 12);
  EXPECT_GT(j["ssim"].get<double>(), 0.0);
  EXPECT_LT(j["ssim"].get<double>(), 0.9);
  // The reference is B: swapped, the relative MSE divides by 0.75^2 + eps.
  const auto s = json_of(run("compare " + p.base + " " + p.bumped + " --json --epsilon 0.001"));
  EXPECT_NEAR(s["relative_mse"].get<double>(), 0.0625 / 0.5635 / (3.0 * n), 1e-15);
  EXPECT_EQ(s["relative_mse_epsilon"].get<double>(), 0.001);
  // The text table has the same figures.
  const auto t = run("compare " + p.bumped + " " + p.base);
  EXPECT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("rmse"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("0.0104167"), std::string::npos) << t.out;  // 0.25 / sqrt(576)
  EXPECT_NE(t.out.find("at (7, 3), channel G"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("the reference"), std::string::npos) << t.out;
  EXPECT_TRUE(t.err.empty()) << t.err;
}

TEST(CliCompare, WritesTheHeatMapAndTheSideBySide) {
  const Pair& p = perturbed_pair();
  const fs::path heat = temp_dir() / "heat.png";
  const fs::path sbs = temp_dir() / "sbs.png";
  const auto j = json_of(run("compare " + p.bumped + " " + p.base + " --heatmap " + heat.string() +
                             " --side-by-side " + sbs.string() + " --exposure 1 --json"));
  EXPECT_EQ(j["heatmap"], heat.string());
  EXPECT_EQ(j["side_by_side"], sbs.string());
  // The default is the relative error; one pixel of 192 differs, so the 99th percentile is 0 and the scale
  // is the largest error, 0.25 / sqrt(0.5^2 + 0.01).
  EXPECT_EQ(j["heatmap_metric"], "relative");
  EXPECT_TRUE(j["heatmap_scale_automatic"].get<bool>());
  EXPECT_NEAR(j["heatmap_scale"].get<double>(), 0.25 / std::sqrt(0.26), 1e-15);
  EXPECT_EQ(j["exposure"].get<double>(), 1.0);
  const auto h = shadelab::read_image(heat);
  ASSERT_TRUE(h.has_value()) << h.error().message;
  EXPECT_EQ(h->width, 16);
  EXPECT_EQ(h->height, 12);
  EXPECT_EQ(h->at(7, 3).r, 1.0);  // the worst pixel is white
  EXPECT_EQ(h->at(7, 3).b, 1.0);
  EXPECT_EQ(h->at(0, 0).g, 0.0);  // no error is black
  const auto s = shadelab::read_image(sbs);
  ASSERT_TRUE(s.has_value()) << s.error().message;
  EXPECT_EQ(s->width, 3 * 16 + 2 * shadelab::side_by_side_gap);
  EXPECT_EQ(s->height, 12);
  EXPECT_EQ(s->at(0, 0).r, 1.0);  // 0.5 at +1 EV
  EXPECT_EQ(s->at(2 * (16 + shadelab::side_by_side_gap) + 7, 3).g, 1.0);
  // A fixed scale: 0.25 of 1 is a quarter of the ramp.
  const auto fixed = json_of(run("compare " + p.bumped + " " + p.base + " --heatmap " + heat.string() +
                                 " --scale 1 --heatmap-metric absolute --json"));
  EXPECT_EQ(fixed["heatmap_scale"].get<double>(), 1.0);
  EXPECT_FALSE(fixed["heatmap_scale_automatic"].get<bool>());
  const Rgb quarter = shadelab::heat_ramp(0.25);
  EXPECT_NEAR(shadelab::read_image(heat)->at(7, 3).r, quarter.r, 0.01);
  // The text output says what it wrote.
  const auto t = run("compare " + p.bumped + " " + p.base + " --heatmap " + heat.string());
  EXPECT_NE(t.out.find("wrote " + heat.string()), std::string::npos) << t.out;
}

TEST(CliCompare, BadInput) {
  const Pair& p = perturbed_pair();
  expect_usage_error("compare /nonexistent/a.exr " + p.base, "/nonexistent/a.exr");
  expect_usage_error("compare " + p.base + " /nonexistent/b.exr", "/nonexistent/b.exr");
  const fs::path junk = temp_dir() / "junk.exr";
  std::ofstream(junk) << "this is not an image";
  expect_usage_error("compare " + junk.string() + " " + p.base, "junk.exr");
  // Different sizes: both files and both sizes in one line.
  const std::string small = write_exr(constant_image(8, 6, 0.5), "small.exr");
  expect_usage_error("compare " + p.base + " " + small, "'" + p.base + "' is 16 x 12, '" + small + "' is 8 x 6");
  // Different channel layouts: grey against RGB, RGBA against RGB.
  const std::string grey = write_png(16, 12, 1, 128, "grey.png");
  const std::string rgb = write_png(16, 12, 3, 128, "rgb.png");
  const std::string rgba = write_png(16, 12, 4, 128, "rgba.png");
  expect_usage_error("compare " + grey + " " + rgb,
                     "'" + grey + "' has 1 channel (grey), '" + rgb + "' has 3 channels (RGB)");
  expect_usage_error("compare " + rgba + " " + rgb, "--ignore-alpha");
  expect_usage_error("compare " + rgba + " " + rgb, "'" + rgba + "' has 4 channels (RGBA)");
  const auto j = json_of(run("compare " + rgba + " " + rgb + " --ignore-alpha --json"));
  EXPECT_EQ(j["rmse"].get<double>(), 0.0);
  EXPECT_EQ(j["channels_a"], 4);
  // Options.
  expect_usage_error("compare " + p.base + " " + p.base + " --heatmap h.jpg", "--heatmap");
  expect_usage_error("compare " + p.base + " " + p.base + " --side-by-side s.exr", "--side-by-side");
  expect_usage_error("compare " + p.base + " " + p.base + " --scale -1", "--scale");
  expect_usage_error("compare " + p.base + " " + p.base + " --epsilon 0", "--epsilon");
  expect_usage_error("compare " + p.base + " " + p.base + " --heatmap-metric ssim", "--heatmap-metric");
  expect_usage_error("compare " + p.base, "B");
  expect_usage_error("compare " + p.base + " " + p.base + " --heatmap /nonexistent/dir/h.png", "/nonexistent/dir/h.png");
  EXPECT_FALSE(fs::exists("/nonexistent/dir/h.png"));
}

TEST(CliCompare, RepairedValuesAreWarnedAbout) {
  Image img = constant_image(12, 12, 0.5);
  img.data[5] = std::nanf("");
  const std::string nan = write_exr(img, "nan.exr");
  const std::string ok = write_exr(constant_image(12, 12, 0.5), "ok.exr");
  const auto r = run("compare " + nan + " " + ok + " --json");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("nan.exr': 1 NaN/Inf values replaced by 0"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["max_error"].get<double>(), 0.5);  // the NaN became 0
  // Too small for SSIM: null in JSON, n/a in the table.
  const std::string tiny = write_exr(constant_image(4, 4, 0.5), "tiny.exr");
  const auto t = json_of(run("compare " + tiny + " " + tiny + " --json"));
  EXPECT_TRUE(t["ssim"].is_null());
  EXPECT_NE(run("compare " + tiny + " " + tiny).out.find("n/a"), std::string::npos);
}

}  // namespace
