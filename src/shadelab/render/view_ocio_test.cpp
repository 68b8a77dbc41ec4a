// OpenColorIO against the kernels: the repo's config (share/ocio/shadelab.ocio, written by
// scripts/make_ocio_config.py from the published formulas with numpy, not from the kernels) through OCIO 2's CPU
// processor (color/ocio.h), and kernels/display.sl's views (render/film.h apply_view), agree in 8-bit code values
// on a ramp and on the HDRIs of Debian's blender-data; the OCIO errors are one line naming config, display and
// view; ACEScg <-> Linear Rec.709 through the config round-trips to 1e-5.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "shadelab/color/ocio.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/srgb.h"
#include "shadelab/render/film.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;

std::string repo_config() { return (fs::path(SHADELAB_SCENES_DIR) / ".." / "share" / "ocio" / "shadelab.ocio").lexically_normal().string(); }

// Greys over 26 stops and saturated ramps of the primaries, secondaries and a few hues, 0 to 2^12.
Image ramp() {
  std::vector<Rgb> px;
  for (int i = 0; i <= 26 * 16; ++i) {
    const double v = std::exp2(-14.0 + i / 16.0);
    for (Rgb d : {Rgb{1, 1, 1}, Rgb{1, 0, 0}, Rgb{0, 1, 0}, Rgb{0, 0, 1}, Rgb{1, 1, 0}, Rgb{0, 1, 1}, Rgb{1, 0, 1},
                  Rgb{1, 0.5, 0.2}, Rgb{0.1, 0.6, 1.0}, Rgb{0.9, 0.85, 0.7}}) {
      px.push_back(Rgb{d.r * v, d.g * v, d.b * v});
    }
  }
  px.push_back(Rgb{0, 0, 0});
  Image img(static_cast<int>(px.size()), 1);
  for (std::size_t i = 0; i < px.size(); ++i) img.set(static_cast<int>(i), 0, px[i]);
  return img;
}

struct Agreement {
  int max_codes = 0;
  double fraction_off = 0.0;  // channels whose codes differ at all
};

Agreement compare(const Image& hdr, ViewTransform kernel_view, const std::string& ocio_view, double stops = 0.0) {
  DisplayView k;
  k.transform = kernel_view;
  DisplayView o;
  o.transform = ViewTransform::ocio;
  o.ocio_config = repo_config();
  o.ocio_display = "sRGB";
  o.ocio_view = ocio_view;
  auto a = apply_view(hdr, stops, k);
  auto b = apply_view(hdr, stops, o);
  EXPECT_TRUE(a && b) << (b ? "" : b.error().message);
  if (!a || !b) return {};
  Agreement g;
  std::size_t off = 0;
  for (std::size_t i = 0; i < a->data.size(); ++i) {
    const int d = std::abs(int(linear_to_srgb8(a->data[i])) - int(linear_to_srgb8(b->data[i])));
    g.max_codes = std::max(g.max_codes, d);
    off += d > 0 ? 1 : 0;
  }
  g.fraction_off = double(off) / double(a->data.size());
  return g;
}

// PBR Neutral reads min and max of R, G, B, which no OCIO 2.1 transform computes, so the config approximates it by a
// 33^3 3D LUT: measured 12-13 codes at most (docs/color.md); the bound records that measurement.
constexpr int kPbrNeutralBound = 13;
struct ViewPair {
  ViewTransform kernel;
  const char* ocio;
  int bound;  // 8-bit codes
};
const ViewPair kViews[] = {{ViewTransform::standard, "Standard", 1}, {ViewTransform::filmic, "Filmic", 1},
                           {ViewTransform::agx, "AgX", 1}, {ViewTransform::aces, "ACES", 1},
                           {ViewTransform::pbr_neutral, "PBR Neutral", kPbrNeutralBound}};

TEST(ViewOcio, RepoConfigAgreesWithTheKernelsOnARamp) {
  const Image r = ramp();
  for (const auto& v : kViews) {
    for (double stops : {0.0, 2.5}) {
      const Agreement g = compare(r, v.kernel, v.ocio, stops);
      std::printf("ramp %s %+.1f EV: max %d codes, %.4f%% of channels differ\n", v.ocio, stops, g.max_codes, 100.0 * g.fraction_off);
      EXPECT_LE(g.max_codes, v.bound) << v.ocio;
    }
  }
}

TEST(ViewOcio, RepoConfigAgreesWithTheKernelsOnBlenderHdris) {
  const fs::path dir = SHADELAB_BLENDER_WORLDS;
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() == ".exr") files.push_back(e.path());
  }
  if (files.empty()) GTEST_SKIP() << "no HDRIs in " << dir << " (Debian's blender-data): skipped";
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    auto full = read_image(f);
    ASSERT_TRUE(full) << full.error().message;
    // Every 3rd pixel of every 3rd row (the test's time: 9 s for the full maps, 1.3 s so).
    Image img((full->width + 2) / 3, (full->height + 2) / 3);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) img.set(x, y, full->at(3 * x, 3 * y));
    for (const auto& v : kViews) {
      const Agreement g = compare(img, v.kernel, v.ocio);
      std::printf("%s %s: max %d codes, %.4f%% of channels differ\n", f.filename().c_str(), v.ocio, g.max_codes,
                  100.0 * g.fraction_off);
      EXPECT_LE(g.max_codes, v.bound) << f << " " << v.ocio;
    }
  }
}

TEST(ViewOcio, ErrorsAreOneLineNamingConfigDisplayAndView) {
  float px[3] = {0.5f, 0.5f, 0.5f};
  auto bad_view = ocio::apply_display_view({repo_config(), "sRGB", "Nope", "", ""}, px, 1);
  ASSERT_FALSE(bad_view);
  EXPECT_NE(bad_view.error().message.find("view 'Nope': no such view (the display's: Standard, Filmic, PBR Neutral, AgX, ACES)"), std::string::npos)
      << bad_view.error().message;
  EXPECT_NE(bad_view.error().message.find("shadelab.ocio"), std::string::npos);
  auto bad_display = ocio::apply_display_view({repo_config(), "P3", "AgX", "", ""}, px, 1);
  ASSERT_FALSE(bad_display);
  EXPECT_NE(bad_display.error().message.find("display 'P3', view 'AgX': no such display (the config's: sRGB)"), std::string::npos);
  auto bad_look = ocio::apply_display_view({repo_config(), "sRGB", "AgX", "punchy", ""}, px, 1);
  ASSERT_FALSE(bad_look);
  EXPECT_NE(bad_look.error().message.find("looks 'punchy'"), std::string::npos) << bad_look.error().message;
  auto missing = ocio::apply_display_view({"/no/such/config.ocio", "sRGB", "AgX", "", ""}, px, 1);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message.rfind("OCIO config '/no/such/config.ocio': ", 0), 0u) << missing.error().message;
  for (const auto* e : {&bad_view, &bad_display, &bad_look, &missing}) {
    EXPECT_EQ(e->error().message.find('\n'), std::string::npos);
  }
  EXPECT_EQ(px[0], 0.5f);  // untouched on error
}

// ACEScg <-> Linear Rec.709 through the config's matrices: the round trip, and the forward matrix against the
// published one (ACES's own OCIO config, "ACEScg" to "Linear Rec.709 (sRGB)": Bradford; first row to 1e-4).
TEST(ViewOcio, AcescgRoundTrip) {
  std::vector<float> px;
  for (int i = 0; i < 300; ++i) {
    const double v = std::exp2(-12.0 + i * 0.05);
    px.insert(px.end(), {float(v), float(0.5 * v + 0.01 * i), float(0.1 * v)});
  }
  const std::vector<float> original = px;
  ASSERT_TRUE(ocio::convert(repo_config(), "Linear Rec.709", "ACEScg", px.data(), px.size() / 3));
  ASSERT_TRUE(ocio::convert(repo_config(), "ACEScg", "Linear Rec.709", px.data(), px.size() / 3));
  for (std::size_t i = 0; i < px.size(); ++i) EXPECT_NEAR(double(px[i]), double(original[i]), 1e-5 * std::max(1.0, std::abs(double(original[i])))) << i;
  float e[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  ASSERT_TRUE(ocio::convert(repo_config(), "ACEScg", "Linear Rec.709", e, 3));
  EXPECT_NEAR(double(e[0]), 1.70505, 1e-4);   // R of ACEScg red
  EXPECT_NEAR(double(e[1]), -0.13026, 1e-4);  // G of ACEScg red
  EXPECT_NEAR(double(e[3]), -0.62179, 1e-4);  // R of ACEScg green
}

}  // namespace
}  // namespace shadelab
