#include "shadelab/sampling/owen.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

TEST(Owen, ReverseBits) {
  for (std::uint32_t x : {0u, 1u, 0x80000000u, 0x12345678u, 0xffffffffu, 0xf0u}) {
    std::uint32_t expected = 0;
    for (int b = 0; b < 32; ++b) expected |= ((x >> b) & 1u) << (31 - b);
    EXPECT_EQ(reverse_bits(x), expected);
  }
}

TEST(Owen, ScrambleIsNested) {
  // Output bit k (from the top) is input bit k XOR a function of input bits 0..k-1 only: flipping input bit k
  // keeps the top k output bits and flips output bit k.
  Pcg32 rng(3, 4);
  for (int trial = 0; trial < 2000; ++trial) {
    const std::uint32_t x = rng.next_u32();
    const std::uint32_t seed = rng.next_u32();
    const std::uint32_t y = owen_scramble(x, seed);
    for (int k = 0; k < 32; ++k) {
      const std::uint32_t flipped = owen_scramble(x ^ (0x80000000u >> k), seed);
      const std::uint32_t top = k == 0 ? 0u : ~0u << (32 - k);
      ASSERT_EQ(flipped & top, y & top) << "bit " << k;
      ASSERT_NE((flipped ^ y) & (0x80000000u >> k), 0u) << "bit " << k;
    }
  }
}

TEST(Owen, ScrambleRandomizesEveryDigit) {
  // For a fixed point, over seeds, each of the top 12 bits is 1 half the time, and the top 6 bits are uniform
  // over their 64 cells (chi-square, 63 degrees of freedom, 99.9% quantile 103.4).
  for (std::uint32_t x : {0u, 0x80000000u, 0x12345678u}) {
    const int n = 64000;
    std::vector<int> ones(12, 0), cells(64, 0);
    for (int s = 0; s < n; ++s) {
      const std::uint32_t y = owen_scramble(x, static_cast<std::uint32_t>(mix64(static_cast<std::uint64_t>(s))));
      for (int b = 0; b < 12; ++b) ones[static_cast<std::size_t>(b)] += (y >> (31 - b)) & 1u;
      ++cells[y >> 26u];
    }
    for (int b = 0; b < 12; ++b) EXPECT_NEAR(ones[static_cast<std::size_t>(b)] / static_cast<double>(n), 0.5, 0.01) << x << " bit " << b;
    double chi2 = 0.0;
    for (int c : cells) chi2 += (c - n / 64.0) * (c - n / 64.0) / (n / 64.0);
    EXPECT_LT(chi2, 103.4) << x;
  }
}

TEST(Owen, ReversedSobolTableMatchesTheDirectSum) {
  // The sampler's nibble table against the Sobol sum over the bits of the index.
  Pcg32 rng(8, 9);
  for (int trial = 0; trial < 5000; ++trial) {
    const std::uint32_t y = trial < 32 ? 1u << trial : rng.next_u32();
    for (int d = 0; d < sobol_dimensions; ++d) {
      std::uint32_t x = 0;
      for (int k = 0; k < 8; ++k) x ^= detail::sobol_reversed.entry[k][(y >> (4 * k)) & 15u][d];
      ASSERT_EQ(x, reverse_bits(sobol_u32(reverse_bits(y), d))) << y << " dimension " << d;
    }
  }
}

// Dimensions 0 and 1 of group g of the first 2^m samples of a pixel: one point in each box of area 2^-m.
bool is_zero_net(std::uint64_t pixel_seed, std::uint32_t g, int m, int d0, int d1) {
  for (int a = 0; a <= m; ++a) {
    std::set<std::pair<int, int>> boxes;
    for (std::uint32_t i = 0; i < (1u << m); ++i) {
      const auto u = PixelSampler(pixel_seed, i).group(g);
      boxes.insert({static_cast<int>(std::floor(std::ldexp(u[static_cast<std::size_t>(d0)], a))),
                    static_cast<int>(std::floor(std::ldexp(u[static_cast<std::size_t>(d1)], m - a)))});
    }
    if (boxes.size() != (1u << m)) return false;
  }
  return true;
}

TEST(PixelSampler, EveryGroupIsStratified) {
  for (std::uint64_t pixel : {1ull, 77ull, 123456789ull}) {
    for (std::uint32_t g : {0u, 1u, 9u}) {
      for (int m : {1, 4, 8}) {
        EXPECT_TRUE(is_zero_net(pixel, g, m, 0, 1)) << pixel << " group " << g << " m " << m;
      }
    }
  }
}

TEST(PixelSampler, ValuesDependOnlyOnPixelSampleAndGroup) {
  const PixelSampler a(42, 17);
  const auto g1 = a.group(1);
  const auto g0 = a.group(0);  // in any order
  EXPECT_EQ(g0, PixelSampler(42, 17).group(0));
  EXPECT_EQ(g1, PixelSampler(42, 17).group(1));
  EXPECT_NE(g0, g1);
  EXPECT_NE(g0, PixelSampler(43, 17).group(0));
  EXPECT_NE(g0, PixelSampler(42, 18).group(0));
  for (std::uint32_t i = 0; i < 1000; ++i) {
    for (double u : PixelSampler(9, i).group(i % 5)) {
      ASSERT_GT(u, 0.0);
      ASSERT_LT(u, 1.0);
    }
  }
}

TEST(PixelSampler, GroupsAndPixelsAreDecorrelated) {
  // Pearson correlation of dimension 0 between groups 0 and 1 (same pixel), and between two pixels (same
  // group), over 4096 samples: independent uniforms give |r| ~ N(0, 1/64); 4 sigma is 0.0625.
  auto corr = [](auto fx, auto fy) {
    const int n = 4096;
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (int i = 0; i < n; ++i) {
      const double x = fx(static_cast<std::uint32_t>(i)), y = fy(static_cast<std::uint32_t>(i));
      sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
    }
    const double cov = sxy / n - sx / n * sy / n;
    return cov / std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
  };
  for (int d = 0; d < 4; ++d) {
    const auto dd = static_cast<std::size_t>(d);
    EXPECT_LT(std::abs(corr([&](std::uint32_t i) { return PixelSampler(5, i).group(0)[dd]; },
                            [&](std::uint32_t i) { return PixelSampler(5, i).group(1)[dd]; })), 0.0625);
    EXPECT_LT(std::abs(corr([&](std::uint32_t i) { return PixelSampler(5, i).group(0)[dd]; },
                            [&](std::uint32_t i) { return PixelSampler(6, i).group(0)[dd]; })), 0.0625);
  }
}

TEST(PixelSampler, ConvergesFasterThanRandomSampling) {
  // Randomized QMC on a smooth integrand, f(x, y) = exp(x) sin(pi y) / ((e - 1) 2 / pi) with integral 1: over
  // 64 pixels (independent scrambles) the RMSE of N-sample estimates falls about as N^-1.5 for scrambled
  // nets (Owen 1997), and exactly as N^-0.5 for independent samples. The fitted slope between N = 16 and
  // N = 1024 must be steeper than -1.
  auto rmse = [](int n, bool qmc) {
    double se = 0.0;
    for (std::uint64_t p = 0; p < 64; ++p) {
      Pcg32 rng(p, 99);
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        double x, y;
        if (qmc) {
          const auto u = PixelSampler(mix64(p), static_cast<std::uint32_t>(i)).group(3);
          x = u[0], y = u[1];
        } else {
          x = rng.next_double(), y = rng.next_double();
        }
        sum += std::exp(x) * std::sin(3.141592653589793 * y) / ((std::exp(1.0) - 1.0) * 2.0 / 3.141592653589793);
      }
      se += (sum / n - 1.0) * (sum / n - 1.0);
    }
    return std::sqrt(se / 64.0);
  };
  const double slope_qmc = std::log(rmse(1024, true) / rmse(16, true)) / std::log(64.0);
  const double slope_mc = std::log(rmse(1024, false) / rmse(16, false)) / std::log(64.0);
  EXPECT_LT(slope_qmc, -1.0);
  EXPECT_NEAR(slope_mc, -0.5, 0.2);
}

}  // namespace
}  // namespace shadelab
