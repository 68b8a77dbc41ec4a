// display: the display transform of rendered images (render/film.h, image/srgb.h), written once for the film
// output of both renderers and for the browser explorer's lit sphere (web/): multiply by 2^exposure, apply the
// clamp to [0, 1] or the filmic curve f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) (Narkowicz,
// "ACES Filmic Tone Mapping Curve", 2015), then encode with the sRGB transfer function of IEC 61966-2-1:1999
// (section 4.7: V = 12.92 L for L <= 0.0031308, else 1.055 L^(1/2.4) - 0.055) into 8-bit codes.

const real SRGB_ENCODE_BREAKPOINT = 0.0031308;  // linear value where the encoding switches segment
const real SRGB_LINEAR_SLOPE = 12.92;           // slope of the linear segment
const real SRGB_EXPONENT = 2.4;                 // exponent of the power segment
const real SRGB_SCALE = 1.055;                  // 1 + a
const real SRGB_OFFSET = 0.055;                 // a

// The linear factor of an exposure in stops.
inline real exposure_scale(real stops) {
  return exp2(stops);
}

inline real tone_clamp(real x) {
  return clamp(x, 0.0, 1.0);
}

// Narkowicz 2015, a fit of the ACES reference rendering transform; negative values (and NaN) map to 0.
inline real tone_filmic(real x) {
  real y = max(0.0, x);
  return clamp(y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14), 0.0, 1.0);
}

// Linear -> encoded sRGB value (IEC 61966-2-1 section 4.7); pow only above the breakpoint, where l > 0.
inline real linear_to_srgb(real l) {
  if (l <= SRGB_ENCODE_BREAKPOINT) return l * SRGB_LINEAR_SLOPE;
  return SRGB_SCALE * pow(l, 1.0 / SRGB_EXPONENT) - SRGB_OFFSET;
}

// The 8-bit code of a linear value: round half up of 255 x the encoding of the value clamped to [0, 1]
// (0 for NaN), as a real in [0, 255].
inline real srgb8_code(real l) {
  if (!(l > 0.0)) return 0.0;
  if (l >= 1.0) return 255.0;
  return floor(255.0 * linear_to_srgb(l) + 0.5);
}
