// Tests of the sRGB transfer function against IEC 61966-2-1 and of the 8- and 16-bit decode tables.
#include "shadelab/image/srgb.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadelab {
namespace {

TEST(Srgb, PublishedConstants) {
  EXPECT_EQ(srgb_decode_breakpoint, 0.04045);
  EXPECT_EQ(srgb_encode_breakpoint, 0.0031308);
  EXPECT_EQ(srgb_linear_slope, 12.92);
  EXPECT_EQ(srgb_exponent, 2.4);
  EXPECT_EQ(srgb_scale, 1.055);
  EXPECT_EQ(srgb_offset, 0.055);
}

TEST(Srgb, LinearSegmentBelowTheBreakpoints) {
  // At and below the breakpoints the curve is the straight line of slope 12.92.
  EXPECT_DOUBLE_EQ(srgb_to_linear(0.04045), 0.04045 / 12.92);
  EXPECT_DOUBLE_EQ(srgb_to_linear(0.02), 0.02 / 12.92);
  EXPECT_DOUBLE_EQ(linear_to_srgb(0.0031308), 0.0031308 * 12.92);
  EXPECT_DOUBLE_EQ(linear_to_srgb(0.001), 0.001 * 12.92);
  EXPECT_EQ(srgb_to_linear(0.0), 0.0);
  EXPECT_EQ(linear_to_srgb(0.0), 0.0);
}

TEST(Srgb, PowerSegmentMatchesPublishedValues) {
  // Reference values evaluated with 40-digit decimal arithmetic from the IEC formulas.
  EXPECT_NEAR(srgb_to_linear(0.5), 0.21404114048223244, 1e-15);
  EXPECT_NEAR(srgb_to_linear(128.0 / 255.0), 0.21586050011389916, 1e-15);
  EXPECT_NEAR(linear_to_srgb(0.18), 0.46135612950044165, 1e-15);
  EXPECT_NEAR(srgb_to_linear(1.0), 1.0, 1e-15);
  EXPECT_NEAR(linear_to_srgb(1.0), 1.0, 1e-15);
  // Just above the decoding breakpoint the power segment applies.
  EXPECT_NEAR(srgb_to_linear(0.0405), std::pow((0.0405 + 0.055) / 1.055, 2.4), 1e-18);
}

TEST(Srgb, IsNotAPureGamma) {
  // A 2.2 gamma differs by orders of magnitude in the shadows, and by about 0.004 at mid grey.
  EXPECT_GT(srgb_to_linear(0.02) / std::pow(0.02, 2.2), 4.0);
  EXPECT_GT(std::abs(srgb_to_linear(0.5) - std::pow(0.5, 2.2)), 0.003);
}

TEST(Srgb, ContinuousAtTheBreakpoints) {
  // The published constants meet to within 3e-9 (decoding) and 3e-8 (encoding), not exactly: the
  // standard rounded 0.04045 and 0.0031308. Both gaps are far below 1/65535.
  const double eps = 1e-12;
  EXPECT_NEAR(srgb_to_linear(0.04045), srgb_to_linear(0.04045 + eps), 3e-9);
  EXPECT_NEAR(linear_to_srgb(0.0031308), linear_to_srgb(0.0031308 + eps), 3e-8);
}

TEST(Srgb, MonotonicAndMutuallyInverse) {
  double previous = -1.0;
  for (int i = 0; i <= 100000; ++i) {
    const double v = i / 100000.0;
    const double l = srgb_to_linear(v);
    EXPECT_GE(l, previous);
    previous = l;
    // Exact inverses to 1e-12 except in the sliver between the two published breakpoints, where the
    // segments do not quite meet (3e-8 in encoded value, 3e-9 in linear value).
    ASSERT_NEAR(linear_to_srgb(l), v, std::abs(v - 0.04045) < 1e-7 ? 3e-8 : 1e-12) << "v = " << v;
    ASSERT_NEAR(srgb_to_linear(linear_to_srgb(v)), v, std::abs(v - 0.0031308) < 1e-8 ? 3e-9 : 1e-12) << "l = " << v;
  }
}

TEST(Srgb, EightBitTableMatchesTheFormula) {
  const auto& table = srgb8_to_linear_table();
  for (int k = 0; k < 256; ++k) {
    EXPECT_EQ(table[static_cast<std::size_t>(k)], static_cast<float>(srgb_to_linear(k / 255.0))) << "code " << k;
  }
  EXPECT_EQ(table[0], 0.0f);
  EXPECT_EQ(table[255], 1.0f);
  EXPECT_NEAR(table[10], 10.0 / 255.0 / 12.92, 1e-9);  // 10/255 = 0.0392 is on the linear segment
  EXPECT_NEAR(table[11], 0.0033465358, 1e-9);          // 11/255 = 0.0431 is the first code on the power segment
  EXPECT_NEAR(table[128], 0.2158605, 1e-7);
}

TEST(Srgb, EveryEightBitCodeRoundTrips) {
  const auto& table = srgb8_to_linear_table();
  for (int k = 0; k < 256; ++k) {
    EXPECT_EQ(linear_to_srgb8(static_cast<double>(table[static_cast<std::size_t>(k)])), k) << "code " << k;
  }
}

TEST(Srgb, EightBitEncodingRoundsAndClamps) {
  EXPECT_EQ(linear_to_srgb8(-1.0), 0);
  EXPECT_EQ(linear_to_srgb8(std::nan("")), 0);
  EXPECT_EQ(linear_to_srgb8(2.0), 255);
  EXPECT_EQ(linear_to_srgb8(INFINITY), 255);
  // Midpoint between codes 100 and 101 in encoded space: just below gives 100, just above 101.
  const double mid = srgb_to_linear(100.5 / 255.0);
  EXPECT_EQ(linear_to_srgb8(mid * (1.0 - 1e-9)), 100);
  EXPECT_EQ(linear_to_srgb8(mid * (1.0 + 1e-9)), 101);
}

TEST(Srgb, SixteenBitTableMatchesTheFormula) {
  const auto& table = srgb16_to_linear_table();
  ASSERT_EQ(table.size(), 65536u);
  for (int k = 0; k < 65536; ++k) {
    ASSERT_EQ(table[static_cast<std::size_t>(k)], static_cast<float>(srgb_to_linear(k / 65535.0))) << "code " << k;
  }
  EXPECT_EQ(table[65535], 1.0f);
}

}  // namespace
}  // namespace shadelab
