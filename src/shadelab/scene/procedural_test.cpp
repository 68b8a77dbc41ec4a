#include "shadelab/scene/procedural.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/gloss.h"
#include "shadelab/scene/scene.h"

namespace shadelab {
namespace {

bool same_pixels(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.data == b.data;
}

TEST(Procedural, NoiseIsPeriodicAndInRange) {
  for (int i = 0; i < 200; ++i) {
    const double u = 0.013 * i;
    const double v = 0.37 + 0.007 * i;
    const double n = periodic_value_noise(u, v, 5, 3, 42);
    EXPECT_GE(n, 0.0);
    EXPECT_LT(n, 1.0);
    // One period along u or v (1 in texture space) gives the same value.
    EXPECT_NEAR(periodic_value_noise(u + 1.0, v, 5, 3, 42), n, 1e-12);
    EXPECT_NEAR(periodic_value_noise(u, v - 1.0, 5, 3, 42), n, 1e-12);
    const double f = periodic_fbm(u, v, 3, 3, 5, 0.5, 9);
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
    EXPECT_NEAR(periodic_fbm(u + 2.0, v + 1.0, 3, 3, 5, 0.5, 9), f, 1e-12);
  }
  // Lattice points hold the hashed values: different seeds give different noise.
  EXPECT_NE(periodic_value_noise(0.0, 0.0, 4, 4, 1), periodic_value_noise(0.0, 0.0, 4, 4, 2));
}

TEST(Procedural, DeterministicFromSeed) {
  const Image a = asphalt_diffuse({64, 3, 0.08});
  const Image b = asphalt_diffuse({64, 3, 0.08});
  const Image c = asphalt_diffuse({64, 4, 0.08});
  EXPECT_TRUE(same_pixels(a, b));
  EXPECT_FALSE(same_pixels(a, c));
  const Image g1 = asphalt_gloss({64, 3, 0.3});
  const Image g2 = asphalt_gloss({64, 3, 0.3});
  const Image g3 = asphalt_gloss({64, 5, 0.3});
  EXPECT_TRUE(same_pixels(g1, g2));
  EXPECT_FALSE(same_pixels(g1, g3));
}

TEST(Procedural, AsphaltDiffuseIsDarkGreyWithSpeckle) {
  const Image img = asphalt_diffuse({256, 1, 0.08});
  ASSERT_EQ(img.width, 256);
  ASSERT_EQ(img.height, 256);
  double sum = 0.0;
  double lo = 1.0;
  double hi = 0.0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const Rgb c = img.at(x, y);
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(c[k], 0.02 - 1e-7);
        EXPECT_LE(c[k], 0.25 + 1e-7);
      }
      EXPECT_GE(c.r, c.b);  // warm grey, never blue
      sum += luminance(c);
      lo = std::min(lo, luminance(c));
      hi = std::max(hi, luminance(c));
    }
  }
  const double mean = sum / static_cast<double>(img.pixel_count());
  EXPECT_GT(mean, 0.05);
  EXPECT_LT(mean, 0.15);
  // Speckle: light aggregate well above the binder and dark pits below it.
  EXPECT_GT(hi, 2.0 * mean);
  EXPECT_LT(lo, 0.6 * mean);
}

struct GlossStats {
  double min_n = 1e300;
  double max_n = 0.0;
  double dry = 0.0;         // fraction with a single-digit exponent
  double wet = 0.0;         // fraction with an exponent in the thousands
  double above_half = 0.0;  // fraction with gloss > 0.5
};

GlossStats gloss_stats(const Image& img) {
  const GlossEncoding enc;  // the default 2..8192 the generator is written for
  GlossStats s;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const Rgb c = img.at(x, y);
      EXPECT_EQ(c.r, c.g);
      EXPECT_EQ(c.r, c.b);
      // Quantized to 8-bit codes like a PNG gloss map.
      const double code = c.r * 255.0;
      EXPECT_NEAR(code, std::round(code), 1e-4);
      const double n = enc.exponent_from_gloss(c.r);
      s.min_n = std::min(s.min_n, n);
      s.max_n = std::max(s.max_n, n);
      s.dry += n < 10.0 ? 1.0 : 0.0;
      s.wet += n >= 1000.0 ? 1.0 : 0.0;
      s.above_half += c.r > 0.5 ? 1.0 : 0.0;
    }
  }
  const auto count = static_cast<double>(img.pixel_count());
  s.dry /= count;
  s.wet /= count;
  s.above_half /= count;
  return s;
}

TEST(Procedural, AsphaltGlossSpansSingleDigitsToThousands) {
  // The zoo article: black is a single-digit exponent (dry, rough), white an exponent in the thousands
  // (puddles, wet streaks).
  const GlossStats s = gloss_stats(asphalt_gloss({256, 7, 0.3}));
  EXPECT_LT(s.min_n, 5.0);     // single digits
  EXPECT_GT(s.max_n, 2000.0);  // thousands
  EXPECT_GT(s.dry, 0.55);      // most of the road is dry
  EXPECT_LT(s.dry, 0.70);
  EXPECT_GT(s.wet, 0.20);  // puddles and streaks, minus their damp rims
  EXPECT_LE(s.wet, 0.30);
  EXPECT_NEAR(s.above_half, 0.3, 0.02);
}

TEST(Procedural, AsphaltGlossWetFractionExtremes) {
  const GlossStats dry = gloss_stats(asphalt_gloss({64, 2, 0.0}));
  EXPECT_LT(dry.max_n, 10.0);
  const GlossStats wet = gloss_stats(asphalt_gloss({64, 2, 1.0}));
  EXPECT_GE(wet.min_n, 1000.0);
}

TEST(Procedural, AsphaltGlossIsSmooth) {
  // Smooth noise, not white noise: neighbouring texels differ little on average, while the map as a
  // whole spans the full range.
  const Image img = asphalt_gloss({256, 7, 0.3});
  double diff = 0.0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const int x1 = (x + 1) % img.width;  // it tiles, so the wrap-around neighbour counts too
      diff += std::abs(img.at(x1, y).r - img.at(x, y).r);
    }
  }
  EXPECT_LT(diff / static_cast<double>(img.pixel_count()), 0.03);
}

TEST(Procedural, Checker) {
  const Image img = checker({8, 4, Rgb::gray(1.0), Rgb::gray(0.0)});
  EXPECT_EQ(img.at(0, 0).r, 1.0);
  EXPECT_EQ(img.at(1, 1).r, 1.0);
  EXPECT_EQ(img.at(2, 0).r, 0.0);
  EXPECT_EQ(img.at(0, 2).r, 0.0);
  EXPECT_EQ(img.at(2, 2).r, 1.0);
  EXPECT_EQ(img.at(7, 0).r, 0.0);
}

TEST(SampleTexture, BilinearWithWrapAround) {
  Texture t;
  t.image = Image(2, 1);
  t.image.set(0, 0, Rgb::gray(1.0));
  t.image.set(1, 0, Rgb::gray(3.0));
  // Texel centres return the texel exactly.
  EXPECT_DOUBLE_EQ(sample_texture(t, {0.25, 0.5}).r, 1.0);
  EXPECT_DOUBLE_EQ(sample_texture(t, {0.75, 0.5}).r, 3.0);
  // Half-way between the centres.
  EXPECT_DOUBLE_EQ(sample_texture(t, {0.5, 0.5}).r, 2.0);
  // u = 0 lies between the last texel and the first (wrap-around).
  EXPECT_DOUBLE_EQ(sample_texture(t, {0.0, 0.5}).r, 2.0);
  EXPECT_DOUBLE_EQ(sample_texture(t, {0.125, 0.5}).r, 1.5);
  EXPECT_DOUBLE_EQ(sample_texture(t, {1.125, 0.5}).r, 1.5);
  EXPECT_DOUBLE_EQ(sample_texture(t, {-0.875, 7.5}).r, 1.5);
  // Non-finite coordinates read a texel, never NaN; an empty texture is black.
  EXPECT_TRUE(std::isfinite(sample_texture(t, {std::nan(""), 0.5}).r));
  EXPECT_TRUE(sample_texture(Texture{}, {0.5, 0.5}).is_black());
}

TEST(SampleTexture, RowsGoDownward) {
  Texture t;
  t.image = Image(1, 2);
  t.image.set(0, 0, Rgb::gray(5.0));  // row 0 is the top: v = 0.25
  t.image.set(0, 1, Rgb::gray(7.0));
  EXPECT_DOUBLE_EQ(sample_texture(t, {0.5, 0.25}).r, 5.0);
  EXPECT_DOUBLE_EQ(sample_texture(t, {0.5, 0.75}).r, 7.0);
}

}  // namespace
}  // namespace shadelab
