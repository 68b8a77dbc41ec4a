// Tests of the tick generator: 1-2-5 steps, exact decimal values, expansion, labels, decades on log axes.
#include "shadelab/plot/ticks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace shadelab {
namespace {

std::vector<double> major_values(const TickSet& set) {
  std::vector<double> v;
  for (const Tick& t : set.ticks) {
    if (!t.minor) {
      v.push_back(t.value);
    }
  }
  return v;
}

std::vector<std::string> major_labels(const TickSet& set) {
  std::vector<std::string> v;
  for (const Tick& t : set.ticks) {
    if (!t.minor) {
      v.push_back(t.label);
    }
  }
  return v;
}

TEST(NiceStep, IsTheSmallestOneTwoFiveStepAtOrAboveTheRawStep) {
  EXPECT_EQ(nice_step(0.3), 0.5);
  EXPECT_EQ(nice_step(1.0), 1.0);
  EXPECT_EQ(nice_step(1.1), 2.0);
  EXPECT_EQ(nice_step(2.0), 2.0);
  EXPECT_EQ(nice_step(2.01), 5.0);
  EXPECT_EQ(nice_step(6.0), 10.0);
  EXPECT_EQ(nice_step(7e-5), 1e-4);
  EXPECT_EQ(nice_step(3e5), 5e5);
  EXPECT_EQ(nice_step(0.1), 0.1);
  EXPECT_EQ(nice_step(0.0), 1.0);  // invalid input: 1, no crash
  EXPECT_EQ(nice_step(std::nan("")), 1.0);
}

TEST(LinearTicks, ZeroToOneGivesExactTenthsOfTwo) {
  const TickSet set = linear_ticks(0.0, 1.0, 6);
  EXPECT_EQ(major_values(set), (std::vector<double>{0.0, 0.2, 0.4, 0.6, 0.8, 1.0}));  // exact: 0.6, not 0.6000000000000001
  EXPECT_EQ(major_labels(set), (std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
  EXPECT_EQ(set.step, 0.2);
  EXPECT_EQ(set.min, 0.0);
  EXPECT_EQ(set.max, 1.0);
}

TEST(LinearTicks, MaxCountPicksTheSmallestStepThatFits) {
  EXPECT_EQ(linear_ticks(0.0, 1.0, 11).step, 0.1);
  EXPECT_EQ(linear_ticks(0.0, 1.0, 10).step, 0.2);  // 0.1 would give 11 ticks
  EXPECT_EQ(linear_ticks(0.0, 1.0, 3).step, 0.5);
  EXPECT_EQ(linear_ticks(0.0, 1.0, 2).step, 1.0);
  EXPECT_EQ(linear_ticks(0.0, 90.0, 10).step, 10.0);
  EXPECT_LE(linear_ticks(-7.3, 1234.5, 7).ticks.size(), 7u);
}

TEST(LinearTicks, ExpansionWidensOnlyTheRequestedEnds) {
  const TickSet both = linear_ticks(0.03, 0.97, 6, true, true);
  EXPECT_EQ(both.min, 0.0);
  EXPECT_EQ(both.max, 1.0);
  EXPECT_EQ(major_values(both).front(), 0.0);
  EXPECT_EQ(major_values(both).back(), 1.0);

  const TickSet low_only = linear_ticks(0.03, 0.97, 6, true, false);
  EXPECT_EQ(low_only.min, 0.0);
  EXPECT_EQ(low_only.max, 0.97);  // kept exactly
  EXPECT_LE(major_values(low_only).back(), 0.97);

  const TickSet none = linear_ticks(0.03, 0.97, 6);
  EXPECT_EQ(none.min, 0.03);
  EXPECT_GE(major_values(none).front(), 0.03);
}

TEST(LinearTicks, NegativeRangesHaveAnExactZeroAndNoNegativeZero) {
  const TickSet set = linear_ticks(-1.0, 1.0, 5);
  EXPECT_EQ(major_values(set), (std::vector<double>{-1.0, -0.5, 0.0, 0.5, 1.0}));
  EXPECT_EQ(major_labels(set), (std::vector<std::string>{"-1.0", "-0.5", "0.0", "0.5", "1.0"}));
  EXPECT_FALSE(std::signbit(set.ticks[2].value));
}

TEST(LinearTicks, IntegerStepsHaveNoDecimals) {
  EXPECT_EQ(major_labels(linear_ticks(0.0, 90.0, 4)), (std::vector<std::string>{"0", "50"}));  // 20 gives 5 ticks
  EXPECT_EQ(major_labels(linear_ticks(0.0, 90.0, 5)), (std::vector<std::string>{"0", "20", "40", "60", "80"}));
  EXPECT_EQ(major_labels(linear_ticks(0.0, 90.0, 10)).back(), "90");
}

TEST(LinearTicks, LargeAndTinyMagnitudesUseTimesTenToThe) {
  const TickSet big = linear_ticks(0.0, 3e6, 4);
  EXPECT_EQ(major_labels(big), (std::vector<std::string>{"0", "1\u00d710^6", "2\u00d710^6", "3\u00d710^6"}));
  const TickSet small = linear_ticks(0.0, 3e-5, 4);
  EXPECT_EQ(major_labels(small), (std::vector<std::string>{"0", "1\u00d710^-5", "2\u00d710^-5", "3\u00d710^-5"}));
  const TickSet fine = linear_ticks(1.0e6, 1.4e6, 5);
  EXPECT_EQ(major_labels(fine).front(), "1.0\u00d710^6");
  EXPECT_EQ(major_labels(fine).back(), "1.4\u00d710^6");
}

TEST(LinearTicks, InvalidRangesGiveNoTicks) {
  EXPECT_TRUE(linear_ticks(1.0, 1.0, 5).ticks.empty());
  EXPECT_TRUE(linear_ticks(2.0, 1.0, 5).ticks.empty());
  EXPECT_TRUE(linear_ticks(0.0, std::nan(""), 5).ticks.empty());
  EXPECT_TRUE(linear_ticks(-1e308, 1e308, 5).ticks.empty());  // the span overflows
}

TEST(LogTicks, OneThousandthToTenGivesDecadesWithMinorTicks) {
  const TickSet set = log_ticks(1e-3, 10.0, 8);
  EXPECT_EQ(major_values(set), (std::vector<double>{1e-3, 1e-2, 1e-1, 1.0, 10.0}));
  EXPECT_EQ(major_labels(set), (std::vector<std::string>{"0.001", "0.01", "0.1", "1", "10"}));
  EXPECT_EQ(set.step, 1.0);
  std::size_t minor = 0;
  for (const Tick& t : set.ticks) {
    minor += t.minor ? 1 : 0;
    EXPECT_EQ(t.minor, t.label.empty());
  }
  EXPECT_EQ(minor, 4u * 8u);  // 2..9 in each of the four decades
  for (std::size_t i = 1; i < set.ticks.size(); ++i) {
    EXPECT_LT(set.ticks[i - 1].value, set.ticks[i].value);
  }
}

TEST(LogTicks, ExpansionGoesToWholeDecades) {
  const TickSet set = log_ticks(0.2, 3000.0, 8, true, true);
  EXPECT_EQ(set.min, 0.1);
  EXPECT_EQ(set.max, 1e4);
  EXPECT_EQ(major_values(set), (std::vector<double>{0.1, 1.0, 10.0, 100.0, 1000.0, 1e4}));
}

TEST(LogTicks, ManyDecadesAreThinnedAndWrittenAsPowers) {
  const TickSet set = log_ticks(1e-12, 1e12, 6);
  EXPECT_EQ(set.step, 5.0);
  EXPECT_EQ(major_labels(set), (std::vector<std::string>{"10^-10", "10^-5", "10^0", "10^5", "10^10"}));
}

TEST(LogTicks, LessThanTwoDecadesUsesOneTwoFive) {
  EXPECT_EQ(major_values(log_ticks(2.0, 50.0, 8)), (std::vector<double>{2.0, 5.0, 10.0, 20.0, 50.0}));
  EXPECT_EQ(major_labels(log_ticks(0.02, 0.5, 8)), (std::vector<std::string>{"0.02", "0.05", "0.1", "0.2", "0.5"}));
  // Not even two 1-2-5 values: linear ticks, still inside the range.
  const TickSet narrow = log_ticks(2.1, 2.9, 5);
  ASSERT_GE(narrow.ticks.size(), 2u);
  EXPECT_GE(narrow.ticks.front().value, 2.1);
  EXPECT_LE(narrow.ticks.back().value, 2.9);
}

TEST(LogTicks, InvalidRangesGiveNoTicks) {
  EXPECT_TRUE(log_ticks(0.0, 1.0, 5).ticks.empty());
  EXPECT_TRUE(log_ticks(-1.0, 1.0, 5).ticks.empty());
  EXPECT_TRUE(log_ticks(1.0, 1.0, 5).ticks.empty());
}

TEST(FormatFixed, RoundsAndNeverPrintsNegativeZero) {
  EXPECT_EQ(format_fixed(0.25, 1), "0.2");  // round half to even, as printf
  EXPECT_EQ(format_fixed(-0.0001, 2), "0.00");
  EXPECT_EQ(format_fixed(-0.0, 0), "0");
  EXPECT_EQ(format_fixed(-1.5, 1), "-1.5");
  EXPECT_EQ(format_fixed(1234.5678, 2), "1234.57");
}

}  // namespace
}  // namespace shadelab
