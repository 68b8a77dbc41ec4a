// shadelab plot ticks (contract in ticks.h).
#include "shadelab/plot/ticks.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <system_error>

namespace shadelab {
namespace {

// Relative slack for "is this value on the range end": range ends often come from data that is a decimal
// number computed in binary (0.30000000000000004).
constexpr double tick_slack = 1e-9;

// 10^k, correctly rounded for |k| <= 22 (exact powers, or 1 / exact power for k < 0).
double pow10(int k) {
  if (k >= 0) {
    return std::pow(10.0, static_cast<double>(k));
  }
  return 1.0 / std::pow(10.0, static_cast<double>(-k));
}

// A step m x 10^e with m in {1, 2, 5}, and the tick value k * step computed as one correctly rounded
// operation on integers, so that the third tick of step 0.2 is 0.6, not 0.6000000000000001.
struct Step {
  int mantissa = 1;
  int exponent = 0;

  double value() const { return value_at(1); }
  double value_at(long long k) const {
    const double n = static_cast<double>(k) * static_cast<double>(mantissa);
    return exponent >= 0 ? n * pow10(exponent) : n / pow10(-exponent);
  }
  Step next() const {
    if (mantissa == 1) {
      return {2, exponent};
    }
    if (mantissa == 2) {
      return {5, exponent};
    }
    return {1, exponent + 1};
  }
};

// The smallest 1-2-5 step >= raw.
Step nice_step_of(double raw) {
  if (!(raw > 1e-300) || !(raw < 1e300)) {
    return {1, 0};  // callers pass a finite positive step; never loop on 0, Inf or NaN
  }
  Step s{1, static_cast<int>(std::floor(std::log10(raw)))};
  // log10 may land one decade high or low near exact powers; walk to the right place.
  while (s.value() > raw && s.exponent > -400) {
    s = {1, s.exponent - 1};
  }
  while (s.value() < raw * (1.0 - 1e-12)) {
    s = s.next();
  }
  return s;
}

std::string chars(double value, std::chars_format format, int precision) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, format, precision);
  if (result.ec != std::errc()) {
    return "?";
  }
  return std::string(buffer.data(), result.ptr);
}

// "m×10^e" with `decimals` digits in the mantissa; 0 stays "0".
std::string format_scientific(double value, int decimals) {
  if (value == 0.0) {
    return "0";
  }
  const std::string s = chars(value, std::chars_format::scientific, std::max(0, decimals));
  const auto e = s.find('e');
  if (e == std::string::npos) {
    return s;
  }
  const int exponent = std::atoi(s.c_str() + e + 1);
  return s.substr(0, e) + "\u00d710^" + std::to_string(exponent);
}

// floor(a / b) for b > 0, also for negative a.
long long floor_div(long long a, long long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

}  // namespace

double nice_step(double raw) { return nice_step_of(raw).value(); }

std::string format_fixed(double value, int decimals) {
  std::string s = chars(value, std::chars_format::fixed, std::clamp(decimals, 0, 40));
  if (!s.empty() && s[0] == '-' && s.find_first_not_of("0.", 1) == std::string::npos) {
    s.erase(0, 1);  // -0.00 -> 0.00
  }
  return s;
}

TickSet linear_ticks(double lo, double hi, int max_count, bool expand_lo, bool expand_hi) {
  TickSet set;
  set.min = lo;
  set.max = hi;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi) || !std::isfinite(hi - lo)) {
    return set;
  }
  max_count = std::max(2, max_count);
  const double span = hi - lo;

  // Start below the answer (a step giving about 2 * max_count ticks) and walk up the 1-2-5 sequence until
  // the tick count fits; the count only falls as the step grows.
  Step step = nice_step_of(span / (2.0 * max_count));
  long long k_lo = 0;
  long long k_hi = 0;
  for (;;) {
    const double s = step.value();
    const double a = lo / s;
    const double b = hi / s;
    k_lo = static_cast<long long>(expand_lo ? std::floor(a + tick_slack) : std::ceil(a - tick_slack));
    k_hi = static_cast<long long>(expand_hi ? std::ceil(b - tick_slack) : std::floor(b + tick_slack));
    if (k_hi - k_lo + 1 <= max_count) {
      break;
    }
    step = step.next();
  }

  if (expand_lo) {
    set.min = step.value_at(k_lo);
  }
  if (expand_hi) {
    set.max = step.value_at(k_hi);
  }
  set.step = step.value();

  const double largest = std::max(std::abs(set.min), std::abs(set.max));
  const bool scientific = largest >= 1e6 || largest < 1e-4;
  for (long long k = k_lo; k <= k_hi; ++k) {
    const double v = step.value_at(k);  // k = 0 gives +0 exactly
    std::string label;
    if (scientific) {
      // One exponent for the whole axis, that of the largest magnitude: 0.5×10^7, 1.0×10^7, ...
      const int e = static_cast<int>(std::floor(std::log10(largest) + tick_slack));
      label = v == 0.0 ? std::string("0")
                       : format_fixed(v / pow10(e), std::max(0, e - step.exponent)) + "\u00d710^" + std::to_string(e);
    } else {
      label = format_fixed(v, std::max(0, -step.exponent));
    }
    set.ticks.push_back({v, std::move(label), false});
  }
  return set;
}

TickSet log_ticks(double lo, double hi, int max_count, bool expand_lo, bool expand_hi) {
  TickSet set;
  set.min = lo;
  set.max = hi;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo > 0.0) || !(lo < hi)) {
    return set;
  }
  max_count = std::max(2, max_count);

  double a = std::log10(lo);
  double b = std::log10(hi);
  if (expand_lo) {
    a = std::floor(a + tick_slack);
    set.min = pow10(static_cast<int>(a));
  }
  if (expand_hi) {
    b = std::ceil(b - tick_slack);
    set.max = pow10(static_cast<int>(b));
  }
  const auto first_decade = static_cast<long long>(std::ceil(a - tick_slack));
  const auto last_decade = static_cast<long long>(std::floor(b + tick_slack));
  const double slack_lo = set.min * tick_slack;
  const double slack_hi = set.max * tick_slack;

  if (last_decade - first_decade + 1 >= 2) {
    // Labelled decades every d-th decade, d from 1, 2, 5, 10, ...
    Step d{1, 0};
    long long major_lo = 0;
    long long major_hi = 0;
    for (;;) {
      const auto dv = static_cast<long long>(d.value());
      major_lo = -floor_div(-first_decade, dv);  // ceil(first / d)
      major_hi = floor_div(last_decade, dv);
      if (major_hi - major_lo + 1 <= max_count) {
        break;
      }
      d = d.next();
    }
    const auto dv = static_cast<long long>(d.value());
    set.step = d.value();

    bool plain = true;
    for (long long j = major_lo; j <= major_hi; ++j) {
      plain = plain && j * dv >= -3 && j * dv <= 4;
    }
    for (long long k = first_decade; k <= last_decade; ++k) {
      const double v = pow10(static_cast<int>(k));
      if (k - floor_div(k, dv) * dv == 0) {
        std::string label = plain ? format_fixed(v, static_cast<int>(std::max(0LL, -k))) : "10^" + std::to_string(k);
        set.ticks.push_back({v, std::move(label), false});
      } else if (last_decade - first_decade < 4LL * max_count) {
        set.ticks.push_back({v, {}, true});
      }
    }
    if (dv == 1) {
      for (long long k = first_decade - 1; k <= last_decade; ++k) {
        for (int m = 2; m <= 9; ++m) {
          const double v = Step{m, static_cast<int>(k)}.value();
          if (v >= set.min - slack_lo && v <= set.max + slack_hi) {
            set.ticks.push_back({v, {}, true});
          }
        }
      }
    }
    std::stable_sort(set.ticks.begin(), set.ticks.end(),
                     [](const Tick& x, const Tick& y) { return x.value < y.value; });
    return set;
  }

  // Fewer than two decades: 1, 2, 5 x 10^k.
  for (long long k = first_decade - 1; k <= last_decade; ++k) {
    for (int m : {1, 2, 5}) {
      const Step s{m, static_cast<int>(k)};
      const double v = s.value();
      if (v >= set.min - slack_lo && v <= set.max + slack_hi) {
        std::string label = set.max >= 1e6 || set.min < 1e-4 ? format_scientific(v, 0)
                                                             : format_fixed(v, static_cast<int>(std::max(0LL, -k)));
        set.ticks.push_back({v, std::move(label), false});
      }
    }
  }
  if (set.ticks.size() >= 2) {
    return set;
  }
  // Less than a 1-2-5 interval: linear ticks on the log axis.
  TickSet linear = linear_ticks(set.min, set.max, max_count);
  linear.step = 0.0;
  return linear;
}

}  // namespace shadelab
