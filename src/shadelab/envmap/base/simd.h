// shadelab envmap SIMD helpers: GCC vector extensions, compiled twice per kernel.
//
// A kernel is written once as an always-inline template over these types and instantiated in two
// wrappers: one with [[gnu::target("avx2,fma")]] (AVX2 + FMA: the 8-lane operations become single ymm
// instructions) and one for the baseline x86-64 ISA (the same operations split into SSE2 halves).
// `cpu_has_avx2_fma()` picks the wrapper at run time, so the binary runs on any x86-64 and uses AVX2
// where the CPU has it. The two wrappers can differ in the last bits (FMA contraction), never in what
// they compute; a given machine always takes the same one, so results do not depend on thread count.
// No fast-math: every reordering below is written out explicitly (independent lane accumulators).
//
// Helpers take vectors by const reference: passing 32-byte vectors by value to a non-inlined function
// would depend on the ISA (GCC's -Wpsabi note); everything here is inlined into one of the wrappers.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace shadelab::simd {

typedef float f8 __attribute__((vector_size(32)));
typedef std::int32_t i8 __attribute__((vector_size(32)));
typedef float f4 __attribute__((vector_size(16)));

#define SHADELAB_INLINE [[gnu::always_inline]] inline
#define SHADELAB_TARGET_AVX2 [[gnu::target("avx2,fma")]]
// AVX-512F (with AVX2 + FMA) for kernels written on 16-lane vectors: a third wrapper, taken where the CPU
// has it; its sums run in another lane order, so its results can differ from the 8-lane ones in the last
// bits (a given machine always takes the same wrapper).
#define SHADELAB_TARGET_AVX512 [[gnu::target("avx2,fma,avx512f")]]
#define SHADELAB_INLINE_LAMBDA __attribute__((always_inline))

inline bool cpu_has_avx2_fma() {
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return has;
}

inline bool cpu_has_avx512() {
  static const bool has = cpu_has_avx2_fma() && __builtin_cpu_supports("avx512f");
  return has;
}
SHADELAB_INLINE f8 splat8(float v) { return f8{} + v; }
SHADELAB_INLINE f4 splat4(float v) { return f4{} + v; }
SHADELAB_INLINE f8 load8(const float* p) {
  f8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
SHADELAB_INLINE f4 load4(const float* p) {
  f4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
SHADELAB_INLINE void store8(float* p, const f8& v) { std::memcpy(p, &v, sizeof v); }
SHADELAB_INLINE i8 bits(const f8& v) {
  i8 i;
  std::memcpy(&i, &v, sizeof i);
  return i;
}
SHADELAB_INLINE f8 from_bits(const i8& i) {
  f8 v;
  std::memcpy(&v, &i, sizeof v);
  return v;
}
// Lane-wise select: mask lanes are all ones (true) or zero, as vector comparisons return.
SHADELAB_INLINE f8 select(const i8& mask, const f8& a, const f8& b) { return from_bits((bits(a) & mask) | (bits(b) & ~mask)); }
SHADELAB_INLINE f8 vmin(const f8& a, const f8& b) { return select(a < b, a, b); }
SHADELAB_INLINE f8 vmax(const f8& a, const f8& b) { return select(a > b, a, b); }
SHADELAB_INLINE float hsum(const f8& v) {
  float s = 0.0f;
  for (int k = 0; k < 8; ++k) s += v[k];
  return s;
}
SHADELAB_INLINE f8 iota8() { return f8{0, 1, 2, 3, 4, 5, 6, 7}; }

// Round to nearest integer (|x| < 2^22) with the 1.5 * 2^23 trick; returns the integer as a float.
SHADELAB_INLINE f8 round8(const f8& x) {
  const f8 magic = splat8(12582912.0f);
  return (x + magic) - magic;
}
// Floor (|x| < 2^22).
SHADELAB_INLINE f8 floor8(const f8& x) {
  const f8 r = round8(x);
  return select(r > x, r - 1.0f, r);
}
// Float -> int32 for values that are already integers (|x| < 2^22).
SHADELAB_INLINE i8 to_int8(const f8& integral) { return bits(integral + splat8(12582912.0f)) - 0x4B400000; }

// 2^x for x in [-64, 0] (smaller x give 2^-64, so that products of the result stay far from the
// denormal range, which costs microcode assists): x = i + f with f in [-1/2, 1/2], 2^f = e^(f ln 2) by its
// Taylor polynomial of degree 5 in f ln 2 (relative error < 3.5e-6 on [-1/2, 1/2]: the remainder is below
// (ln2/2)^6 / 6! x 1.42), 2^i via the exponent bits.
SHADELAB_INLINE f8 exp2_8(const f8& x_in) {
  const f8 x = vmax(x_in, splat8(-64.0f));
  const f8 i = round8(x);
  const f8 f = (x - i) * 0.69314718056f;  // f ln 2 in [-0.347, 0.347]
  f8 p = splat8(1.0f / 120.0f);
  p = p * f + 1.0f / 24.0f;
  p = p * f + 1.0f / 6.0f;
  p = p * f + 0.5f;
  p = p * f + 1.0f;
  p = p * f + 1.0f;
  return p * from_bits((to_int8(i) + 127) << 23);
}

// ln(1 - d) for d in [0, 1). With s = d / (2 - d), ln(1 - d) = -2 atanh(s) = -2 (s + s^3/3 + s^5/5 + ...);
// for d <= 1/4, s <= 1/7 and six terms leave s^13/13 < 1e-12. This branch keeps the relative accuracy of d
// itself, so ln(1 - d) stays accurate where 1 - d rounds to 1 (narrow lobes). Larger d (wide lobes only) are
// reduced: 1 - d = m 2^e with m in [0.75, 1.5), ln = e ln 2 + 2 atanh((m - 1)/(m + 1)), |s| <= 1/5.
SHADELAB_INLINE f8 atanh_series(const f8& s) {
  const f8 s2 = s * s;
  f8 p = splat8(1.0f / 11.0f);
  p = p * s2 + 1.0f / 9.0f;
  p = p * s2 + 1.0f / 7.0f;
  p = p * s2 + 1.0f / 5.0f;
  p = p * s2 + 1.0f / 3.0f;
  p = p * s2 + 1.0f;
  return p * s;
}
SHADELAB_INLINE f8 int_to_float8(const i8& i) {
  f8 f;
  for (int k = 0; k < 8; ++k) f[k] = static_cast<float>(i[k]);
  return f;
}
SHADELAB_INLINE f8 log1m_8(const f8& d) {
  const f8 small = -2.0f * atanh_series(d / (2.0f - d));
  const f8 t = 1.0f - d;
  const i8 e = ((bits(t) >> 23) & 0xFF) - 127;                      // t = mant 2^e, mant in [1, 2)
  const f8 mant = from_bits((bits(t) & 0x007FFFFF) | 0x3F800000);
  const i8 big = mant >= 1.5f;                                        // -> m = mant / 2 in [0.75, 1), e + 1
  const f8 m = select(big, mant * 0.5f, mant);
  const f8 ef = int_to_float8(e - big);                               // big is -1 (all ones) where true
  const f8 large = ef * 0.69314718056f + 2.0f * atanh_series((m - 1.0f) / (m + 1.0f));
  return select(d <= 0.25f, small, large);
}

// sqrt(x) for x >= 0 to about 1e-7 relative: 1/sqrt(x) from the exponent-halving bit estimate
// (0x5f3759df, Lomont 2003), three Newton steps y <- y (3/2 - x y^2 / 2) (relative error 1.7e-3, 4.7e-6,
// then below float rounding), times x. Pure arithmetic, so it compiles the same for every ISA; sqrt(0) = 0.
SHADELAB_INLINE f8 sqrt8(const f8& x) {
  f8 y = from_bits(0x5f3759df - (bits(x) >> 1));
  const f8 half_x = 0.5f * x;
  y = y * (1.5f - half_x * y * y);
  y = y * (1.5f - half_x * y * y);
  y = y * (1.5f - half_x * y * y);
  return x * y;
}

// acos(x) for x in [-1, 1]: Abramowitz & Stegun 4.4.46, acos(x) = sqrt(1 - x) (a0 + a1 x + ... + a7 x^7) on
// [0, 1] with |error| <= 2e-8, and acos(-x) = pi - acos(x).
SHADELAB_INLINE f8 acos8(const f8& x_in) {
  const f8 x = vmin(vmax(x_in, splat8(-1.0f)), splat8(1.0f));
  const i8 neg = x < 0.0f;
  const f8 a = select(neg, -x, x);
  f8 p = splat8(-0.0012624911f);
  p = p * a + 0.0066700901f;
  p = p * a - 0.0170881256f;
  p = p * a + 0.0308918810f;
  p = p * a - 0.0501743046f;
  p = p * a + 0.0889789874f;
  p = p * a - 0.2145988016f;
  p = p * a + 1.5707963050f;
  const f8 r = sqrt8(1.0f - a) * p;
  return select(neg, 3.14159265359f - r, r);
}

}  // namespace shadelab::simd

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
