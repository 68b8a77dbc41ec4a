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

// ---- View transforms (docs/color.md): scene-linear Rec.709 (the working space) -> linear display values in [0, 1]
// of the sRGB display, which srgb8_code then encodes. Every view first takes negative values (and NaN) to 0.
// VIEW_* numbers the views for a shader's uniform (view_transform); render/film.h's ViewTransform matches them.
const int VIEW_STANDARD = 0;
const int VIEW_FILMIC = 1;
const int VIEW_PBR_NEUTRAL = 2;
const int VIEW_AGX = 3;
const int VIEW_ACES = 4;

inline rgb view_nonnegative(rgb c) {
  return rgb(max(0.0, c.r), max(0.0, c.g), max(0.0, c.b));
}

inline rgb view_clamp01(rgb c) {
  return rgb(clamp(c.r, 0.0, 1.0), clamp(c.g, 0.0, 1.0), clamp(c.b, 0.0, 1.0));
}

// The product of the matrix with rows r0, r1, r2 and the column c.
inline rgb view_matrix(rgb r0, rgb r1, rgb r2, rgb c) {
  return rgb(r0.r * c.r + r0.g * c.g + r0.b * c.b, r1.r * c.r + r1.g * c.g + r1.b * c.b,
             r2.r * c.r + r2.g * c.g + r2.b * c.b);
}

// standard: the clamp to [0, 1] (the sRGB display of the values as they are; today's default of render).
inline rgb view_standard(rgb c) {
  return view_clamp01(view_nonnegative(c));
}

// filmic: Narkowicz 2015's curve per channel (tone_filmic above).
inline rgb view_filmic(rgb c) {
  return rgb(tone_filmic(c.r), tone_filmic(c.g), tone_filmic(c.b));
}

// pbr-neutral: the Khronos PBR Neutral tone mapper, its specification (KhronosGroup/ToneMapping,
// PBR_Neutral/README.md, 2024): F90 = 0.04, Ks = 0.8 - F90, Kd = 0.15; x = min(R, G, B);
// f = x - x^2 / (4 F90) for x <= 2 F90, else F90; p = max(c - f); out = c - f for p <= Ks, else
// (c - f) (pn / p) g + pn (1 - g) with pn = 1 - (1 - Ks)^2 / (p + 1 - 2 Ks) and g = 1 / (Kd (p - pn) + 1).
const real PBR_NEUTRAL_F90 = 0.04;
const real PBR_NEUTRAL_KS = 0.76;  // 0.8 - F90: where highlight compression starts
const real PBR_NEUTRAL_KD = 0.15;  // speed of desaturation
inline rgb view_pbr_neutral(rgb c_in) {
  rgb c = view_nonnegative(c_in);
  real x = min(c.r, min(c.g, c.b));
  real f = PBR_NEUTRAL_F90;
  if (x <= 2.0 * PBR_NEUTRAL_F90) f = x - x * x / (4.0 * PBR_NEUTRAL_F90);
  c = c - f;
  real p = max(c.r, max(c.g, c.b));
  if (p <= PBR_NEUTRAL_KS) return c;
  // p > Ks > 0 here, and p + 1 - 2 Ks > 1 - Ks > 0: both divisions are safe.
  real pn = 1.0 - (1.0 - PBR_NEUTRAL_KS) * (1.0 - PBR_NEUTRAL_KS) / (p + 1.0 - 2.0 * PBR_NEUTRAL_KS);
  real g = 1.0 / (PBR_NEUTRAL_KD * (p - pn) + 1.0);  // p > pn, so the divisor is > 1
  return c * (pn / p * g) + rgb(pn * (1.0 - g));
}

// agx: Blender 4's "AgX Base" (Troy Sobotka's AgX) in the closed form Filament published (google/filament,
// ToneMapper.cpp, AgxToneMapper, 2023) and three.js adopted (AgXToneMapping, r160): linear Rec.709 -> linear
// Rec.2020, the inset matrix, log2 encoding over [-12.47393, 4.026069] (= log2(0.18) + [-10, 6.5] stops), the
// sigmoid as Wrensch's 6th-order polynomial fit (iolite-engine.com, "Minimal AgX Implementation", 2023), the
// outset matrix, a 2.2 power back to linear, linear Rec.2020 -> Rec.709, clamp to [0, 1]. No look.
const real AGX_MIN_EV = -12.47393;
const real AGX_MAX_EV = 4.026069;
// Linear Rec.709 -> linear Rec.2020 (both D65): RGB->XYZ of the ITU-R BT.709 primaries followed by XYZ->RGB of
// the BT.2020 primaries, derived from the primaries in double precision (display_view_test.cpp derives it again).
inline rgb agx_rec709_to_rec2020(rgb c) {
  return view_matrix(rgb(0.6274038959346989, 0.32928303837788386, 0.04331306568741722),
                     rgb(0.06909728935823202, 0.9195403950754589, 0.011362315566309166),
                     rgb(0.016391438875150228, 0.08801330787722579, 0.895595253247624), c);
}
inline rgb agx_rec2020_to_rec709(rgb c) {
  return view_matrix(rgb(1.6604910021084345, -0.5876411387885498, -0.07284986331988487),
                     rgb(-0.12455047452159065, 1.1328998971259598, -0.008349422604369465),
                     rgb(-0.01815076335490522, -0.10057889800800743, 1.1187296613629125), c);
}
// Filament's AgxInsetMatrix and the inverse of its AgxOutsetMatrixInv (the published values, rows; each row sums
// to 1, so greys stay grey).
inline rgb agx_inset(rgb c) {
  return view_matrix(rgb(0.856627153315983, 0.0951212405381588, 0.0482516061458583),
                     rgb(0.137318972929847, 0.761241990602591, 0.101439036467562),
                     rgb(0.11189821299995, 0.0767994186031903, 0.811302368396859), c);
}
inline rgb agx_outset(rgb c) {
  return view_matrix(rgb(1.1271005818144368, -0.11060664309660323, -0.016493938717834573),
                     rgb(-0.1413297634984383, 1.157823702216272, -0.016493938717834257),
                     rgb(-0.14132976349843826, -0.11060664309660294, 1.2519364065950405), c);
}
// log2 encoding of one channel, clamped to [0, 1]; values below 1e-10 count as 1e-10 (log2 needs x > 0).
inline real agx_log_encode(real x) {
  return clamp((log2(max(x, 1.0e-10)) - AGX_MIN_EV) / (AGX_MAX_EV - AGX_MIN_EV), 0.0, 1.0);
}
// Wrensch's polynomial fit of the AgX Base sigmoid on [0, 1].
inline real agx_sigmoid(real x) {
  real x2 = x * x;
  real x4 = x2 * x2;
  return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
}
// The 2.2 power back to linear; 0 at and below 0 (pow needs x > 0).
inline real agx_linearize(real x) {
  if (x <= 0.0) return 0.0;
  return pow(x, 2.2);
}
inline rgb view_agx(rgb c_in) {
  rgb c = agx_inset(agx_rec709_to_rec2020(view_nonnegative(c_in)));
  c = rgb(agx_sigmoid(agx_log_encode(c.r)), agx_sigmoid(agx_log_encode(c.g)), agx_sigmoid(agx_log_encode(c.b)));
  c = agx_outset(c);
  c = rgb(agx_linearize(c.r), agx_linearize(c.g), agx_linearize(c.b));
  return view_clamp01(agx_rec2020_to_rec709(c));
}

// aces: Stephen Hill's fit of the ACES 1.0 RRT + sRGB ODT (github.com/TheRealMJP/BakingLab, ACES.hlsl, 2016):
// sRGB -> ACES AP1 with the RRT's saturation (ACESInputMat), the rational fit
// (v (v + 0.0245786) - 0.000090537) / (v (0.983729 v + 0.4329510) + 0.238081), the ODT's saturation -> sRGB
// (ACESOutputMat), clamp to [0, 1]. No exposure factor (three.js's ACESFilmicToneMapping divides by 0.6; this does not).
inline real aces_rrt_odt_fit(real v) {
  return (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);  // divisor >= 0.238
}
inline rgb view_aces(rgb c_in) {
  rgb c = view_matrix(rgb(0.59719, 0.35458, 0.04823), rgb(0.07600, 0.90834, 0.01566), rgb(0.02840, 0.13383, 0.83777),
                      view_nonnegative(c_in));
  c = rgb(aces_rrt_odt_fit(c.r), aces_rrt_odt_fit(c.g), aces_rrt_odt_fit(c.b));
  return view_clamp01(view_matrix(rgb(1.60475, -0.53108, -0.07367), rgb(-0.10208, 1.10813, -0.00605),
                                  rgb(-0.00327, -0.07276, 1.07602), c));
}

// The view numbered `view` (VIEW_*) of the linear colour c after 2^exposure_stops: linear display values in [0, 1].
inline rgb view_transform(int view, real exposure_stops, rgb c_in) {
  rgb c = c_in * exposure_scale(exposure_stops);
  if (view == VIEW_FILMIC) return view_filmic(c);
  if (view == VIEW_PBR_NEUTRAL) return view_pbr_neutral(c);
  if (view == VIEW_AGX) return view_agx(c);
  if (view == VIEW_ACES) return view_aces(c);
  return view_standard(c);
}
