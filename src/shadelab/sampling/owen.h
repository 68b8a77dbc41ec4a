// shadelab hash-based Owen scrambling and the path tracer's per-pixel sampler.
//
// Owen scrambling (Owen 1995, "Randomly permuted (t,m,s)-nets and (t,s)-sequences") flips every digit of a
// point depending on all the digits before it: in base 2, output bit k (from the top) = input bit k XOR a
// random function of input bits 0..k-1. A scrambled (t,m,s)-net is again a (t,m,s)-net, and each point is
// uniform on [0,1)^s, so estimates stay unbiased while keeping the net's stratification. The random functions
// come from a hash (Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020): on the bit-reversed
// value, every operation of the hash below only lets low bits change higher ones (x ^= x * even, x += seed,
// x *= odd), which is exactly the nested structure. The constants are those of N. Vegdahl's improved
// Laine-Karras hash ("Building a better LK hash", 2021), which randomizes the top bits better than the
// original Laine-Karras constants.
//
// The sampler follows Burley's section 4: the dimensions of a path come in groups of four; for group g of
// sample i in a pixel, the sample index is itself Owen-scrambled with a seed hashed from (pixel, g) (a
// shuffle within aligned power-of-two blocks, so the first 2^m samples are still a complete block of the
// Sobol sequence), then the four Sobol dimensions of the shuffled index are each Owen-scrambled with their
// own hashed seed. Within a group the points are a (0,2)-sequence in dimensions 0,1 and well stratified in
// all four; different groups and pixels are decorrelated by their seeds. Every value depends only on
// (pixel seed, sample index, dimension), never on what was drawn before, on the thread or on the shard.
#pragma once

#include <array>
#include <cstdint>

#include "shadelab/sampling/sobol.h"

namespace shadelab {

// SplitMix64's finalizer (Steele, Lea, Flood, "Fast splittable pseudorandom number generators", 2014).
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30u)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27u)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31u);
}

constexpr std::uint32_t reverse_bits(std::uint32_t x) {
  x = __builtin_bswap32(x);  // bytes reversed; then the bits within each byte
  x = ((x >> 4u) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4u);
  x = ((x >> 2u) & 0x33333333u) | ((x & 0x33333333u) << 2u);
  return ((x >> 1u) & 0x55555555u) | ((x & 0x55555555u) << 1u);
}

// The hash of owen_scramble in the bit-reversed domain, where every operation only lets low bits change
// higher ones (x ^= x * even, x += seed, x *= odd).
constexpr std::uint32_t owen_hash_reversed(std::uint32_t x, std::uint32_t seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16u) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

// A nested uniform (Owen) scramble of the 32-bit fixed-point number x in [0, 1) with the given seed.
constexpr std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(owen_hash_reversed(reverse_bits(x), seed));
}

namespace detail {

// The first four Sobol dimensions of the index whose bit-reversal is y, bit-reversed, by nibbles of y:
// entry [k][v][d] is the XOR of reverse_bits(V_d[31 - p]) over the set bits p = 4 k + b of v << 4k. Since bit
// reversal is linear over XOR, XOR-ing the eight entries of y gives reverse_bits(sobol_u32(reverse_bits(y), d)),
// which is what the scrambles below work on, without reversing the index and the points back and forth.
struct SobolReversedTable {
  std::uint32_t entry[8][16][sobol_dimensions];
};

constexpr SobolReversedTable sobol_reversed_table() {
  SobolReversedTable t{};
  for (int k = 0; k < 8; ++k) {
    for (std::uint32_t v = 0; v < 16; ++v) {
      for (int d = 0; d < sobol_dimensions; ++d) {
        std::uint32_t x = 0;
        for (int b = 0; b < 4; ++b) {
          if (((v >> b) & 1u) != 0u) x ^= reverse_bits(sobol_matrices[static_cast<std::size_t>(d)][static_cast<std::size_t>(31 - (4 * k + b))]);
        }
        t.entry[k][v][d] = x;
      }
    }
  }
  return t;
}

inline constexpr SobolReversedTable sobol_reversed = sobol_reversed_table();

}  // namespace detail

enum class SamplerKind {
  owen_sobol,   // the stratified sampler described above (the default)
  independent,  // independent uniform numbers, hashed from (pixel, sample, group, dimension): plain Monte
                // Carlo with the same indexing, for comparing convergence rates
};

// The samples of one pixel: sample `index` of the pixel with seed `pixel_seed`, in groups of four dimensions.
class PixelSampler {
 public:
  constexpr PixelSampler(std::uint64_t pixel_seed, std::uint32_t index, SamplerKind kind = SamplerKind::owen_sobol)
      : m_seed(pixel_seed), m_index_reversed(reverse_bits(index)), m_kind(kind) {}

  // Group g of this sample: four values in (0, 1), the scrambled 32-bit Sobol points x as (x + 1/2) 2^-32 (the
  // centre of their 2^-32 cell, so never 0 or 1). Per group: index shuffle = owen_scramble(index, seed_g),
  // point d = owen_scramble(sobol(shuffled, d), seed_g_d), all seeds hashed from (pixel seed, g).
  // Only the first `dims` (1..4) values are computed when fewer are needed; the others are left 0.5 (the
  // values computed do not depend on `dims`).
  std::array<double, 4> group(std::uint32_t g, int dims = sobol_dimensions) const {
    const std::uint64_t key = m_seed ^ (static_cast<std::uint64_t>(g) * 0xd1b54a32d192ed03ULL);
    const std::uint64_t h0 = mix64(key);  // three independent hashes of (pixel, group), computed side by side
    const std::uint64_t h1 = mix64(key ^ 0x2545f4914f6cdd1dULL);
    const std::uint64_t h2 = mix64(key ^ 0x9fb21c651e98df25ULL);
    const std::uint32_t seeds[sobol_dimensions] = {static_cast<std::uint32_t>(h0 >> 32u), static_cast<std::uint32_t>(h1),
                                                   static_cast<std::uint32_t>(h1 >> 32u), static_cast<std::uint32_t>(h2)};
    // The shuffled index, bit-reversed, then its Sobol point, bit-reversed (table above).
    const std::uint32_t y = owen_hash_reversed(m_index_reversed, static_cast<std::uint32_t>(h0));
    std::uint32_t xr[sobol_dimensions] = {0u, 0u, 0u, 0u};
    for (int k = 0; k < 8; ++k) {
      const std::uint32_t* e = detail::sobol_reversed.entry[k][(y >> (4 * k)) & 15u];
      for (int d = 0; d < sobol_dimensions; ++d) xr[d] ^= e[d];
    }
    std::array<double, 4> u{0.5, 0.5, 0.5, 0.5};
    if (m_kind == SamplerKind::independent) {
      const std::uint64_t k = mix64(h0 ^ (static_cast<std::uint64_t>(m_index_reversed) << 32u));
      for (int d = 0; d < dims; ++d) {
        u[static_cast<std::size_t>(d)] = static_cast<double>(mix64(k + static_cast<std::uint64_t>(d)) >> 11u) * 0x1.0p-53;
      }
      return u;
    }
    for (int d = 0; d < dims; ++d) {
      const std::uint32_t x = reverse_bits(owen_hash_reversed(xr[d], seeds[d]));
      u[static_cast<std::size_t>(d)] = (static_cast<double>(x) + 0.5) * 0x1.0p-32;
    }
    return u;
  }

 private:
  std::uint64_t m_seed;
  std::uint32_t m_index_reversed;
  SamplerKind m_kind;
};

}  // namespace shadelab
