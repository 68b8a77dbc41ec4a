// Tests of the image metrics: identical images, a known perturbation with every figure in closed form, SSIM
// against closed forms, a hand-worked window and a direct per-window evaluation, the heat-map ramp, the heat
// map and the side-by-side picture, and the errors.
#include "shadelab/image/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "shadelab/image/srgb.h"

namespace shadelab {
namespace {

Image constant_image(int w, int h, double v) {
  Image img(w, h);
  for (float& f : img.data) f = static_cast<float>(v);
  return img;
}

// A deterministic image of varied values in [0, 2).
Image noise_image(int w, int h, unsigned seed) {
  Image img(w, h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 2.0f);
  for (float& f : img.data) f = u(rng);
  return img;
}

Plane constant_plane(int w, int h, double v) {
  Plane p;
  p.width = w;
  p.height = h;
  p.values.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), v);
  return p;
}

double& plane_at(Plane& p, int x, int y) {
  return p.values[static_cast<std::size_t>(y) * static_cast<std::size_t>(p.width) + static_cast<std::size_t>(x)];
}

// The 1D SSIM weights computed here from the definition: exp(-k^2 / 4.5), k = -5..5, over their sum.
double test_weight(int k) {
  double sum = 0.0;
  for (int j = -5; j <= 5; ++j) sum += std::exp(-j * j / 4.5);
  return std::exp(-(k - 5) * (k - 5) / 4.5) / sum;
}

const double c1 = 0.01 * 0.01;  // (K1 L)^2
const double c2 = 0.03 * 0.03;  // (K2 L)^2

// SSIM of one window in which y is constant c and x is c except one pixel, c + d, of 2D weight w:
// mu_x = c + w d, sigma_x^2 = w (1 - w) d^2, sigma_y = sigma_xy = 0 (Wang et al. eq. 13).
double one_pixel_window_ssim(double c, double d, double w) {
  const double mu_x = c + w * d;
  const double var_x = w * (1.0 - w) * d * d;
  return ((2.0 * mu_x * c + c1) * c2) / ((mu_x * mu_x + c * c + c1) * (var_x + c2));
}

// ------------------------------------------------------------------------------------------- the figures

TEST(Metrics, IdenticalImagesGiveZeroAndSsimOne) {
  const Image a = noise_image(37, 23, 1);
  const auto d = compare_images(a, a);
  ASSERT_TRUE(d.has_value()) << d.error().message;
  EXPECT_EQ(d->width, 37);
  EXPECT_EQ(d->height, 23);
  EXPECT_EQ(d->mse, 0.0);
  EXPECT_EQ(d->rmse, 0.0);
  EXPECT_EQ(d->relative_mse, 0.0);
  EXPECT_EQ(d->max_abs_error, 0.0);
  EXPECT_EQ(d->max_x, 0);
  EXPECT_EQ(d->max_y, 0);
  EXPECT_EQ(d->mean_luminance_ratio, 1.0);
  EXPECT_EQ(d->ssim, 1.0);
  EXPECT_EQ(d->ssim_windows, 27LL * 13LL);
}

// A constant 0.5 image, and the same with +0.25 on the green channel of pixel (7, 3). Every value involved
// is a float exactly, so each figure has a closed form.
class MetricsPerturbation : public ::testing::Test {
 protected:
  static constexpr int w = 16;
  static constexpr int h = 12;
  static constexpr double n = w * h;
  Image base = constant_image(w, h, 0.5);
  Image bumped = [] {
    Image img = constant_image(w, h, 0.5);
    img.set(7, 3, Rgb{0.5, 0.75, 0.5});
    return img;
  }();
};

TEST_F(MetricsPerturbation, KnownFiguresWithTheReferenceUnbumped) {
  const auto d = compare_images(bumped, base);
  ASSERT_TRUE(d.has_value()) << d.error().message;
  EXPECT_DOUBLE_EQ(d->mse, 0.0625 / (3.0 * n));
  EXPECT_DOUBLE_EQ(d->rmse, 0.25 / std::sqrt(3.0 * n));
  EXPECT_DOUBLE_EQ(d->relative_mse, 0.0625 / (0.25 + 0.01) / (3.0 * n));  // reference value 0.5
  EXPECT_EQ(d->relative_mse_epsilon, 0.01);
  EXPECT_EQ(d->max_abs_error, 0.25);
  EXPECT_EQ(d->max_x, 7);
  EXPECT_EQ(d->max_y, 3);
  EXPECT_EQ(d->max_channel, 1);
  EXPECT_DOUBLE_EQ(d->mean_luminance_b, 0.5);
  EXPECT_DOUBLE_EQ(d->mean_luminance_a, 0.5 + 0.7152 * 0.25 / n);
  EXPECT_DOUBLE_EQ(d->mean_luminance_ratio, 1.0 + 0.7152 * 0.5 / n);
  // SSIM: each of the 6 x 2 windows holds the bumped pixel once, at window offset (7 - i, 3 - j), on the
  // display value V = sRGB(Y).
  const double v0 = linear_to_srgb(0.5);
  const double dv = linear_to_srgb(0.5 + 0.7152 * 0.25) - v0;
  double sum = 0.0;
  for (int j = 0; j <= h - 11; ++j)
    for (int i = 0; i <= w - 11; ++i) sum += one_pixel_window_ssim(v0, dv, test_weight(7 - i) * test_weight(3 - j));
  EXPECT_EQ(d->ssim_windows, 12);
  EXPECT_NEAR(d->ssim, sum / 12.0, 1e-12);
  EXPECT_LT(d->ssim, 0.9);
}

TEST_F(MetricsPerturbation, TheRelativeMseDividesByTheReference) {
  // Swapped: the reference now holds 0.75 there. RMSE and max error are symmetric; the relative MSE is not.
  const auto d = compare_images(base, bumped);
  ASSERT_TRUE(d.has_value());
  EXPECT_DOUBLE_EQ(d->rmse, 0.25 / std::sqrt(3.0 * n));
  EXPECT_EQ(d->max_abs_error, 0.25);
  EXPECT_DOUBLE_EQ(d->relative_mse, 0.0625 / (0.5625 + 0.01) / (3.0 * n));
  EXPECT_DOUBLE_EQ(d->mean_luminance_ratio, 0.5 / (0.5 + 0.7152 * 0.25 / n));
  // A different epsilon is used as given.
  CompareOptions o;
  o.relative_mse_epsilon = 0.001;
  EXPECT_DOUBLE_EQ(compare_images(base, bumped, o)->relative_mse, 0.0625 / (0.5625 + 0.001) / (3.0 * n));
}

TEST(Metrics, MaxErrorTiesGoToTheFirstInRowMajorOrder) {
  Image a = constant_image(5, 4, 0.25);
  const Image b = constant_image(5, 4, 0.25);
  a.set(3, 2, Rgb{0.25, 0.25, 0.75});
  a.set(1, 3, Rgb{0.75, 0.25, 0.25});
  a.set(4, 1, Rgb{0.25, -0.25, 0.25});  // negative difference, same size, first in row-major order
  const auto d = compare_images(a, b);
  EXPECT_EQ(d->max_abs_error, 0.5);
  EXPECT_EQ(d->max_x, 4);
  EXPECT_EQ(d->max_y, 1);
  EXPECT_EQ(d->max_channel, 1);
}

TEST(Metrics, LuminanceRatioOfBlackReferences) {
  const Image black = constant_image(4, 4, 0.0);
  EXPECT_EQ(compare_images(black, black)->mean_luminance_ratio, 1.0);
  EXPECT_TRUE(std::isnan(compare_images(constant_image(4, 4, 0.1), black)->mean_luminance_ratio));
  // A ratio of luminances, not of channel means: pure blue against pure green.
  Image blue(3, 3), green(3, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) {
      blue.set(x, y, Rgb{0, 0, 1});
      green.set(x, y, Rgb{0, 1, 0});
    }
  EXPECT_DOUBLE_EQ(compare_images(blue, green)->mean_luminance_ratio, 0.0722 / 0.7152);
}

// ------------------------------------------------------------------------------------------------- SSIM

TEST(Ssim, WeightsAreTheNormalisedGaussian) {
  const auto& w = ssim_weights();
  ASSERT_EQ(w.size(), 11u);
  double sum = 0.0;
  for (int k = 0; k < 11; ++k) {
    EXPECT_NEAR(w[static_cast<std::size_t>(k)], test_weight(k), 1e-16) << k;
    EXPECT_DOUBLE_EQ(w[static_cast<std::size_t>(k)], w[static_cast<std::size_t>(10 - k)]);
    sum += w[static_cast<std::size_t>(k)];
  }
  EXPECT_NEAR(sum, 1.0, 1e-15);
  // 1 / sum_k exp(-k^2 / 4.5) = 1 / 3.7592327951692...
  EXPECT_NEAR(w[5], 0.26601172486179436, 1e-15);
}

TEST(Ssim, ConstantImagesHaveTheClosedForm) {
  // sigma = 0 everywhere: SSIM = (2 c d + C1) / (c^2 + d^2 + C1) in every window.
  for (const auto& [c, d] : {std::pair{0.5, 0.6}, {0.2, 0.9}, {0.0, 0.01}, {0.3, 0.3}, {1.0, 0.0}}) {
    const double expected = (2.0 * c * d + c1) / (c * c + d * d + c1);
    EXPECT_NEAR(mean_ssim(constant_plane(13, 12, c), constant_plane(13, 12, d)), expected, 1e-12) << c << " " << d;
  }
  // Through compare_images: grey linear images (0.2 and 0.3 as floats), V = sRGB(Y).
  const auto d = compare_images(constant_image(20, 15, 0.2), constant_image(20, 15, 0.3));
  const double va = linear_to_srgb(static_cast<double>(0.2f));
  const double vb = linear_to_srgb(static_cast<double>(0.3f));
  EXPECT_NEAR(d->ssim, (2.0 * va * vb + c1) / (va * va + vb * vb + c1), 1e-12);
}

TEST(Ssim, HandWorkedSingleWindow) {
  // 11 x 11, one window. x is 0.5 except 0.9 at the centre; y is 0.5. The centre's 2D weight is
  // (1 / 3.7592327951692631)^2 = 0.0707622...; mu_x = 0.5 + 0.4 w, sigma_x^2 = w (1 - w) 0.16, and
  // SSIM = (2 mu_x 0.5 + C1) C2 / ((mu_x^2 + 0.25 + C1)(sigma_x^2 + C2)) = 0.0786843477011699
  // (also by a direct double sum over the 121 pixels).
  Plane x = constant_plane(11, 11, 0.5);
  const Plane y = constant_plane(11, 11, 0.5);
  plane_at(x, 5, 5) = 0.9;
  const Plane map = ssim_map(x, y);
  ASSERT_EQ(map.width, 1);
  ASSERT_EQ(map.height, 1);
  EXPECT_NEAR(map.at(0, 0), 0.0786843477011699, 1e-13);
  EXPECT_NEAR(mean_ssim(x, y), one_pixel_window_ssim(0.5, 0.4, test_weight(5) * test_weight(5)), 1e-13);
  // The same bump in a corner weighs w0^2 = 1.06e-6: SSIM 0.9998120238782485.
  Plane corner = constant_plane(11, 11, 0.5);
  plane_at(corner, 0, 10) = 0.9;
  EXPECT_NEAR(mean_ssim(corner, y), 0.9998120238782485, 1e-13);
}

TEST(Ssim, TwoWindowsAreAveraged) {
  // 12 x 11: windows centred on x = 5 and x = 6. A bump at (0, 5) is in the first only (offset (0, 5)).
  Plane x = constant_plane(12, 11, 0.25);
  const Plane y = constant_plane(12, 11, 0.25);
  plane_at(x, 0, 5) = 0.75;
  const double first = one_pixel_window_ssim(0.25, 0.5, test_weight(0) * test_weight(5));
  const Plane map = ssim_map(x, y);
  ASSERT_EQ(map.width, 2);
  EXPECT_NEAR(map.at(0, 0), first, 1e-13);
  EXPECT_NEAR(map.at(1, 0), 1.0, 1e-13);
  EXPECT_NEAR(mean_ssim(x, y), (first + 1.0) / 2.0, 1e-13);
}

TEST(Ssim, MatchesADirectEvaluationOfEveryWindow) {
  // Two-pass weighted means and (co)variances per window, straight from Wang et al. eqs. 13-16.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Plane x = constant_plane(17, 14, 0.0);
  Plane y = constant_plane(17, 14, 0.0);
  for (std::size_t i = 0; i < x.values.size(); ++i) {
    x.values[i] = u(rng);
    y.values[i] = 0.7 * x.values[i] + 0.3 * u(rng);
  }
  const Plane map = ssim_map(x, y);
  ASSERT_EQ(map.width, 7);
  ASSERT_EQ(map.height, 4);
  double total = 0.0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 7; ++i) {
      double mx = 0, my = 0;
      for (int b = 0; b < 11; ++b)
        for (int a = 0; a < 11; ++a) {
          mx += test_weight(a) * test_weight(b) * x.at(i + a, j + b);
          my += test_weight(a) * test_weight(b) * y.at(i + a, j + b);
        }
      double vx = 0, vy = 0, cxy = 0;
      for (int b = 0; b < 11; ++b)
        for (int a = 0; a < 11; ++a) {
          const double wt = test_weight(a) * test_weight(b);
          vx += wt * (x.at(i + a, j + b) - mx) * (x.at(i + a, j + b) - mx);
          vy += wt * (y.at(i + a, j + b) - my) * (y.at(i + a, j + b) - my);
          cxy += wt * (x.at(i + a, j + b) - mx) * (y.at(i + a, j + b) - my);
        }
      const double s = ((2 * mx * my + c1) * (2 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
      EXPECT_NEAR(map.at(i, j), s, 1e-12) << i << " " << j;
      total += s;
    }
  EXPECT_NEAR(mean_ssim(x, y), total / 28.0, 1e-12);
  EXPECT_GT(total / 28.0, 0.5);
  EXPECT_LT(total / 28.0, 0.99);
}

TEST(Ssim, PropertiesAndTheDisplayTransform) {
  const Image a = noise_image(24, 20, 3);
  const Image b = noise_image(24, 20, 4);
  const double ab = compare_images(a, b)->ssim;
  EXPECT_NEAR(ab, compare_images(b, a)->ssim, 1e-15);  // symmetric (up to rounding)
  EXPECT_LT(ab, 1.0);
  EXPECT_GT(ab, -1.0);
  // The display transform clamps: 2 and 3 both show as white at EV 0, and differ at EV -2.
  const Image two = constant_image(12, 12, 2.0);
  const Image three = constant_image(12, 12, 3.0);
  EXPECT_EQ(compare_images(two, three)->ssim, 1.0);
  CompareOptions darker;
  darker.exposure_stops = -2.0;
  const double v2 = linear_to_srgb(0.5);
  const double v3 = linear_to_srgb(0.75);
  const auto d = compare_images(two, three, darker);
  EXPECT_NEAR(d->ssim, (2 * v2 * v3 + c1) / (v2 * v2 + v3 * v3 + c1), 1e-12);
  EXPECT_EQ(d->ssim_exposure_stops, -2.0);
  // The display value of one pixel: V = sRGB(clamp(2^EV Y)).
  Image one(1, 1);
  one.set(0, 0, Rgb{0.125, 0.25, 0.375});
  EXPECT_DOUBLE_EQ(ssim_display_plane(one, 1.0).values[0], linear_to_srgb(2.0 * luminance(Rgb{0.125, 0.25, 0.375})));
  EXPECT_EQ(ssim_display_plane(one, 10.0).values[0], linear_to_srgb(1.0));
  // Smaller than one window: no SSIM.
  const auto small = compare_images(constant_image(10, 30, 0.5), constant_image(10, 30, 0.5));
  ASSERT_TRUE(small.has_value());
  EXPECT_TRUE(std::isnan(small->ssim));
  EXPECT_EQ(small->ssim_windows, 0);
  EXPECT_TRUE(ssim_map(constant_plane(11, 11, 0.5), constant_plane(11, 12, 0.5)).values.empty());
}

// ------------------------------------------------------------------------------------- heat map and panels

TEST(MetricsHeatRamp, BlackToWhiteWithRisingLuminance) {
  const Rgb lo = heat_ramp(0.0);
  const Rgb hi = heat_ramp(1.0);
  EXPECT_EQ(lo.r, 0.0);
  EXPECT_EQ(lo.g, 0.0);
  EXPECT_EQ(lo.b, 0.0);
  EXPECT_NEAR(hi.r, 1.0, 1e-12);
  EXPECT_NEAR(hi.g, 1.0, 1e-12);
  EXPECT_NEAR(hi.b, 1.0, 1e-12);
  EXPECT_EQ(luminance(heat_ramp(-1.0)), 0.0);
  EXPECT_EQ(luminance(heat_ramp(std::nan(""))), 0.0);
  EXPECT_EQ(luminance(heat_ramp(7.0)), luminance(hi));
  double previous = -1.0;
  for (int i = 0; i <= 1000; ++i) {
    const Rgb c = heat_ramp(i / 1000.0);
    EXPECT_GT(luminance(c), previous) << i;
    previous = luminance(c);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(c[k], 0.0);
      EXPECT_LE(c[k], 1.0);
    }
  }
  // Its hues: purple (red and blue over green), then red, then orange-yellow.
  const Rgb purple = heat_ramp(0.1);
  EXPECT_GT(purple.r, 5.0 * purple.g);
  EXPECT_GT(purple.b, 5.0 * purple.g);
  const Rgb red = heat_ramp(0.5);
  EXPECT_GT(red.r, 5.0 * red.g);
  EXPECT_GT(red.r, 5.0 * red.b);
  const Rgb orange = heat_ramp(0.75);
  EXPECT_GT(orange.r, orange.g);
  EXPECT_GT(orange.g, 2.0 * orange.b);
}

TEST(MetricsHeatmap, ScaleAndMetric) {
  Image a = constant_image(6, 5, 0.5);
  const Image b = constant_image(6, 5, 0.5);
  a.set(2, 1, Rgb{0.5, 0.5, 0.9});  // error 0.4
  a.set(4, 3, Rgb{0.7, 0.5, 0.5});  // error 0.2
  CompareOptions o;
  o.heatmap_metric = ErrorMetric::absolute;
  auto h = error_heatmap(a, b, o);
  ASSERT_TRUE(h.has_value()) << h.error().message;
  EXPECT_EQ(h->image.width, 6);
  EXPECT_EQ(h->image.height, 5);
  EXPECT_NEAR(h->max_error, 0.4, 1e-7);
  // Automatic: the 99th percentile of 30 errors is the one of rank floor(0.99 x 29) = 28 (from 0), the
  // smaller of the two: 0.2 is white, and so is 0.4, beyond the scale.
  EXPECT_NEAR(h->scale, 0.2, 1e-7);
  EXPECT_EQ(h->percentile_error, h->scale);
  EXPECT_NEAR(luminance(h->image.at(2, 1)), 1.0, 1e-6);
  EXPECT_NEAR(luminance(h->image.at(4, 3)), 1.0, 1e-6);
  EXPECT_EQ(luminance(h->image.at(0, 0)), 0.0);
  // A fixed scale: 0.2 of 0.8 is a quarter; above the scale saturates.
  o.heatmap_scale = 0.8;
  h = error_heatmap(a, b, o);
  EXPECT_EQ(h->scale, 0.8);
  EXPECT_NEAR(luminance(h->image.at(4, 3)), luminance(heat_ramp(0.25)), 1e-6);
  EXPECT_NEAR(luminance(h->image.at(2, 1)), luminance(heat_ramp(0.5)), 1e-6);
  o.heatmap_scale = 0.1;
  EXPECT_NEAR(luminance(error_heatmap(a, b, o)->image.at(4, 3)), 1.0, 1e-6);
  // Relative (the default): |a - b| / sqrt(b^2 + eps).
  EXPECT_DOUBLE_EQ(pixel_error(Rgb{0.5, 0.5, 0.9}, Rgb::gray(0.5), ErrorMetric::relative), 0.4 / std::sqrt(0.26));
  EXPECT_DOUBLE_EQ(pixel_error(Rgb{0.5, 0.5, 0.9}, Rgb::gray(2.0), ErrorMetric::relative), 1.5 / std::sqrt(4.01));  // red
  EXPECT_DOUBLE_EQ(pixel_error(Rgb{0.5, 0.5, 0.9}, Rgb::gray(0.5), ErrorMetric::absolute), 0.4);
  EXPECT_EQ(CompareOptions{}.heatmap_metric, ErrorMetric::relative);
  EXPECT_NEAR(error_heatmap(a, b)->max_error, 0.4 / std::sqrt(0.26), 1e-6);
  // Identical images: black, and the automatic scale falls back to 1.
  h = error_heatmap(b, b);
  EXPECT_EQ(h->max_error, 0.0);
  EXPECT_EQ(h->scale, 1.0);
  for (float f : h->image.data) EXPECT_EQ(f, 0.0f);
  // One differing pixel: the percentile is 0, so the scale is the maximum.
  Image one = b;
  one.set(5, 4, Rgb{0.5, 0.25, 0.5});
  EXPECT_DOUBLE_EQ(error_heatmap(one, b, o = {})->scale, 0.25 / std::sqrt(0.26));
  o.heatmap_scale = -1.0;
  EXPECT_FALSE(error_heatmap(a, b, o).has_value());
}

TEST(MetricsHeatmap, AutomaticScaleIsThe99thPercentile) {
  // 10 x 10, pixel i (row-major) off by i / 1024 in red: the errors are 0, 1, ..., 99 (/ 1024). Rank
  // floor(0.99 x 99) = 98: the scale is 98 / 1024, pixel 49 sits at the ramp's middle, pixel 99 saturates.
  Image a = constant_image(10, 10, 0.5);
  const Image b = constant_image(10, 10, 0.5);
  for (int i = 0; i < 100; ++i) a.set(i % 10, i / 10, Rgb{0.5 + i / 1024.0, 0.5, 0.5});
  CompareOptions o;
  o.heatmap_metric = ErrorMetric::absolute;
  const auto h = error_heatmap(a, b, o);
  ASSERT_TRUE(h.has_value());
  EXPECT_EQ(h->scale, 98.0 / 1024.0);
  EXPECT_EQ(h->max_error, 99.0 / 1024.0);
  EXPECT_NEAR(luminance(h->image.at(9, 4)), luminance(heat_ramp(0.5)), 1e-6);
  EXPECT_NEAR(luminance(h->image.at(9, 9)), 1.0, 1e-6);
  EXPECT_NEAR(luminance(h->image.at(8, 9)), 1.0, 1e-6);
  EXPECT_LT(luminance(h->image.at(7, 9)), 0.99);
}

TEST(MetricsSideBySide, PanelsInOrderWithOneExposure) {
  const Image a = constant_image(7, 3, 0.25);
  const Image b = constant_image(7, 3, 0.125);
  const Image heat = error_heatmap(a, b)->image;
  CompareOptions o;
  o.exposure_stops = 1.0;
  const auto s = side_by_side(a, b, heat, o);
  ASSERT_TRUE(s.has_value()) << s.error().message;
  EXPECT_EQ(s->width, 3 * 7 + 2 * side_by_side_gap);
  EXPECT_EQ(s->height, 3);
  EXPECT_DOUBLE_EQ(s->at(0, 0).r, 0.5);                          // A x 2
  EXPECT_DOUBLE_EQ(s->at(6, 2).g, 0.5);
  const double grey = static_cast<double>(0.18f);
  EXPECT_DOUBLE_EQ(s->at(7, 1).b, grey);                         // gap
  EXPECT_DOUBLE_EQ(s->at(7 + side_by_side_gap, 1).b, 0.25);     // B x 2
  EXPECT_DOUBLE_EQ(s->at(14 + side_by_side_gap, 0).r, grey);    // gap
  EXPECT_NEAR(s->at(14 + 2 * side_by_side_gap, 2).r, 1.0, 1e-6);  // heat map unscaled: white
  EXPECT_FALSE(side_by_side(a, b, Image(6, 3)).has_value());
}

// ------------------------------------------------------------------------------------------------ errors

TEST(Metrics, ErrorsNameTheImages) {
  const auto sizes = compare_images(Image(640, 360), Image(320, 180));
  ASSERT_FALSE(sizes.has_value());
  EXPECT_NE(sizes.error().message.find("A is 640 x 360, B is 320 x 180"), std::string::npos)
      << sizes.error().message;
  CompareOptions named;
  named.name_a = "'game.png'";
  named.name_b = "'ref.exr'";
  const auto empty = compare_images(Image(4, 4), Image(), named);
  ASSERT_FALSE(empty.has_value());
  EXPECT_NE(empty.error().message.find("'ref.exr' is empty"), std::string::npos) << empty.error().message;
  Image nan = constant_image(4, 4, 0.5);
  nan.data[3 * (2 * 4 + 3) + 1] = std::nanf("");
  const auto bad = compare_images(nan, constant_image(4, 4, 0.5), named);
  ASSERT_FALSE(bad.has_value());
  EXPECT_NE(bad.error().message.find("'game.png' has a NaN or infinite value at pixel (3, 2)"), std::string::npos)
      << bad.error().message;
  Image broken(3, 3);
  broken.data.pop_back();
  EXPECT_FALSE(compare_images(broken, Image(3, 3)).has_value());
  CompareOptions eps;
  eps.relative_mse_epsilon = 0.0;
  EXPECT_FALSE(compare_images(Image(3, 3), Image(3, 3), eps).has_value());
  EXPECT_FALSE(error_heatmap(Image(3, 3), Image(3, 4)).has_value());
}

}  // namespace
}  // namespace shadelab
