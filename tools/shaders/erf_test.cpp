// The shaders' erf (erf.sl, Abramowitz & Stegun 7.1.26) against std::erf: its stated bound 1.5e-7 holds, and it
// is odd. The .sl text is compiled here as C++ with the dialect's types (sl.h), exactly as exported.
#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/kernels/sl.h"

namespace shadelab::shaders::erf_sl {
using namespace shadelab::kernel;  // the dialect's real, abs, exp
#include "erf.sl"
}  // namespace shadelab::shaders::erf_sl

namespace shadelab::shaders {
namespace {

TEST(ShaderErf, WithinTheStatedBoundOfStdErf) {
  double worst = 0.0;
  for (int i = -80000; i <= 80000; ++i) {
    const double x = i * 1e-4;  // [-8, 8]
    worst = std::max(worst, std::abs(erf_sl::erf(x) - std::erf(x)));
  }
  EXPECT_LE(worst, 1.5e-7);  // A&S 7.1.26: |error| <= 1.5e-7
  EXPECT_GT(worst, 1e-9);    // it is the approximation, not std::erf
}

TEST(ShaderErf, OddAndLimits) {
  for (double x : {0.1, 0.7, 1.3, 2.9}) EXPECT_EQ(erf_sl::erf(-x), -erf_sl::erf(x));
  EXPECT_NEAR(erf_sl::erf(0.0), 0.0, 1.5e-7);
  EXPECT_NEAR(erf_sl::erf(10.0), 1.0, 1e-15);
}

}  // namespace
}  // namespace shadelab::shaders
