#include "shadelab/sampling/sobol.h"

#include <gtest/gtest.h>

#include <vector>

namespace shadelab {
namespace {

// t of the 2D point set {(x_i, y_i)}, i in [first, first + 2^m): the smallest t such that every dyadic box
// of area 2^(t-m) holds exactly 2^t points (a (t,m,2)-net; Niederreiter 1992, definition 4.1).
int net_t(const std::vector<std::uint32_t>& x, const std::vector<std::uint32_t>& y, int m) {
  for (int t = 0; t <= m; ++t) {
    bool ok = true;
    const int k = m - t;  // boxes of 2^-a x 2^-(k-a)
    for (int a = 0; a <= k && ok; ++a) {
      std::vector<int> count(static_cast<std::size_t>(1) << k, 0);
      for (std::size_t i = 0; i < x.size(); ++i) {
        const std::uint32_t bx = a == 0 ? 0u : x[i] >> (32 - a);
        const std::uint32_t by = k - a == 0 ? 0u : y[i] >> (32 - (k - a));
        ++count[(static_cast<std::size_t>(bx) << (k - a)) | by];
      }
      for (int c : count) ok = ok && c == (1 << t);
    }
    if (ok) return t;
  }
  return m + 1;
}

std::vector<std::uint32_t> points(int dimension, std::uint32_t first, int m) {
  std::vector<std::uint32_t> v;
  for (std::uint32_t i = 0; i < (1u << m); ++i) v.push_back(sobol_u32(first + i, dimension));
  return v;
}

TEST(Sobol, FirstDimensionIsVanDerCorput) {
  // Radical inverse in base 2, computed digit by digit.
  for (std::uint32_t i = 0; i < 5000; ++i) {
    double expected = 0.0, scale = 0.5;
    for (std::uint32_t n = i; n != 0; n >>= 1u, scale *= 0.5) expected += (n & 1u) * scale;
    EXPECT_EQ(sobol_u32(i, 0) * 0x1.0p-32, expected) << i;
    EXPECT_EQ(radical_inverse(i), expected) << i;  // the library's one radical inverse
  }
  EXPECT_EQ(radical_inverse(0xffffffffu), 1.0 - 0x1p-32);  // all 32 digits
}

TEST(Sobol, SecondDimensionIsPascalsTriangleModTwo) {
  // With the polynomial x + 1 the generator matrix is C[r][c] = binom(c, r) mod 2, which by Lucas' theorem is 1
  // exactly when the bits of r are a subset of those of c.
  for (int c = 0; c < 32; ++c) {
    for (int r = 0; r < 32; ++r) {
      const std::uint32_t bit = (detail::sobol_matrices[1][static_cast<std::size_t>(c)] >> (31 - r)) & 1u;
      EXPECT_EQ(bit, (r & c) == r ? 1u : 0u) << "row " << r << " column " << c;
    }
  }
  // The first points of the second Sobol dimension: 0, 1/2, 3/4, 1/4, 5/8.
  const double expected[5] = {0.0, 0.5, 0.75, 0.25, 0.625};
  for (std::uint32_t i = 0; i < 5; ++i) EXPECT_EQ(sobol_u32(i, 1) * 0x1.0p-32, expected[i]);
}

TEST(Sobol, EveryDimensionIsAZeroOneSequence) {
  // Every aligned block of 2^m consecutive points has one point in each interval [k 2^-m, (k+1) 2^-m).
  for (int d = 0; d < sobol_dimensions; ++d) {
    for (int m = 0; m <= 12; ++m) {
      for (std::uint32_t block : {0u, 1u, 7u, 1000u}) {
        std::vector<int> count(static_cast<std::size_t>(1) << m, 0);
        for (std::uint32_t x : points(d, block << m, m)) ++count[m == 0 ? 0 : x >> (32 - m)];
        for (int c : count) ASSERT_EQ(c, 1) << "dimension " << d << " m " << m << " block " << block;
      }
    }
  }
}

TEST(Sobol, TwoDimensionalProjectionsAreNets) {
  // Dimensions 0 and 1 form a (0,2)-sequence. Joe and Kuo chose their direction numbers for small t in the 2D
  // projections; measured for m <= 16: t <= 1 for the pairs with dimension 2, t <= 2 for those with
  // dimension 3 (poor direction numbers give t growing with m: m_k = 1 everywhere repeats dimension 0, t = m).
  for (int m = 1; m <= 12; ++m) {
    for (std::uint32_t block : {0u, 3u}) {
      for (int a = 0; a < sobol_dimensions; ++a) {
        for (int b = a + 1; b < sobol_dimensions; ++b) {
          const int bound = b == 1 ? 0 : b == 2 ? 1 : 2;
          EXPECT_LE(net_t(points(a, block << m, m), points(b, block << m, m), m), bound) << a << "," << b << " m " << m;
        }
      }
    }
  }
}

TEST(Sobol, FirstPointsMatchAnIndependentImplementation) {
  // The first 8 points of dimensions 1..3 as SciPy's scipy.stats.qmc.Sobol(d=4, scramble=False) prints them
  // (Joe and Kuo's direction numbers, generated in Gray-code order: point i there is point i ^ (i >> 1) here).
  // Other valid direction numbers (m = (1, 1) for dimension 2, say) pass the net tests above but not this one.
  const double scipy[8][3] = {{0.0, 0.0, 0.0},       {0.5, 0.5, 0.5},       {0.25, 0.25, 0.25},    {0.75, 0.75, 0.75},
                              {0.375, 0.625, 0.875}, {0.875, 0.125, 0.375}, {0.125, 0.875, 0.625}, {0.625, 0.375, 0.125}};
  for (std::uint32_t i = 0; i < 8; ++i) {
    for (int d = 1; d < sobol_dimensions; ++d) {
      EXPECT_EQ(sobol_u32(i ^ (i >> 1u), d) * 0x1.0p-32, scipy[i][d - 1]) << "point " << i << " dimension " << d;
    }
  }
}

}  // namespace
}  // namespace shadelab
