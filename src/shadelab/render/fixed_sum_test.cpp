#include "shadelab/render/fixed_sum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

std::vector<Rgb> samples(int n, std::uint64_t seed) {
  // Radiance-like values over many orders of magnitude, with the occasional firefly.
  Pcg32 rng(seed, 5);
  std::vector<Rgb> v;
  for (int i = 0; i < n; ++i) {
    const double scale = std::pow(10.0, -6.0 + 10.0 * rng.next_double());
    v.push_back({scale * rng.next_double(), scale * rng.next_double(), -0.01 * rng.next_double()});
  }
  return v;
}

TEST(FixedSum, AnyGroupingGivesTheSameSum) {
  // The samples summed in one go, in reverse order, and in 1..16 contiguous parts summed separately and then
  // added in any order: the same integers. (A double sum of the same values differs between groupings.)
  const auto v = samples(5000, 1);
  FixedRgb whole;
  for (const Rgb& x : v) ASSERT_TRUE(whole.add(x));
  FixedRgb reversed;
  for (auto it = v.rbegin(); it != v.rend(); ++it) reversed.add(*it);
  EXPECT_EQ(whole, reversed);
  for (int parts : {1, 2, 3, 7, 16}) {
    std::vector<FixedRgb> part(static_cast<std::size_t>(parts));
    for (std::size_t i = 0; i < v.size(); ++i) part[i * static_cast<std::size_t>(parts) / v.size()].add(v[i]);
    FixedRgb merged;
    for (auto it = part.rbegin(); it != part.rend(); ++it) merged += *it;
    EXPECT_EQ(merged, whole) << parts << " parts";
  }
  double forward = 0.0, backward = 0.0;
  for (const Rgb& x : v) forward += x.r;
  for (auto it = v.rbegin(); it != v.rend(); ++it) backward += it->r;
  EXPECT_NE(forward, backward);  // why the exact sum is needed at all
}

// Each sample's fixed-point value against the definition computed another way: round(v 2^40) in long double
// (64-bit significand, so v 2^40 and its fraction are exact; rounded half to even by hand) as the
// integer, for values across the int64 / Int128 switch (2^23), halfway cases, negatives, tiny values and the
// clamp.
TEST(FixedSum, EachSampleIsItsValueTimes2To40RoundedHalfToEven) {
  std::vector<double> values = {0.0, -0.0, 0x1.0p-41, 0x1.8p-40, 0x1.4p-39, -0x1.8p-40, -0x1.4p-39, 0x1.0p-1074,
                                0.5, -2.5e-7, 1.0 / 3.0, 8388607.75, 8388608.0, -8388608.0, 9.5e6, -1.25e9, 0x1.0p52,
                                0x1.0p60, -0x1.0p60};
  Pcg32 rng(7, 1);
  for (int i = 0; i < 2000; ++i) {
    const double v = std::ldexp(rng.next_double() - 0.5, static_cast<int>(rng.next_u32() % 120u) - 60);
    values.push_back(v);
    values.push_back(std::ldexp(std::floor(std::ldexp(v, 40)) + 0.5, -40));  // a halfway case
  }
  for (const double v : values) {
    FixedRgb one;
    ASSERT_TRUE(one.add({v, 0.0, 0.0}));
    const double x = std::clamp(v, -0x1.0p52, 0x1.0p52);
    Int128 want = 0;
    if (std::abs(x) < 0x1.0p23) {
      const long double y = static_cast<long double>(x) * 1099511627776.0L;  // 2^40: exact, a power-of-2 scaling
      long double f = std::floor(y);
      const long double frac = y - f;
      if (frac > 0.5L || (frac == 0.5L && std::fmod(f, 2.0L) != 0.0L)) f += 1.0L;
      want = static_cast<Int128>(f);
    } else {
      // |x| >= 2^23: x's last bit is at least 2^-29, so x 2^40 is an integer: floor(x) 2^40 plus the
      // fraction's 2^40 multiple, both exact.
      const double whole = std::floor(x);
      want = static_cast<Int128>(whole) * (static_cast<Int128>(1) << 40) + static_cast<Int128>(std::ldexp(x - whole, 40));
    }
    EXPECT_TRUE(one.c[0] == want) << v;
  }
}

TEST(FixedSum, MeanIsWithinTheQuantizationBound) {
  // Against a long double sum: each sample is rounded to a multiple of 2^-40, so the mean is off by at most
  // 2^-41 plus the final double rounding.
  const auto v = samples(20000, 2);
  FixedRgb s;
  long double exact[3] = {0, 0, 0};
  for (const Rgb& x : v) {
    s.add(x);
    exact[0] += x.r, exact[1] += x.g, exact[2] += x.b;
  }
  const Rgb m = s.mean(v.size());
  const double got[3] = {m.r, m.g, m.b};
  for (int k = 0; k < 3; ++k) {
    const double want = static_cast<double>(exact[k] / static_cast<long double>(v.size()));
    EXPECT_LE(std::abs(got[k] - want), 0x1.0p-41 + 4.0 * std::numeric_limits<double>::epsilon() * std::abs(want)) << k;
  }
  // A single value is recovered to 2^-41.
  FixedRgb one;
  one.add({0.1, 1e-12, 123456.789});
  EXPECT_NEAR(one.mean(1).r, 0.1, 0x1.0p-41);
  EXPECT_NEAR(one.mean(1).g, 1e-12, 0x1.0p-41);
  EXPECT_NEAR(one.mean(1).b, 123456.789, 0x1.0p-41);
  EXPECT_EQ(FixedRgb{}.mean(0).r, 0.0);
}

TEST(FixedSum, NonFiniteSamplesAddNothingAndHugeOnesAreClamped) {
  FixedRgb s;
  EXPECT_TRUE(s.add({1.0, 2.0, 3.0}));
  EXPECT_FALSE(s.add({std::nan(""), 0.0, 0.0}));
  EXPECT_FALSE(s.add({0.0, std::numeric_limits<double>::infinity(), 0.0}));
  EXPECT_EQ(s.mean(1).r, 1.0);
  EXPECT_EQ(s.mean(1).g, 2.0);
  FixedRgb big;
  for (int i = 0; i < 1000; ++i) big.add({1e300, -1e300, 0x1.0p52});
  EXPECT_EQ(big.mean(1000).r, fixed_point_clamp);
  EXPECT_EQ(big.mean(1000).g, -fixed_point_clamp);
  EXPECT_EQ(big.mean(1000).b, fixed_point_clamp);
}

TEST(FixedSum, WordsRoundTrip) {
  for (Int128 v : {Int128{0}, Int128{1}, Int128{-1}, static_cast<Int128>(0x1.0p100), -static_cast<Int128>(0x1.0p90) - 7}) {
    EXPECT_TRUE(from_words(to_words(v)) == v);
  }
  const auto w = to_words(Int128{-2});
  EXPECT_EQ(w[0], 0xfffffffeu);
  EXPECT_EQ(w[3], 0xffffffffu);
}

}  // namespace
}  // namespace shadelab
