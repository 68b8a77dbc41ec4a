// shadelab exact accumulation of path samples: a sum that does not depend on how the samples are grouped.
//
// Floating-point addition is not associative, so a pixel summed over samples 0..99 in one go and the same
// pixel summed as (0..49) + (50..99) on two machines can differ in the last bits. Here every sample's radiance
// v (per channel) is first rounded to a fixed-point number
//   q = round_half_even(v * 2^40)           (one rounding, exact in IEEE double: v * 2^40 is a power-of-2 scaling)
// and the q are added as signed 128-bit integers, which is exact and associative: the sum of any split of the
// samples, added in any order, is the same integer. The pixel value is then double(sum) * 2^-40 / n.
//
// Precision: each sample moves by at most 2^-41 (4.5e-13) in absolute terms, so the mean moves by at most that
// too: below the float ulp of the written value for every pixel brighter than about 4e-6 W m^-2 sr^-1, and far
// below any Monte Carlo noise. Range: |v| is clamped to 2^52 (4.5e15; the sun is about 2e7 in these units) so
// that 2^31 samples of 2^(52+40) can never overflow 127 bits. A NaN or infinite sample adds 0 and is counted.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "shadelab/color/rgb.h"

namespace shadelab {

__extension__ typedef __int128 Int128;  // GCC and Clang; -Wpedantic knows no 128-bit type
__extension__ typedef unsigned __int128 UInt128;

inline constexpr int fixed_point_bits = 40;
inline constexpr double fixed_point_clamp = 0x1.0p52;
inline constexpr double fixed_point_scale = static_cast<double>(std::uint64_t{1} << fixed_point_bits);  // 2^40
inline constexpr double fixed_point_inv_scale = 1.0 / fixed_point_scale;  // 2^-40, exact (a power of 2)

// std::nearbyint in the default rounding mode (to nearest, ties to even), without the library call the
// baseline x86-64 ISA needs: below 2^52 in magnitude, y + 2^52 has no fraction bits left, so the addition
// rounds y to an integer by the current mode and subtracting 2^52 again is exact; from 2^52 on y is an integer.
// (Needs strict IEEE evaluation: no fast-math, which the project never uses.)
inline double round_half_even(double y) {
  constexpr double big = 0x1.0p52;
  if (!(std::abs(y) < big)) return y;
  return y >= 0.0 ? (y + big) - big : (y - big) + big;
}

struct FixedRgb {
  Int128 c[3] = {0, 0, 0};

  // Adds one sample; returns false (and adds nothing) when a channel is NaN or infinite.
  bool add(const Rgb& v) {
    const double ch[3] = {v.r, v.g, v.b};
    Int128 q[3];
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(ch[k])) return false;
      const double x = std::clamp(ch[k], -fixed_point_clamp, fixed_point_clamp);
      // x * 2^40 is exact (a power-of-2 scaling of a value at most 2^52, so no overflow, and no underflow when
      // scaling up), as std::ldexp(x, 40) is. Integers below 2^63 in magnitude (any sample below about 8e6)
      // convert through int64, exactly and without the 128-bit conversion routine; the rest through Int128.
      const double r = round_half_even(x * fixed_point_scale);
      q[k] = std::abs(r) < 0x1.0p63 ? static_cast<Int128>(static_cast<std::int64_t>(r)) : static_cast<Int128>(r);
    }
    for (int k = 0; k < 3; ++k) c[k] += q[k];
    return true;
  }

  FixedRgb& operator+=(const FixedRgb& o) {
    for (int k = 0; k < 3; ++k) c[k] += o.c[k];
    return *this;
  }
  bool operator==(const FixedRgb& o) const { return c[0] == o.c[0] && c[1] == o.c[1] && c[2] == o.c[2]; }

  // The mean of n samples (0 when n is 0): double(sum) 2^-40 / n, the same arithmetic wherever it is done.
  Rgb mean(std::uint64_t n) const {
    if (n == 0) return {};
    const auto d = static_cast<double>(n);
    // double(c) is 0 or at least 1 in magnitude, so the scaling by 2^-40 is exact (no subnormal), as ldexp's.
    return {static_cast<double>(c[0]) * fixed_point_inv_scale / d, static_cast<double>(c[1]) * fixed_point_inv_scale / d,
            static_cast<double>(c[2]) * fixed_point_inv_scale / d};
  }
};

// A 128-bit value as four 32-bit words, least significant first (two's complement), for files.
inline std::array<std::uint32_t, 4> to_words(Int128 v) {
  const auto u = static_cast<UInt128>(v);
  return {static_cast<std::uint32_t>(u), static_cast<std::uint32_t>(u >> 32u), static_cast<std::uint32_t>(u >> 64u),
          static_cast<std::uint32_t>(u >> 96u)};
}
inline Int128 from_words(const std::array<std::uint32_t, 4>& w) {
  const UInt128 u = static_cast<UInt128>(w[0]) | (static_cast<UInt128>(w[1]) << 32u) | (static_cast<UInt128>(w[2]) << 64u) |
                    (static_cast<UInt128>(w[3]) << 96u);
  return static_cast<Int128>(u);
}

}  // namespace shadelab
