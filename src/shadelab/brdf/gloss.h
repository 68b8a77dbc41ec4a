// shadelab gloss maps: the zoo article's logarithmic encoding of the Blinn-Phong exponent in a texture
// ("black represents a single-digit exponent, white an exponent in the thousands"; Schüler 2011).
//
//   n(g) = n_black (n_white / n_black)^g,   g = log(n / n_black) / log(n_white / n_black)
//
// with defaults n_black = 2 and n_white = 8192 (= 2^(1 + 12 g)), the range of 8-bit gloss maps used in
// production (Lazarov, "Physically-based lighting in Call of Duty: Black Ops", SIGGRAPH 2011, used 2^(13 g)).
// The exponent's Beckmann equivalent is m = sqrt(2 / (n + 2)) (microfacet.h).
#pragma once

#include <cstdint>

#include "shadelab/core/error.h"

namespace shadelab {

// The Phong exponent (R.L)^n of a Blinn-Phong lobe (N.H)^n: n / 4 (the half vector turns half as fast as L,
// so the two lobes have the same angular width near their peak; envmap/specular/prefilter.h).
constexpr double phong_exponent_from_blinn_phong(double n_blinn) { return n_blinn / 4.0; }

struct GlossEncoding {
  double n_black = 2.0;     // exponent stored as gloss 0
  double n_white = 8192.0;  // exponent stored as gloss 1

  // Checks 0 < n_black < n_white, both finite.
  Result<GlossEncoding> validated() const;

  double exponent_from_gloss(double g) const;  // g in [0, 1], clamped
  double gloss_from_exponent(double n) const;  // clamped to [0, 1]
  // 8-bit texel value <-> exponent (value / 255 is the gloss).
  double exponent_from_texel(std::uint8_t value) const { return exponent_from_gloss(value / 255.0); }
  std::uint8_t texel_from_exponent(double n) const;
};

}  // namespace shadelab
