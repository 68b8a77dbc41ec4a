// The packed formats' encoders against the Vulkan 1.3 / D3D11 definitions: exact values at known bit
// patterns, every code decoded by the formula written out here, encoding = the nearest code (ties to even)
// found by searching all codes, the shared-exponent algorithm written out in double, round-trip bounds.
#include "shadelab/envmap/base/texel_format.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

// The definition, written independently: E = bits >> m, M = the low m bits.
double spec_ufloat(std::uint32_t bits, int m) {
  const double e = static_cast<double>(bits >> m);
  const double mant = static_cast<double>(bits & ((1u << m) - 1));
  if (e == 0) return std::pow(2.0, -14) * mant / std::pow(2.0, m);
  return std::pow(2.0, e - 15) * (1.0 + mant / std::pow(2.0, m));
}

TEST(TexelFormat, UfloatKnownBitPatterns) {
  EXPECT_EQ(encode_ufloat(1.0f, 6), 0x3C0u);   // E = 15, M = 0
  EXPECT_EQ(encode_ufloat(1.0f, 5), 0x1E0u);
  EXPECT_EQ(encode_ufloat(0.5f, 6), 0x380u);
  EXPECT_EQ(encode_ufloat(1.5f, 6), 0x3E0u);   // M = 32 of 64
  EXPECT_EQ(encode_ufloat(65024.0f, 6), 0x7BFu);  // the largest finite 11-bit value
  EXPECT_EQ(encode_ufloat(64512.0f, 5), 0x3DFu);  // the largest finite 10-bit value
  EXPECT_EQ(encode_ufloat(std::ldexp(1.0f, -14), 6), 0x040u);  // the smallest normal
  EXPECT_EQ(encode_ufloat(std::ldexp(1.0f, -20), 6), 0x001u);  // the smallest subnormal: 2^-14 / 64
  EXPECT_EQ(encode_ufloat(std::ldexp(1.0f, -19), 5), 0x001u);  // 10-bit: 2^-14 / 32
  EXPECT_EQ(encode_ufloat(0.0f, 6), 0u);
  EXPECT_EQ(encode_ufloat(-0.0f, 6), 0u);
  EXPECT_EQ(encode_ufloat(-3.0f, 6), 0u);
  EXPECT_EQ(encode_ufloat(-INFINITY, 6), 0u);
  EXPECT_EQ(encode_ufloat(INFINITY, 6), 0x7C0u);
  EXPECT_EQ(encode_ufloat(1e9f, 6), 0x7BFu);  // finite overflow clamps to the largest finite
  EXPECT_TRUE(std::isnan(decode_ufloat(encode_ufloat(NAN, 6), 6)));
  EXPECT_TRUE(std::isnan(decode_ufloat(encode_ufloat(NAN, 5), 5)));
  EXPECT_EQ(decode_ufloat(0x7C0u, 6), INFINITY);
  EXPECT_EQ(decode_ufloat(0x3E0u, 5), INFINITY);
  // Ties to even: 1 + 1/128 is half way between 1 (M = 0) and 1 + 1/64 (M = 1).
  EXPECT_EQ(encode_ufloat(1.0f + 1.0f / 128, 6), 0x3C0u);
  EXPECT_EQ(encode_ufloat(1.0f + 3.0f / 128, 6), 0x3C2u);
  EXPECT_EQ(encode_ufloat(std::ldexp(1.0f, -21), 6), 0u);         // half the smallest subnormal: to 0 (even)
  EXPECT_EQ(encode_ufloat(std::ldexp(3.0f, -21), 6), 2u);         // 1.5 x the smallest: to 2 (even)
  EXPECT_EQ(encode_ufloat(2.0f - 1.0f / 256, 6), 0x400u);        // rounds up across the exponent: 2.0
  // Packed: R in bits 0..10, G in 11..21, B in 22..31.
  EXPECT_EQ(encode_rg11b10(1.0f, 0.0f, 0.0f), 0x3C0u);
  EXPECT_EQ(encode_rg11b10(0.0f, 1.0f, 0.0f), 0x3C0u << 11);
  EXPECT_EQ(encode_rg11b10(0.0f, 0.0f, 1.0f), 0x1E0u << 22);
}

TEST(TexelFormat, UfloatEveryCodeMatchesTheDefinition) {
  for (int m : {6, 5}) {
    for (std::uint32_t code = 0; code < (31u << m); ++code) {
      const double v = spec_ufloat(code, m);
      EXPECT_EQ(decode_ufloat(code, m), static_cast<float>(v)) << code;
      EXPECT_EQ(encode_ufloat(static_cast<float>(v), m), code) << code;  // every finite value is exact
    }
  }
}

TEST(TexelFormat, UfloatEncodesToTheNearestCode) {
  Pcg32 rng(3);
  for (int m : {6, 5}) {
    const std::uint32_t finite = 31u << m;
    std::vector<double> table(finite);
    for (std::uint32_t c = 0; c < finite; ++c) table[c] = spec_ufloat(c, m);
    for (int i = 0; i < 3000; ++i) {
      const auto v = static_cast<float>(std::exp(std::log(1e-7) + (std::log(7e4) - std::log(1e-7)) * rng.next_double()));
      // The nearest code by search, ties to the even code; beyond the largest finite: the largest finite.
      std::uint32_t best = 0;
      double best_d = std::numeric_limits<double>::infinity();
      for (std::uint32_t c = 0; c < finite; ++c) {
        const double d = std::abs(table[c] - static_cast<double>(v));
        if (d < best_d || (d == best_d && (c & 1u) == 0)) {
          best = c;
          best_d = d;
        }
      }
      ASSERT_EQ(encode_ufloat(v, m), best) << v << " m=" << m;
    }
  }
}

// The shared-exponent algorithm of the Vulkan specification, in double with std::log2 and std::pow.
std::uint32_t spec_rgb9e5(double r, double g, double b) {
  const double max_v = 511.0 / 512.0 * std::pow(2.0, 16);
  auto cl = [&](double c) { return std::isnan(c) ? 0.0 : std::min(std::max(c, 0.0), max_v); };
  r = cl(r);
  g = cl(g);
  b = cl(b);
  const double mx = std::max({r, g, b});
  const double exp_p = std::max(-16.0, mx > 0 ? std::floor(std::log2(mx)) : -1e9) + 16.0;
  const double max_s = std::floor(mx / std::pow(2.0, exp_p - 24) + 0.5);
  const double e = max_s == 512.0 ? exp_p + 1 : exp_p;
  auto s = [&](double c) { return static_cast<std::uint32_t>(std::floor(c / std::pow(2.0, e - 24) + 0.5)); };
  return s(r) | (s(g) << 9) | (s(b) << 18) | (static_cast<std::uint32_t>(e) << 27);
}

TEST(TexelFormat, Rgb9e5KnownBitPatterns) {
  EXPECT_EQ(encode_rgb9e5(1, 1, 1), 256u | (256u << 9) | (256u << 18) | (16u << 27));
  EXPECT_EQ(encode_rgb9e5(0, 0, 0), 0u);
  EXPECT_EQ(encode_rgb9e5(65408, 65408, 65408), 0xFFFFFFFFu);  // the largest value: M = 511, E = 31
  EXPECT_EQ(encode_rgb9e5(1e30f, 0, 0), 511u | (31u << 27));   // clamped
  EXPECT_EQ(encode_rgb9e5(-1, NAN, 1), (256u << 18) | (16u << 27));
  EXPECT_EQ(encode_rgb9e5(0.5f, 0.25f, 0), 256u | (128u << 9) | (15u << 27));
  // max_s rounds to 512: the exponent goes up by one (2 - 2^-10 -> 256 at E = 17).
  EXPECT_EQ(encode_rgb9e5(2.0f - 1.0f / 1024, 0, 0), 256u | (17u << 27));
  const auto d = decode_rgb9e5(256u | (128u << 9) | (1u << 18) | (15u << 27));
  EXPECT_EQ(d[0], 0.5f);
  EXPECT_EQ(d[1], 0.25f);
  EXPECT_EQ(d[2], std::ldexp(1.0f, -9));
  EXPECT_EQ(decode_rgb9e5(0xFFFFFFFFu)[2], 65408.0f);
}

TEST(TexelFormat, Rgb9e5MatchesTheSpecificationAndItsBound) {
  Pcg32 rng(5);
  for (int i = 0; i < 20000; ++i) {
    float c[3];
    for (float& v : c) v = static_cast<float>(std::exp(std::log(1e-9) + (std::log(1e5) - std::log(1e-9)) * rng.next_double()));
    if (i % 7 == 0) c[i % 3] = 0.0f;
    const std::uint32_t p = encode_rgb9e5(c[0], c[1], c[2]);
    ASSERT_EQ(p, spec_rgb9e5(static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2]))) << c[0] << " " << c[1] << " " << c[2];
    const auto back = decode_rgb9e5(p);
    const double mx = std::min(static_cast<double>(std::max({c[0], c[1], c[2]})), 65408.0);
    for (int k = 0; k < 3; ++k) {
      // Half a step 2^(E - 24) of the shared exponent: max / step lies in [255.75, 512) (255.75 where max_s
      // rounds up to 512 and E goes up), so half a step is at most max / 511.5; below 2^-16 it is 2^-25.
      const double bound = std::max(mx / 511.5, std::ldexp(1.0, -25));
      ASSERT_LE(static_cast<double>(std::abs(back[static_cast<std::size_t>(k)] - std::min(c[k], 65408.0f))), bound) << c[k];
    }
  }
}

TEST(TexelFormat, RoundTripBoundsOfEveryFormat) {
  Pcg32 rng(7);
  Image img(64, 64);
  for (float& v : img.data) v = static_cast<float>(std::exp(std::log(1e-4) + (std::log(6e4) - std::log(1e-4)) * rng.next_double()));
  for (TexelFormat f : all_texel_formats) {
    std::vector<char> bytes;
    TexelEncodeInfo info;
    append_texels(bytes, img, f, &info);
    ASSERT_EQ(bytes.size(), img.pixel_count() * texel_bytes(f));
    EXPECT_EQ(info.clamped_values, 0u);
    const auto back = decode_texels(bytes.data(), img.pixel_count(), f);
    double worst = 0.0;
    for (std::size_t p = 0; p < img.pixel_count(); ++p) {
      const double mx = static_cast<double>(std::max({img.data[3 * p], img.data[3 * p + 1], img.data[3 * p + 2]}));
      for (std::size_t k = 0; k < 3; ++k) {
        const double v = static_cast<double>(img.data[3 * p + k]);
        const double scale = f == TexelFormat::rgb9e5 ? mx : v;  // shared exponent: relative to the largest channel
        worst = std::max(worst, std::abs(static_cast<double>(back[3 * p + k]) - v) / scale);
      }
    }
    if (f == TexelFormat::rgba32f) {
      EXPECT_EQ(worst, 0.0);  // float in, float out
      continue;
    }
    const double bound = f == TexelFormat::rgba16f ? std::ldexp(1.0, -11) : f == TexelFormat::rg11b10f ? std::ldexp(1.0, -6)
                                                                                                      : 1.0 / 511.5;
    EXPECT_LE(worst, bound) << texel_format_name(f);
    EXPECT_GT(worst, bound / 4) << texel_format_name(f);  // the bound is tight: a coarser encoding would fail it
  }
}

TEST(TexelFormat, CountsWhatItClamps) {
  Image img(2, 1);
  img.set(0, 0, {1e6, -1, 0.5});
  img.set(1, 0, {70000, 65000, 64600});
  TexelEncodeInfo h, r11, e5;
  std::vector<char> bytes;
  append_texels(bytes, img, TexelFormat::rgba16f, &h);
  append_texels(bytes, img, TexelFormat::rg11b10f, &r11);
  append_texels(bytes, img, TexelFormat::rgb9e5, &e5);
  EXPECT_EQ(h.clamped_values, 2u);    // 1e6 and 70000 beyond 65504
  EXPECT_EQ(r11.clamped_values, 3u);  // 1e6, 70000 (> 65024) and B 64600 (> 64512)
  EXPECT_EQ(r11.negative_values, 1u);
  EXPECT_EQ(e5.clamped_values, 2u);   // 1e6, 70000 (> 65408)
  EXPECT_EQ(e5.negative_values, 1u);
}

TEST(TexelFormat, Names) {
  for (TexelFormat f : all_texel_formats) EXPECT_TRUE(parse_texel_format(texel_format_name(f)) == f);
  EXPECT_FALSE(parse_texel_format("rgb8").has_value());
}

}  // namespace
}  // namespace shadelab
