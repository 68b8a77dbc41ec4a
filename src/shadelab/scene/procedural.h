// shadelab procedural textures: generated in code, deterministic from a seed, tileable (they wrap around in
// both directions, as sample_texture does), so a scene needs no image files for them.
//
// - asphalt_diffuse: the diffuse colour of dry asphalt: a dark grey binder with low-frequency mottling and
//   a speckle of light and dark aggregate. Linear albedo in [0.02, 0.25] with a mean near `albedo`
//   (0.08 by default: asphalt is among the darkest common surfaces, sRGB codes around 60-100).
// - asphalt_gloss: the gloss map of the zoo article's wet/dry asphalt (Schüler 2011, "Blinn-Phong
//   Normalization Zoo": "all the surface variation went into the glossiness map ... black represents a
//   single-digit exponent ... white represents an exponent in the thousands"). Dry rough asphalt has gloss
//   0.06-0.14 (exponents 3 to 6 under the default GlossEncoding 2..8192); puddles and wet streaks have gloss
//   0.86-0.94 (exponents 2600 to 5000); between them a smooth damp rim. The puddles are smooth fractal
//   noise, the streaks are noise stretched along v (tyre tracks, run-off); the threshold between wet and dry
//   is the quantile of that wetness field that makes exactly `wet_fraction` of the texels more wet than dry.
//   Values are quantized to 8-bit codes (k / 255) like a gloss map read from a PNG, and R = G = B.
// - checker: `squares` x `squares` squares of two colours, square (0, 0) colour_a.
//
// Contract: every generator returns a size x size Image (size >= 1), identical for identical options on
// every platform (integer hashing, no global state, no threads); different seeds give different textures.
// The options are assumed valid (the scene parser checks them: size in [1, 8192], fractions in [0, 1]).
#pragma once

#include <cstdint>

#include "shadelab/color/rgb.h"
#include "shadelab/image/image.h"

namespace shadelab {

struct AsphaltDiffuseOptions {
  int size = 512;
  std::uint64_t seed = 1;
  double albedo = 0.08;  // mean albedo of the binder before speckle
};

struct AsphaltGlossOptions {
  int size = 512;
  std::uint64_t seed = 1;
  double wet_fraction = 0.3;  // fraction of the texels that are more wet than dry (gloss above the midpoint)
};

struct CheckerOptions {
  int size = 256;
  int squares = 8;  // per side
  Rgb colour_a{0.8, 0.8, 0.8};
  Rgb colour_b{0.2, 0.2, 0.2};
};

Image asphalt_diffuse(const AsphaltDiffuseOptions& options);
Image asphalt_gloss(const AsphaltGlossOptions& options);
Image checker(const CheckerOptions& options);

// Tileable value noise in [0, 1] at texture coordinates (u, v): lattice values hashed from the lattice
// point modulo `period` (so the noise repeats every 1 in u and v) and the seed, interpolated with Perlin's
// quintic fade. Exposed for the tests.
double periodic_value_noise(double u, double v, int period_u, int period_v, std::uint64_t seed);

// Fractal sum of `octaves` periodic_value_noise octaves, the periods doubling and the amplitudes scaled by
// `gain` per octave, normalized by the total amplitude so the result stays in [0, 1].
double periodic_fbm(double u, double v, int period_u, int period_v, int octaves, double gain, std::uint64_t seed);

}  // namespace shadelab
