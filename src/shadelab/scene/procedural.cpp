#include "shadelab/scene/procedural.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace shadelab {

namespace {

// 64-bit mixing function: the finalizer of SplitMix64 (Steele, Lea & Flood, "Fast splittable pseudorandom
// number generators", OOPSLA 2014). Bijective, so distinct inputs never collide.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Uniform value in [0, 1) for lattice point (x, y) and seed: 53 high bits of the hash.
double hash01(std::uint64_t x, std::uint64_t y, std::uint64_t seed) {
  const std::uint64_t h = mix64(mix64(mix64(seed) ^ x) ^ (y * 0x9e3779b97f4a7c15ULL));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

// Perlin's quintic fade 6t^5 - 15t^4 + 10t^3 (Perlin, "Improving Noise", SIGGRAPH 2002).
double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

std::uint64_t wrap_index(double cell, int period) {
  const long long p = period;
  long long i = static_cast<long long>(cell) % p;
  if (i < 0) i += p;
  return static_cast<std::uint64_t>(i);
}

// Seeds for the independent noise fields of one texture: the user's seed mixed with a field number.
std::uint64_t field_seed(std::uint64_t seed, std::uint64_t field) { return mix64(seed ^ mix64(field + 1)); }

double texel_centre(int i, int size) { return (i + 0.5) / size; }

// Mean and standard deviation of a field, for turning it into z-scores.
void standardize(std::vector<double>& f) {
  double mean = 0.0;
  for (double x : f) mean += x;
  mean /= static_cast<double>(f.size());
  double var = 0.0;
  for (double x : f) var += (x - mean) * (x - mean);
  const double sd = std::sqrt(var / static_cast<double>(f.size()));
  // A constant field (size 1) has sd 0: leave it centred at 0.
  for (double& x : f) x = sd > 0.0 ? (x - mean) / sd : 0.0;
}

// The threshold t such that exactly `count` values of f are > t (f unchanged).
double threshold_for_count(const std::vector<double>& f, std::size_t count) {
  const std::size_t n = f.size();
  std::vector<double> s = f;
  std::sort(s.begin(), s.end());
  if (count == 0) return s.back() + 1.0;
  if (count >= n) return s.front() - 1.0;
  return 0.5 * (s[n - count - 1] + s[n - count]);  // between the largest dry and the smallest wet value
}

}  // namespace

double periodic_value_noise(double u, double v, int period_u, int period_v, std::uint64_t seed) {
  const double x = u * period_u;
  const double y = v * period_v;
  const double x0 = std::floor(x);
  const double y0 = std::floor(y);
  const double tx = fade(x - x0);
  const double ty = fade(y - y0);
  const std::uint64_t ix0 = wrap_index(x0, period_u);
  const std::uint64_t ix1 = wrap_index(x0 + 1.0, period_u);
  const std::uint64_t iy0 = wrap_index(y0, period_v);
  const std::uint64_t iy1 = wrap_index(y0 + 1.0, period_v);
  const double a = hash01(ix0, iy0, seed);
  const double b = hash01(ix1, iy0, seed);
  const double c = hash01(ix0, iy1, seed);
  const double d = hash01(ix1, iy1, seed);
  const double top = a + (b - a) * tx;
  const double bottom = c + (d - c) * tx;
  return top + (bottom - top) * ty;
}

double periodic_fbm(double u, double v, int period_u, int period_v, int octaves, double gain, std::uint64_t seed) {
  double sum = 0.0;
  double total = 0.0;
  double amplitude = 1.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * periodic_value_noise(u, v, period_u << o, period_v << o,
                                            field_seed(seed, 100u + static_cast<std::uint64_t>(o)));
    total += amplitude;
    amplitude *= gain;
  }
  return total > 0.0 ? sum / total : 0.0;
}

Image asphalt_diffuse(const AsphaltDiffuseOptions& options) {
  const int n = std::max(options.size, 1);
  Image image(n, n);
  const int stone_period = std::max(1, n / 6);  // aggregate grains about 6 texels across
  const Rgb tint{1.03, 1.0, 0.95};              // a slightly warm grey
  for (int j = 0; j < n; ++j) {
    const double v = texel_centre(j, n);
    for (int i = 0; i < n; ++i) {
      const double u = texel_centre(i, n);
      // Binder: low-frequency mottling of +-25% about the mean albedo.
      const double mottle = periodic_fbm(u, v, 4, 4, 4, 0.5, field_seed(options.seed, 1));
      double albedo = options.albedo * (0.75 + 0.5 * mottle);
      // Aggregate: grains where a fine noise is high, each 1.5-2.3 times lighter than the binder.
      const double grains = periodic_fbm(u, v, stone_period, stone_period, 2, 0.5, field_seed(options.seed, 2));
      const double tone = periodic_value_noise(u, v, stone_period, stone_period, field_seed(options.seed, 3));
      const double stone = options.albedo * (1.5 + 0.8 * tone);
      albedo += (stone - albedo) * smoothstep(0.60, 0.68, grains);
      // Speckle: single bright (quartz) and dark texels.
      const double h =
          hash01(static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j), field_seed(options.seed, 4));
      if (h > 0.95) albedo *= 1.7;
      if (h < 0.04) albedo *= 0.6;
      const double a = std::clamp(albedo, 0.0, 1.0);
      image.set(
          i, j,
          {std::clamp(a * tint.r, 0.02, 0.25), std::clamp(a * tint.g, 0.02, 0.25), std::clamp(a * tint.b, 0.02, 0.25)});
    }
  }
  return image;
}

Image asphalt_gloss(const AsphaltGlossOptions& options) {
  const int n = std::max(options.size, 1);
  const std::size_t count = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  std::vector<double> puddles(count);
  std::vector<double> streaks(count);
  for (int j = 0; j < n; ++j) {
    const double v = texel_centre(j, n);
    for (int i = 0; i < n; ++i) {
      const double u = texel_centre(i, n);
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i);
      // Puddles: fractal noise over a domain warped by two smoother noises, for ragged organic outlines.
      const double wu = u + 0.06 * (periodic_fbm(u, v, 4, 4, 3, 0.5, field_seed(options.seed, 16)) - 0.5);
      const double wv = v + 0.06 * (periodic_fbm(u, v, 4, 4, 3, 0.5, field_seed(options.seed, 17)) - 0.5);
      puddles[k] = periodic_fbm(wu, wv, 4, 4, 6, 0.5, field_seed(options.seed, 11));
      // Streaks (tyre tracks, run-off) along v: narrow bands across u (24 cells, constant along v), swaying
      // slowly with v, fading in and out along their length.
      const double sway = 0.02 * (periodic_fbm(0.0, v, 1, 3, 2, 0.5, field_seed(options.seed, 18)) - 0.5);
      const double streak = periodic_fbm(u + sway, v, 24, 1, 2, 0.5, field_seed(options.seed, 12));
      const double along = periodic_fbm(u, v, 3, 3, 2, 0.5, field_seed(options.seed, 13));
      streaks[k] = streak * (0.7 + 0.6 * along);
    }
  }
  // Wetness: the wetter of the two fields, each as a z-score; streaks a little rarer than puddles.
  standardize(puddles);
  standardize(streaks);
  std::vector<double> wetness(count);
  for (std::size_t k = 0; k < count; ++k) wetness[k] = std::max(puddles[k], streaks[k] - 0.6);
  const double fraction = std::clamp(options.wet_fraction, 0.0, 1.0);
  const auto wet_count = static_cast<std::size_t>(std::llround(fraction * static_cast<double>(count)));
  const double threshold = threshold_for_count(wetness, wet_count);
  const double rim = 0.25;  // half-width of the damp rim, in standard deviations of the wetness field

  const int grain_period = std::max(1, n / 16);
  Image image(n, n);
  for (int j = 0; j < n; ++j) {
    const double v = texel_centre(j, n);
    for (int i = 0; i < n; ++i) {
      const double u = texel_centre(i, n);
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i);
      // wet > 0.5 exactly where wetness > threshold, so wet_fraction of the texels are more wet than dry.
      const double wet = smoothstep(threshold - rim, threshold + rim, wetness[k]);
      const double dry_gloss =
          0.06 + 0.08 * periodic_fbm(u, v, grain_period, grain_period, 3, 0.5, field_seed(options.seed, 14));
      const double wet_gloss = 0.86 + 0.08 * periodic_fbm(u, v, 4, 4, 3, 0.5, field_seed(options.seed, 15));
      const double g = dry_gloss + (wet_gloss - dry_gloss) * wet;
      const double code = std::round(std::clamp(g, 0.0, 1.0) * 255.0) / 255.0;  // an 8-bit gloss map
      image.set(i, j, Rgb::gray(code));
    }
  }
  return image;
}

Image checker(const CheckerOptions& options) {
  const int n = std::max(options.size, 1);
  const int squares = std::max(options.squares, 1);
  Image image(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const long long cx = static_cast<long long>(i) * squares / n;
      const long long cy = static_cast<long long>(j) * squares / n;
      image.set(i, j, (cx + cy) % 2 == 0 ? options.colour_a : options.colour_b);
    }
  }
  return image;
}

}  // namespace shadelab
