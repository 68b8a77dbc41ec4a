// Tests of sampling/distribution.h: piecewise-constant 1D and 2D distributions. The pdf is checked against
// the table (value / mean), its integral against one, sampling frequencies against the table with a
// chi-square test at a fixed seed, invert against sample, and bad tables against the Error they must give.
#include "shadelab/sampling/distribution.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

// Pearson's statistic for counts against expected counts (all expected counts >= 5 in these tests).
double chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
  double chi2 = 0.0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] == 0.0) {
      EXPECT_EQ(observed[i], 0.0) << "bin " << i << " has no mass but was sampled";
      continue;
    }
    chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
  }
  return chi2;
}

// The chi-square 0.999 quantile (Wilson & Hilferty 1931), accurate to ~1 % for k >= 5.
double chi2_quantile_999(int k) {
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + 3.0902 * std::sqrt(a), 3.0);
}

const std::vector<double> k_table{1.0, 2.0, 0.0, 4.0, 0.5, 0.0, 0.0, 3.0, 7.0, 0.25};

TEST(Distribution1D, PdfIsTheNormalizedTable) {
  auto d = Distribution1D::create(k_table);
  ASSERT_TRUE(d.has_value()) << d.error().message;
  const double sum = std::accumulate(k_table.begin(), k_table.end(), 0.0);
  const double mean = sum / static_cast<double>(k_table.size());
  EXPECT_EQ(d->size(), k_table.size());
  EXPECT_NEAR(d->integral(), mean, 1e-15);
  for (std::size_t i = 0; i < k_table.size(); ++i) {
    EXPECT_EQ(d->value(i), k_table[i]);
    // Anywhere inside bin i the density is value / mean (the table normalized over [0, 1)).
    for (double t : {0.0, 0.3, 0.999}) {
      const double x = (static_cast<double>(i) + t) / static_cast<double>(k_table.size());
      EXPECT_NEAR(d->pdf(x), k_table[i] / mean, 1e-12) << "bin " << i << ", x = " << x;
    }
  }
  EXPECT_EQ(d->pdf(-0.1), 0.0);
  EXPECT_EQ(d->pdf(1.0), 0.0);
  EXPECT_EQ(d->pdf(1.5), 0.0);

  // Midpoint quadrature on a grid that nests the bins: exact for a piecewise-constant pdf up to rounding.
  double total = 0.0;
  constexpr int n = 10000;
  for (int i = 0; i < n; ++i) total += d->pdf((i + 0.5) / n) / n;
  EXPECT_NEAR(total, 1.0, 1e-12);
}

TEST(Distribution1D, SamplesLandInTheirBinWithTheirPdf) {
  auto d = Distribution1D::create(k_table);
  ASSERT_TRUE(d.has_value());
  const auto size = static_cast<double>(k_table.size());
  for (int i = 0; i <= 1000; ++i) {
    const double u = std::min(i / 1000.0, std::nextafter(1.0, 0.0));
    const auto s = d->sample(u);
    ASSERT_LT(s.index, k_table.size());
    EXPECT_GE(s.x, 0.0);
    EXPECT_LT(s.x, 1.0);
    EXPECT_EQ(static_cast<std::size_t>(s.x * size), s.index) << "u = " << u;
    EXPECT_GT(k_table[s.index], 0.0) << "u = " << u << " sampled an empty bin";
    EXPECT_EQ(s.pdf, d->pdf(s.x));
  }
  // The sample map is the inverse CDF: monotone in u.
  double previous = -1.0;
  for (int i = 0; i < 1000; ++i) {
    const double x = d->sample((i + 0.5) / 1000.0).x;
    EXPECT_GE(x, previous);
    previous = x;
  }
}

TEST(Distribution1D, SamplesAtBinEdgesStayInTheirBin) {
  // u one ulp either side of every CDF step, on tables whose values span 12 decades with empty bins: the
  // rounding of (i + t) / n must not move x into a neighbouring bin, where pdf() would give another density
  // (zero for an empty neighbour).
  Pcg32 rng(31337u, 5u);
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t n = 1 + rng.next_u32() % 40;
    std::vector<double> table(n);
    for (double& v : table) {
      v = rng.next_double() < 0.3 ? 0.0 : std::pow(10.0, 12.0 * rng.next_double() - 6.0);
    }
    auto d = Distribution1D::create(table);
    ASSERT_TRUE(d.has_value());
    for (std::size_t i = 0; i <= n; ++i) {
      const double edge = d->invert(static_cast<double>(i) / static_cast<double>(n));  // = CDF at edge i
      for (double u : {std::nextafter(edge, 0.0), edge, std::nextafter(edge, 1.0)}) {
        if (u < 0.0 || u >= 1.0) continue;
        const auto s = d->sample(u);
        ASSERT_LT(s.index, n);
        EXPECT_EQ(static_cast<std::size_t>(s.x * static_cast<double>(n)), s.index)
            << "trial " << trial << ", u = " << u << ", x = " << s.x;
        EXPECT_GT(table[s.index], 0.0) << "trial " << trial << ", u = " << u;
        EXPECT_GT(s.pdf, 0.0) << "trial " << trial << ", u = " << u;
        EXPECT_EQ(s.pdf, d->pdf(s.x));
      }
    }
  }
}

TEST(Distribution1D, SamplingFrequenciesMatchTheTable) {
  auto d = Distribution1D::create(k_table);
  ASSERT_TRUE(d.has_value());
  const double sum = std::accumulate(k_table.begin(), k_table.end(), 0.0);
  constexpr int samples = 200000;
  // Bins of the table, each split in two halves: the halves must be equally likely (uniform within a bin).
  std::vector<double> observed(2 * k_table.size(), 0.0);
  std::vector<double> expected(2 * k_table.size(), 0.0);
  for (std::size_t i = 0; i < k_table.size(); ++i) {
    expected[2 * i] = expected[2 * i + 1] = 0.5 * samples * k_table[i] / sum;
  }
  Pcg32 rng(12345u, 1u);
  for (int s = 0; s < samples; ++s) {
    const double x = d->sample(rng.next_double()).x;
    observed[static_cast<std::size_t>(x * static_cast<double>(observed.size()))] += 1.0;
  }
  const int nonzero_bins = 2 * 7;
  EXPECT_LT(chi_square(observed, expected), chi2_quantile_999(nonzero_bins - 1));
}

TEST(Distribution1D, InvertUndoesSample) {
  auto d = Distribution1D::create(k_table);
  ASSERT_TRUE(d.has_value());
  for (int i = 0; i <= 2000; ++i) {
    const double u = std::min(i / 2000.0, std::nextafter(1.0, 0.0));
    EXPECT_NEAR(d->invert(d->sample(u).x), u, 1e-9) << "u = " << u;
  }
  // invert is the CDF: 0 at 0, 1 at 1, clamped outside.
  EXPECT_EQ(d->invert(0.0), 0.0);
  EXPECT_EQ(d->invert(-1.0), 0.0);
  EXPECT_EQ(d->invert(1.0), 1.0);
  EXPECT_EQ(d->invert(2.0), 1.0);
  // At a bin edge the CDF is the running sum of the table.
  const double sum = std::accumulate(k_table.begin(), k_table.end(), 0.0);
  double running = 0.0;
  for (std::size_t i = 0; i < k_table.size(); ++i) {
    const double edge = static_cast<double>(i) / static_cast<double>(k_table.size());
    EXPECT_NEAR(d->invert(edge), running / sum, 1e-12);
    running += k_table[i];
  }
}

TEST(Distribution1D, SingleBinAndAllZeroTablesAreUniform) {
  const std::vector<std::vector<double>> tables{{3.0}, {0.0, 0.0, 0.0, 0.0}};
  for (const auto& table : tables) {
    auto d = Distribution1D::create(table);
    ASSERT_TRUE(d.has_value()) << d.error().message;
    for (int i = 0; i < 100; ++i) {
      const double u = (i + 0.5) / 100.0;
      const auto s = d->sample(u);
      EXPECT_NEAR(s.x, u, 1e-15);
      EXPECT_NEAR(s.pdf, 1.0, 1e-15);
      EXPECT_NEAR(d->pdf(u), 1.0, 1e-15);
      EXPECT_NEAR(d->invert(u), u, 1e-15);
    }
  }
  auto zero = Distribution1D::create(std::vector<double>{0.0, 0.0});
  ASSERT_TRUE(zero.has_value());
  EXPECT_EQ(zero->integral(), 0.0);  // the table has no mass, even though it samples uniformly
}

TEST(Distribution1D, BadTablesGiveAnError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::vector<double>> bad{
      {}, {1.0, -0.5, 2.0}, {-1e-300}, {1.0, nan}, {nan}, {inf, 1.0}, {1.0, -inf}};
  for (const auto& table : bad) {
    auto d = Distribution1D::create(table);
    ASSERT_FALSE(d.has_value()) << "a table of " << table.size() << " entries was accepted";
    EXPECT_NE(d.error().message.find("distribution"), std::string::npos) << d.error().message;
  }
  // The message names the offending entry.
  auto d = Distribution1D::create(std::vector<double>{1.0, 2.0, -3.0});
  ASSERT_FALSE(d.has_value());
  EXPECT_NE(d.error().message.find('2'), std::string::npos) << d.error().message;
}

// A 2D table of width 5 and height 4 with an empty row and empty cells.
constexpr std::size_t k_w = 5;
constexpr std::size_t k_h = 4;
const std::vector<double> k_table2{
    1.0, 2.0, 3.0, 0.0, 1.0,   //
    0.0, 0.0, 0.0, 0.0, 0.0,   //
    5.0, 0.5, 0.5, 8.0, 2.0,   //
    0.1, 0.2, 0.3, 0.4, 0.5};  //

TEST(Distribution2D, PdfIsTheNormalizedTable) {
  auto d = Distribution2D::create(k_table2, k_w, k_h);
  ASSERT_TRUE(d.has_value()) << d.error().message;
  EXPECT_EQ(d->width(), k_w);
  EXPECT_EQ(d->height(), k_h);
  const double mean = std::accumulate(k_table2.begin(), k_table2.end(), 0.0) / static_cast<double>(k_w * k_h);
  for (std::size_t y = 0; y < k_h; ++y) {
    for (std::size_t x = 0; x < k_w; ++x) {
      const Vec2 p{(static_cast<double>(x) + 0.4) / static_cast<double>(k_w),
                   (static_cast<double>(y) + 0.7) / static_cast<double>(k_h)};
      EXPECT_NEAR(d->pdf(p), k_table2[y * k_w + x] / mean, 1e-12) << x << ", " << y;
    }
  }
  EXPECT_EQ(d->pdf({-0.1, 0.5}), 0.0);
  EXPECT_EQ(d->pdf({0.5, 1.0}), 0.0);

  double total = 0.0;
  constexpr int n = 500;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) total += d->pdf({(i + 0.5) / n, (j + 0.5) / n}) / (n * n);
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
}

TEST(Distribution2D, SamplingFrequenciesMatchTheTable) {
  auto d = Distribution2D::create(k_table2, k_w, k_h);
  ASSERT_TRUE(d.has_value());
  const double sum = std::accumulate(k_table2.begin(), k_table2.end(), 0.0);
  constexpr int samples = 200000;
  std::vector<double> observed(k_w * k_h, 0.0);
  std::vector<double> expected(k_w * k_h, 0.0);
  int nonzero = 0;
  for (std::size_t i = 0; i < k_table2.size(); ++i) {
    expected[i] = samples * k_table2[i] / sum;
    nonzero += k_table2[i] > 0.0 ? 1 : 0;
  }
  Pcg32 rng(777u, 2u);
  for (int s = 0; s < samples; ++s) {
    const auto smp = d->sample({rng.next_double(), rng.next_double()});
    ASSERT_EQ(smp.pdf, d->pdf(smp.p));
    ASSERT_GT(smp.pdf, 0.0);
    const auto x = static_cast<std::size_t>(smp.p.x * static_cast<double>(k_w));
    const auto y = static_cast<std::size_t>(smp.p.y * static_cast<double>(k_h));
    observed[y * k_w + x] += 1.0;
  }
  EXPECT_LT(chi_square(observed, expected), chi2_quantile_999(nonzero - 1));
}

TEST(Distribution2D, InvertUndoesSample) {
  auto d = Distribution2D::create(k_table2, k_w, k_h);
  ASSERT_TRUE(d.has_value());
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) {
      const Vec2 u{(i + 0.5) / 100.0, (j + 0.5) / 100.0};
      const Vec2 back = d->invert(d->sample(u).p);
      EXPECT_NEAR(back.x, u.x, 1e-9) << u.x << ", " << u.y;
      EXPECT_NEAR(back.y, u.y, 1e-9) << u.x << ", " << u.y;
    }
  }
}

TEST(Distribution2D, AllZeroTableIsUniform) {
  auto d = Distribution2D::create(std::vector<double>(12, 0.0), 4, 3);
  ASSERT_TRUE(d.has_value()) << d.error().message;
  for (int i = 0; i < 10; ++i) {
    const Vec2 u{(i + 0.5) / 10.0, (9.5 - i) / 10.0};
    const auto s = d->sample(u);
    EXPECT_NEAR(s.p.x, u.x, 1e-15);
    EXPECT_NEAR(s.p.y, u.y, 1e-15);
    EXPECT_NEAR(s.pdf, 1.0, 1e-15);
  }
}

TEST(Distribution2D, BadTablesGiveAnError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> six{1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  EXPECT_FALSE(Distribution2D::create(six, 4, 2).has_value());  // 6 values for 4 x 2
  EXPECT_FALSE(Distribution2D::create(six, 2, 2).has_value());  // 6 values for 2 x 2
  EXPECT_FALSE(Distribution2D::create(six, 0, 6).has_value());
  EXPECT_FALSE(Distribution2D::create(six, 6, 0).has_value());
  EXPECT_FALSE(Distribution2D::create({}, 0, 0).has_value());
  EXPECT_TRUE(Distribution2D::create(six, 3, 2).has_value());
  EXPECT_TRUE(Distribution2D::create(six, 2, 3).has_value());

  std::vector<double> negative = six;
  negative[4] = -1.0;  // row 1 of a 3 x 2 table
  auto d = Distribution2D::create(negative, 3, 2);
  ASSERT_FALSE(d.has_value());
  EXPECT_NE(d.error().message.find("row 1"), std::string::npos) << d.error().message;

  std::vector<double> with_nan = six;
  with_nan[0] = nan;
  auto e = Distribution2D::create(with_nan, 3, 2);
  ASSERT_FALSE(e.has_value());
  EXPECT_NE(e.error().message.find("row 0"), std::string::npos) << e.error().message;
}

}  // namespace
}  // namespace shadelab
