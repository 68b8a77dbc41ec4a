// Tests of LDR-FLIP (flip.h) against facts that do not come from the code: identical images give 0; two
// flat images give the colour error computed here by hand from the CIE L* formula and the published L*a*b*
// of the sRGB primaries; the error is symmetric and in [0, 1] (Andersson et al. 2020, section 6); a larger
// viewing distance (more pixels per degree) hides fine noise (the contrast sensitivity filters, section 4.1);
// and, when SHADELAB_FLIP_IMAGES names a folder holding the FLIP repository's images/reference.png and
// images/test.png (github.com/NVlabs/flip, not shipped here), the mean the authors publish for them
// (src/tests/test.py: 0.159691 at 67 pixels per degree).
#include "shadelab/image/flip.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "shadelab/image/image_io.h"

namespace shadelab {
namespace {

Image flat(int w, int h, const Rgb& c) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set(x, y, c);
  return img;
}

Image noise(int w, int h, unsigned seed) {
  Image img(w, h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float& f : img.data) f = u(rng);
  return img;
}

// By hand: c_max from the published CIE L*a*b* (D65) of the sRGB primaries (B. Lindbloom's calculator,
// brucelindbloom.com, and every colour reference: green 87.737, -86.185, 83.181; blue 32.303, 79.197,
// -107.864), Hunt-adjusted and HyAB (flip.h), then the paper's mapping of HyAB^0.7.
double hand_cmax_hyab() {
  const double gl = 87.737, ga = 0.01 * gl * -86.185, gb = 0.01 * gl * 83.181;
  const double bl = 32.303, ba = 0.01 * bl * 79.197, bb = 0.01 * bl * -107.864;
  return std::abs(gl - bl) + std::sqrt((ga - ba) * (ga - ba) + (gb - bb) * (gb - bb));
}

double hand_colour_error(double hyab) {
  const double cmax = std::pow(hand_cmax_hyab(), 0.7), knee = 0.4 * cmax, e = std::pow(hyab, 0.7);
  return e < knee ? e * 0.95 / knee : 0.95 + (e - knee) / (cmax - knee) * 0.05;
}

// CIE 1976 lightness of a neutral of relative luminance Y (> 0.008856).
double cie_lightness(double y) { return 116.0 * std::cbrt(y) - 16.0; }

TEST(Flip, IdenticalImagesGiveZero) {
  const Image a = noise(40, 30, 1);
  const FlipResult r = flip(a, a).value();
  EXPECT_EQ(r.mean, 0.0);
  for (double v : r.map.values) EXPECT_EQ(v, 0.0);
}

TEST(Flip, MaxDistanceIsGreenToBlue) {
  EXPECT_NEAR(flip_max_hyab(), hand_cmax_hyab(), 2e-3 * hand_cmax_hyab());
}

TEST(Flip, FlatBlackAgainstWhiteByHand) {
  // White is L* 100, a* = b* = 0; black L* 0: HyAB 100, above the knee.
  const double expected = hand_colour_error(100.0);
  EXPECT_GT(expected, 0.95);
  const FlipResult r = flip(flat(24, 24, Rgb::gray(0.0)), flat(24, 24, Rgb::gray(1.0))).value();
  for (double v : r.map.values) EXPECT_NEAR(v, expected, 2e-4);
  EXPECT_NEAR(flip_flat_color_error(Rgb::gray(0.0), Rgb::gray(1.0)), expected, 2e-4);
}

TEST(Flip, FlatGreysByHand) {
  // Neutral greys: a* = b* = 0, HyAB = |L1 - L2|, below the knee (linear part of the mapping).
  const double hyab = std::abs(cie_lightness(0.5) - cie_lightness(0.2));
  const double expected = hand_colour_error(hyab);
  EXPECT_LT(expected, 0.95);
  const FlipResult r = flip(flat(20, 16, Rgb::gray(0.2)), flat(20, 16, Rgb::gray(0.5))).value();
  for (double v : r.map.values) EXPECT_NEAR(v, expected, 1e-4);
  EXPECT_NEAR(r.mean, expected, 1e-4);
}

TEST(Flip, RampAgainstFlatGreyByHand) {
  // The feature pipeline by hand. Reference: a grey ramp in x, g(x) = 0.3 + s (x - 32), linear in YCxCz's Y
  // and in y = (Y + 16) / 116 = g (greys: Cx = Cz = 0); test: flat grey 0.5. At x = 32, away from the
  // edges, the symmetric colour filters keep the ramp's value 0.3, so e_c is the flat greys' error by hand.
  // The edge detector, a Gaussian derivative whose positive weights sum to 1, answers a ramp of slope s with
  // s sum_k k^2 g_k / sum_{k>0} k g_k = s sqrt(2 pi) sigma^3 / sigma^2 (the sums as integrals), sigma =
  // 0.5 * 0.082 * 67 pixels; the point detector gives 0 (a line has no second derivative); the flat test
  // image has neither. So e_f = (s sqrt(2 pi) sigma / sqrt(2))^0.5 and FLIP = e_c^(1 - e_f) (paper, section 6).
  const double s = 0.004, sigma = 0.5 * 0.082 * 67.0;
  Image ramp(64, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) ramp.set(x, y, Rgb::gray(0.3 + s * (x - 32)));
  const double ec = hand_colour_error(std::abs(cie_lightness(0.5) - cie_lightness(0.3)));
  const double ef = std::sqrt(s * std::sqrt(2.0 * 3.141592653589793) * sigma / std::sqrt(2.0));
  EXPECT_GT(ef, 0.1);
  const FlipResult r = flip(flat(64, 32, Rgb::gray(0.5)), ramp).value();
  EXPECT_NEAR(r.map.at(32, 16), std::pow(ec, 1.0 - ef), 1e-3);  // 2e-4 apart: the sums as integrals, the 3.3-sigma cut
  EXPECT_GT(r.map.at(32, 16), ec + 0.05);  // the feature term raises the error
}

TEST(Flip, ClampsToTheDisplayRange) {
  const FlipResult r = flip(flat(16, 16, Rgb::gray(3.0)), flat(16, 16, Rgb::gray(1.0))).value();
  EXPECT_EQ(r.mean, 0.0);
}

TEST(Flip, SymmetricAndBounded) {
  const Image a = noise(48, 40, 2), b = noise(48, 40, 3);
  const FlipResult ab = flip(a, b).value(), ba = flip(b, a).value();
  ASSERT_EQ(ab.map.values.size(), ba.map.values.size());
  for (std::size_t i = 0; i < ab.map.values.size(); ++i) {
    EXPECT_EQ(ab.map.values[i], ba.map.values[i]);
    EXPECT_GE(ab.map.values[i], 0.0);
    EXPECT_LE(ab.map.values[i], 1.0);
  }
  EXPECT_GT(ab.mean, 0.0);
}

TEST(Flip, DistanceHidesFineNoise) {
  // Per-pixel noise against its flat mean: seen from farther (more pixels per degree) the filters blur the
  // noise away and the error falls.
  const Image a = noise(64, 64, 4), b = flat(64, 64, Rgb::gray(0.5));
  FlipOptions near, far;
  near.pixels_per_degree = 20.0;
  far.pixels_per_degree = 200.0;
  EXPECT_GT(flip(a, b, near).value().mean, flip(a, b, far).value().mean);
}

TEST(Flip, Errors) {
  EXPECT_FALSE(flip(flat(4, 4, Rgb::gray(0.1)), flat(5, 4, Rgb::gray(0.1))));
  EXPECT_FALSE(flip(Image{}, flat(4, 4, Rgb::gray(0.1))));
  Image nan = flat(4, 4, Rgb::gray(0.1));
  nan.data[5] = std::nanf("");
  EXPECT_FALSE(flip(nan, flat(4, 4, Rgb::gray(0.1))));
  FlipOptions bad;
  bad.pixels_per_degree = 0.0;
  EXPECT_FALSE(flip(flat(4, 4, Rgb::gray(0.1)), flat(4, 4, Rgb::gray(0.1)), bad));
}

TEST(Flip, PublishedMeanOfTheFlipRepositoryImages) {
  const char* dir = std::getenv("SHADELAB_FLIP_IMAGES");
  if (dir == nullptr) GTEST_SKIP() << "SHADELAB_FLIP_IMAGES not set (docs/images.md)";
  const std::filesystem::path d(dir);
  const Image ref = read_image(d / "reference.png").value();
  const Image test = read_image(d / "test.png").value();
  const FlipResult r = flip(test, ref).value();
  EXPECT_NEAR(r.mean, 0.159691, 5e-6);
}

}  // namespace
}  // namespace shadelab
