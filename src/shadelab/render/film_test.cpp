#include "shadelab/render/film.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "shadelab/image/image_io.h"

namespace shadelab {
namespace {

TEST(Film, FilmicCurveIsTheAcesFit) {
  EXPECT_DOUBLE_EQ(filmic_curve(0.0), 0.0);
  // Published behaviour of the fit: 0.18 grey maps near 0.27, large values saturate to 1, monotonic.
  EXPECT_NEAR(filmic_curve(0.18), 0.18 * (2.51 * 0.18 + 0.03) / (0.18 * (2.43 * 0.18 + 0.59) + 0.14), 1e-15);
  EXPECT_NEAR(filmic_curve(0.18), 0.267, 2e-3);
  EXPECT_DOUBLE_EQ(filmic_curve(1e6), 1.0);
  double prev = 0.0;
  for (double x = 0.01; x < 5; x *= 1.3) {  // strictly increasing until it saturates near x = 10
    EXPECT_GT(filmic_curve(x), prev);
    prev = filmic_curve(x);
  }
}

TEST(Film, ExposureDoublesPerStop) {
  Image img(1, 1);
  img.set(0, 0, Rgb::gray(0.1));
  EXPECT_NEAR(tonemap(img, 1.0, ToneCurve::clamp).at(0, 0).r, 0.2, 1e-7);
  EXPECT_NEAR(tonemap(img, 4.0, ToneCurve::clamp).at(0, 0).r, 1.0, 1e-7);  // clamped
}

TEST(Film, WritesEveryOutputAtomically) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "shadelab_film";
  std::filesystem::create_directories(dir);
  RenderResult r;
  r.beauty = Image(4, 2);
  r.albedo = Image(4, 2);
  r.normal = Image(4, 2);
  r.depth = Image(4, 2);
  FilmOutputs o;
  o.exr = dir / "out.exr";
  o.png = dir / "out.png";
  o.aovs = true;
  const auto written = write_film(r, o);
  ASSERT_TRUE(written.has_value()) << written.error().message;
  EXPECT_EQ(written->size(), 5u);
  EXPECT_TRUE(std::filesystem::exists(dir / "out.normal.exr"));
  o.exr = dir / "missing" / "out.exr";
  EXPECT_FALSE(write_film(r, o).has_value());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shadelab
