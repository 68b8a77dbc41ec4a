// shadelab sRGB transfer function: the exact piecewise curve of IEC 61966-2-1:1999 (not a 2.2 gamma).
//
// Contract: srgb_to_linear decodes an encoded value V in [0, 1] to linear light L in [0, 1]; linear_to_srgb
// is its inverse. Outside [0, 1] both follow their segment's formula (the linear segment below the
// breakpoint, the power segment above), NaN stays NaN. linear_to_srgb8 clamps to [0, 1] first (NaN -> 0)
// and rounds to the nearest 8-bit code. The decode tables hold the formula evaluated in double precision
// and rounded once to float; srgb8_to_linear_table()[k] is srgb_to_linear(k / 255.0). The tables are built
// on first use (thread-safe) and live for the program's lifetime.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "shadelab/kernels/kernels.h"

namespace shadelab {

// IEC 61966-2-1:1999, section 4.7 (encoding) and 5.2 (decoding); the published constants.
inline constexpr double srgb_decode_breakpoint = 0.04045;    // encoded value where decoding switches segment
inline constexpr double srgb_encode_breakpoint = 0.0031308;  // linear value where encoding switches segment
inline constexpr double srgb_linear_slope = 12.92;           // slope of the linear segment
inline constexpr double srgb_exponent = 2.4;                 // exponent of the power segment
inline constexpr double srgb_scale = 1.055;                  // 1 + a, with a = 0.055
inline constexpr double srgb_offset = 0.055;                 // a

// Encoded sRGB value -> linear. IEC 61966-2-1: L = V / 12.92 for V <= 0.04045, else ((V + 0.055) / 1.055)^2.4.
inline double srgb_to_linear(double v) {
  if (v <= srgb_decode_breakpoint) {
    return v / srgb_linear_slope;
  }
  return std::pow((v + srgb_offset) / srgb_scale, srgb_exponent);
}

// Linear -> encoded sRGB value. IEC 61966-2-1: V = 12.92 L for L <= 0.0031308, else 1.055 L^(1/2.4) - 0.055
// (the kernel kernels/display.sl, shared with the explorer's WebGL sphere).
inline double linear_to_srgb(double l) { return kernel::linear_to_srgb(l); }

// Linear -> 8-bit sRGB code: round(255 * linear_to_srgb(clamp(l, 0, 1))); NaN gives 0 (kernels/display.sl).
inline std::uint8_t linear_to_srgb8(double l) {
  // srgb8_code is an integer in [0, 255], so the cast is exact.
  return static_cast<std::uint8_t>(kernel::srgb8_code(l));
}

// srgb_to_linear(k / 255) for the 256 codes of an 8-bit channel.
const std::array<float, 256>& srgb8_to_linear_table();

// srgb_to_linear(k / 65535) for the 65536 codes of a 16-bit channel.
const std::vector<float>& srgb16_to_linear_table();

}  // namespace shadelab
