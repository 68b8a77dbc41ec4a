// shadelab Sobol sequence, the first four dimensions, as 32-bit fixed-point numbers in [0, 1).
//
//   x_d(i) = XOR over the set bits j of i of V_d[j],  V_d[j] = m_{d,j+1} 2^(31-j)        (Sobol 1967)
// with the direction numbers m of Joe and Kuo ("Constructing Sobol sequences with better two-dimensional
// projections", SIAM J. Sci. Comput. 30, 2008; file new-joe-kuo-6.21201): dimension 0 is the van der Corput
// sequence (m_j = 1), and dimensions 1..3 use the primitive polynomials of degree s with coefficient bits a
// and initial numbers m_1..m_s:
//   d = 1: s = 1, a = 0, m = (1)      (the matrix is Pascal's triangle mod 2)
//   d = 2: s = 2, a = 1, m = (1, 3)
//   d = 3: s = 3, a = 1, m = (1, 3, 1)
// and the recurrence m_k = 2 a_1 m_{k-1} ^ 4 a_2 m_{k-2} ^ ... ^ 2^(s-1) a_{s-1} m_{k-s+1} ^ 2^s m_{k-s} ^ m_{k-s}
// (Bratley and Fox, ACM TOMS 14, 1988, algorithm 659).
//
// Every dimension is a (0,1)-sequence and dimensions 0 and 1 together a (0,2)-sequence: the first 2^m points
// put exactly one point into every dyadic box of area 2^-m. Points are computed by index (no state), so any
// sample can be drawn alone, in any order, on any thread or machine.
#pragma once

#include <array>
#include <cstdint>

namespace shadelab {

inline constexpr int sobol_dimensions = 4;

namespace detail {

struct SobolPolynomial {
  int degree;           // s
  std::uint32_t a;      // the inner coefficient bits a_1 .. a_{s-1}, a_1 the most significant
  std::uint32_t m[3];   // initial direction numbers m_1 .. m_s (odd, m_k < 2^k)
};

constexpr std::array<std::uint32_t, 32> sobol_matrix(int dimension) {
  std::array<std::uint32_t, 32> v{};
  if (dimension == 0) {
    for (int j = 0; j < 32; ++j) v[static_cast<std::size_t>(j)] = 1u << (31 - j);
    return v;
  }
  constexpr SobolPolynomial polynomials[3] = {{1, 0u, {1u, 0u, 0u}}, {2, 1u, {1u, 3u, 0u}}, {3, 1u, {1u, 3u, 1u}}};
  const SobolPolynomial& p = polynomials[dimension - 1];
  std::uint32_t m[33] = {};  // m[1..32]
  for (int k = 1; k <= p.degree; ++k) m[k] = p.m[k - 1];
  for (int k = p.degree + 1; k <= 32; ++k) {
    std::uint32_t mk = m[k - p.degree] ^ (m[k - p.degree] << p.degree);
    for (int i = 1; i < p.degree; ++i) {
      const std::uint32_t ai = (p.a >> (p.degree - 1 - i)) & 1u;
      if (ai != 0u) mk ^= m[k - i] << i;
    }
    m[k] = mk;
  }
  for (int j = 0; j < 32; ++j) v[static_cast<std::size_t>(j)] = m[j + 1] << (31 - j);
  return v;
}

inline constexpr std::array<std::array<std::uint32_t, 32>, sobol_dimensions> sobol_matrices = {
    sobol_matrix(0), sobol_matrix(1), sobol_matrix(2), sobol_matrix(3)};

}  // namespace detail

// Dimension `dimension` (0..3) of point `index` of the Sobol sequence, times 2^32.
constexpr std::uint32_t sobol_u32(std::uint32_t index, int dimension) {
  const auto& v = detail::sobol_matrices[static_cast<std::size_t>(dimension)];
  std::uint32_t x = 0;
  for (std::size_t j = 0; index != 0u; index >>= 1u, ++j) {
    if ((index & 1u) != 0u) x ^= v[j];
  }
  return x;
}

// The van der Corput radical inverse in base 2, phi(i) = sum_k b_k 2^-(k+1) for i = sum_k b_k 2^k: the second
// coordinate of the Hammersley points ((i + 1/2)/N, phi(i)) (Hammersley & Handscomb 1964; Karis 2013), and
// Sobol's dimension 0, whose generator matrix is the identity. The library's one radical inverse.
constexpr double radical_inverse(std::uint32_t i) { return static_cast<double>(sobol_u32(i, 0)) * 0x1p-32; }

}  // namespace shadelab
