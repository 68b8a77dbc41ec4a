// shadelab random numbers: PCG32 (O'Neill, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
// Algorithms for Random Number Generation", 2014), the XSH-RR output over a 64-bit LCG.
// Deterministic: the same (seed, stream) gives the same sequence on every platform and thread count.
#pragma once

#include <cstdint>

namespace shadelab {

class Pcg32 {
 public:
  explicit Pcg32(std::uint64_t seed = 0x853c49e6748fea9bULL, std::uint64_t stream = 0xda3e39cb94b95bdbULL) {
    reseed(seed, stream);
  }

  void reseed(std::uint64_t seed, std::uint64_t stream) {
    m_state = 0;
    m_inc = (stream << 1u) | 1u;
    next_u32();
    m_state += seed;
    next_u32();
  }

  std::uint32_t next_u32() {
    const std::uint64_t old = m_state;
    m_state = old * 6364136223846793005ULL + m_inc;  // LCG multiplier from PCG's reference code
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  // Uniform double in [0, 1) with 53 random bits.
  double next_double() {
    const std::uint64_t hi = next_u32();
    const std::uint64_t lo = next_u32();
    const std::uint64_t bits = ((hi << 32u) | lo) >> 11u;
    return static_cast<double>(bits) * 0x1.0p-53;
  }

 private:
  std::uint64_t m_state = 0;
  std::uint64_t m_inc = 1;
};

}  // namespace shadelab
