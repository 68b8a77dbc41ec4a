#include "shadelab/envmap/diffuse/sh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "shadelab/envmap/base/latlong.h"
#include "shadelab/envmap/base/simd.h"
#include "shadelab/kernels/kernels.h"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace shadelab {

// The basis and the evaluation are the kernel kernels/sh9.sl, the text exported shaders use.
ShBasis sh9_basis(const Vec3& n) {
  const kernel::Sh9Basis b = kernel::sh9_basis(n);
  ShBasis out;
  for (std::size_t i = 0; i < 9; ++i) out[i] = b.y[i];
  return out;
}

BandFactors sh_window_factors(ShWindow window) {
  switch (window) {
    case ShWindow::hanning: {
      // (1 + cos(pi l / w)) / 2 with width w = 5
      return {1.0, 0.5 * (1.0 + std::cos(pi / 5.0)), 0.5 * (1.0 + std::cos(2.0 * pi / 5.0))};
    }
    case ShWindow::lanczos: {
      // sinc(pi l / w) = sin(pi l / w) / (pi l / w) with width w = 4
      const double a1 = pi / 4.0;
      const double a2 = pi / 2.0;
      return {1.0, std::sin(a1) / a1, std::sin(a2) / a2};
    }
    case ShWindow::none: break;
  }
  return {1.0, 1.0, 1.0};
}

namespace {

using namespace simd;

// The projection kernel: for one row of texels (RGB interleaved) and five weight arrays g_k, the 15 sums
// sum_x L_c(x) g_k(x), in float with 8 independent lanes (the row is at most a few thousand texels). The
// SH9 projection of a cube row and of a lat-long ring both reduce to five such weights (see below). Each
// g3[k] holds its weights expanded to the row's interleaved layout (g(0) three times, g(1) three times, ...),
// so the row is read as it lies, 24 floats (8 texels) a step, each float multiplied by its lane-aligned
// weight with no de-interleaving; the channel of float j of the row is j mod 3. Two passes (k = 0..2, then
// 3..4) keep the accumulators in registers (9 and 6 of the 16); the row (12 n bytes) stays in L1 between.
//
// A row may be summed in chunks of texels (RowAccumulators keeps its 15 lane vectors between them), so that
// the cube projection can run the six faces' rows over one chunk of expanded weights while those stay in
// L1: lane l of accumulator (k, j) sums its products in the same order (x = 8 i + l, i ascending) as one
// pass over the whole row would, so the sums do not depend on the chunk size.
struct RowAccumulators {
  f8 acc[5][3];
};

template <int K0, int K1>
SHADELAB_INLINE void chunk_pass(const float* rgb, const float* const g3[5], int steps, RowAccumulators& ra, const float* next) {
  constexpr int K = K1 - K0;
  f8 acc[K][3];
  for (int k = 0; k < K; ++k)
    for (int j = 0; j < 3; ++j) acc[k][j] = ra.acc[K0 + k][j];
  for (int i = 0; i < steps; ++i) {
    const float* p = rgb + 24 * i;
    if (next != nullptr) {
      // The row to be read next is elsewhere in memory: ask for it now, 96 bytes of it per step as this row
      // is read, so that it arrives before it is needed (a row is too short a stream for the hardware
      // prefetcher to get ahead of).
      __builtin_prefetch(next + 24 * i);
      __builtin_prefetch(next + 24 * i + 16);
    }
    const f8 v0 = load8(p), v1 = load8(p + 8), v2 = load8(p + 16);
    for (int k = 0; k < K; ++k) {
      const float* w = g3[K0 + k] + 24 * i;
      acc[k][0] += load8(w) * v0;
      acc[k][1] += load8(w + 8) * v1;
      acc[k][2] += load8(w + 16) * v2;
    }
  }
  for (int k = 0; k < K; ++k)
    for (int j = 0; j < 3; ++j) ra.acc[K0 + k][j] = acc[k][j];
}

// Sums `steps` steps of 8 texels of a row into `ra`: rgb and g3 point at the chunk's first texel.
SHADELAB_INLINE void chunk_sums5_impl(const float* rgb, const float* const g3[5], int steps, RowAccumulators& ra, const float* next) {
  chunk_pass<0, 3>(rgb, g3, steps, ra, next);
  chunk_pass<3, 5>(rgb, g3, steps, ra, nullptr);
}

// The row's 15 sums from its accumulators, then the texels no step covered (x from x_begin to x_end,
// weights g3 indexed by x as in the row): out[3 k + c] = lanes of (k, j) for the floats of channel c,
// then those texels in order.
SHADELAB_INLINE void finish_row(const RowAccumulators& ra, const float* rgb, const float* const g3[5], int x_begin, int x_end, float out[15]) {
  float lanes[5][24];
  for (int k = 0; k < 5; ++k) {
    store8(lanes[k], ra.acc[k][0]);
    store8(lanes[k] + 8, ra.acc[k][1]);
    store8(lanes[k] + 16, ra.acc[k][2]);
  }
  // Fifteen independent chains (k, c), each adding its lanes in ascending float index j = c + 3 i.
  for (int i = 0; i < 15; ++i) out[i] = 0.0f;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 5; ++k)
      for (int c = 0; c < 3; ++c) out[3 * k + c] += lanes[k][c + 3 * i];
  for (int k = 0; k < 5; ++k)
    for (int x = x_begin; x < x_end; ++x)
      for (int c = 0; c < 3; ++c) out[3 * k + c] += g3[k][3 * x + c] * rgb[3 * x + c];
}

SHADELAB_INLINE void row_sums5_impl(const float* rgb, const float* const g3[5], int n, float out[15], const float* next) {
  RowAccumulators ra{};
  chunk_sums5_impl(rgb, g3, n / 8, ra, next);
  finish_row(ra, rgb, g3, n / 8 * 8, n, out);
}

// `next`: the row that will be summed next (prefetched while this one is read), or nullptr.
SHADELAB_TARGET_AVX2 void row_sums5_avx2(const float* rgb, const float* const g[5], int n, float out[15], const float* next) {
  row_sums5_impl(rgb, g, n, out, next);
}
void row_sums5_base(const float* rgb, const float* const g[5], int n, float out[15], const float* next) {
  row_sums5_impl(rgb, g, n, out, next);
}

// Texels per chunk of the cube projection: its five expanded weight arrays (7.5 KiB) stay in L1 while the
// three face pairs' chunks are combined and summed over them.
constexpr int cube_chunk = 128;
constexpr int prefetch_ahead = 3;  // (chunk, face pair) items ahead (6 KiB each), prefetched into L2

// The cube kernel runs on 8 lanes (AVX2, or SSE2 halves) or on 16 (AVX-512: one zmm register per 16
// floats, and 32 registers for the 24 accumulators of both passes at once): V<W> is the W-lane vector.
typedef float f16 __attribute__((vector_size(64)));
template <int W>
struct Lanes;
template <>
struct Lanes<8> {
  using V = f8;
};
template <>
struct Lanes<16> {
  using V = f16;
};
template <int W>
using V = typename Lanes<W>::V;
template <int W>
SHADELAB_INLINE V<W> loadv(const float* p) {
  V<W> v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <int W>
SHADELAB_INLINE void storev(float* p, const V<W>& v) {
  std::memcpy(p, &v, sizeof v);
}

// Expands the five weights g_k (w, w c, w c^2, w c sc, w c^2 sc) of texels [x0, x0 + count) of one face row
// into g3 (count a multiple of W): g3[k][3 i + ch] = g_k(x0 + i), W texels a step, the products computed in
// float lane by lane (the same products as texel by texel) and spread to the interleaved layout by lane
// shuffles (float j of a step takes lane j / 3).
template <int W>
SHADELAB_INLINE void expand_weights(const float* w, const float* c, const float* sc, int count, float* const g3[5]) {
  for (int i = 0; i < count; i += W) {
    const V<W> wv = loadv<W>(w + i), cv = loadv<W>(c + i), sv = loadv<W>(sc + i);
    const V<W> g1 = wv * cv;
    const V<W> g2 = g1 * cv;
    const V<W> v[5] = {wv, g1, g2, g1 * sv, g2 * sv};
    for (int k = 0; k < 5; ++k) {
      float* out = g3[k] + 3 * i;
      // __builtin_shufflevector (GCC >= 12 and clang): constant lane indices.
      if constexpr (W == 8) {
        storev<8>(out, __builtin_shufflevector(v[k], v[k], 0, 0, 0, 1, 1, 1, 2, 2));
        storev<8>(out + 8, __builtin_shufflevector(v[k], v[k], 2, 3, 3, 3, 4, 4, 4, 5));
        storev<8>(out + 16, __builtin_shufflevector(v[k], v[k], 5, 5, 6, 6, 6, 7, 7, 7));
      } else {
        storev<16>(out, __builtin_shufflevector(v[k], v[k], 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5));
        storev<16>(out + 16, __builtin_shufflevector(v[k], v[k], 5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 9, 9, 9, 10, 10));
        storev<16>(out + 32, __builtin_shufflevector(v[k], v[k], 10, 11, 11, 11, 12, 12, 12, 13, 13, 13, 14, 14, 14, 15, 15, 15));
      }
    }
  }
}

// The cube projection sums four texel rows at once: face f = 2 P and its opposite f' = f + 1 (a face pair)
// in row y (top, t) and in row n - 1 - y (bottom, b). The four share every weight g_k (w, c and sc depend on
// (x, y) only, and the two rows' tc differ in sign only), and at each x their combinations
//   Ee = (f_t + f'_t) + (f_b + f'_b),  Eo = (f_t + f'_t) - (f_b + f'_b),
//   Oe = (f_t - f'_t) + (f_b - f'_b),  Oo = (f_t - f'_t) - (f_b - f'_b)
// carry all that the world moments need (pair_terms): a local moment even in the local axes the two faces
// flip needs only E, an odd one only O; one with an odd power of tc only o, an even power only e. Of the 20
// sums S_k(q) = sum_x g_k(x) q(x) each pair needs 8 (PairSums): 24 multiply-adds per 8 x 4 texels where one
// row at a time takes 60, and no lane reversal (the four rows are read in the same direction).
enum Combo : int { Ee = 0, Eo = 1, Oe = 2, Oo = 3 };
struct PairSums {
  int combo[8];  // the first four E combinations, the last four O
  int k[8];
};
// The +-X and +-Z pairs flip local a and c and keep b; the +-Y pair flips b and c and keeps a (face_sign).
constexpr PairSums pair_sums_xz = {{Ee, Ee, Ee, Eo, Oe, Oe, Oo, Oo}, {0, 2, 4, 1, 1, 3, 2, 4}};
constexpr PairSums pair_sums_y = {{Ee, Ee, Ee, Eo, Oe, Oe, Oo, Oo}, {0, 2, 3, 2, 1, 4, 1, 4}};

template <int W>
struct PairAccumulators {
  V<W> acc[8][3];
};

// Sums `steps` steps of W texels of the rows src (f_t, f'_t, f_b, f'_b at the chunk's first texel) against
// the chunk's expanded weights g3 into sums [S0, S1) of PairSums (pass 0: [0, 4), the E sums; pass 1:
// [4, 8), the O sums; [0, 8) both at once where 24 accumulators fit in registers): lane l of accumulator
// (s, j) adds its products in ascending step, whatever the chunk size or the pass split. Float j of a step
// has channel j mod 3, as the weights. `next`: the four rows of the item prefetch_ahead items later
// (prefetched into L2 as this one is read: a chunk is too short a stream for the hardware prefetcher), or
// nullptr.
template <int W, PairSums S, int S0, int S1>
SHADELAB_INLINE void pair_pass(const float* const src[4], int steps, const float* const g3[5], PairAccumulators<W>& pa,
                               const float* const* next) {
  constexpr int step = 3 * W;
  V<W> acc[S1 - S0][3];
  for (int s = S0; s < S1; ++s)
    for (int j = 0; j < 3; ++j) acc[s - S0][j] = pa.acc[s][j];
  for (int i = 0; i < steps; ++i) {
    if (next != nullptr) {
      for (int g = 0; g < 4; ++g)
        for (int line = 0; line < step; line += 16) __builtin_prefetch(next[g] + step * i + line, 0, 1);
    }
    for (int j = 0; j < 3; ++j) {
      const int o = step * i + W * j;
      const V<W> a = loadv<W>(src[0] + o), b = loadv<W>(src[1] + o), c = loadv<W>(src[2] + o), d = loadv<W>(src[3] + o);
      V<W> q[4];  // Combo order; the pass computes the ones it needs
      if (S0 < 4) {
        const V<W> t = a + b, u = c + d;
        q[Ee] = t + u;
        q[Eo] = t - u;
      }
      if (S1 > 4) {
        const V<W> t = a - b, u = c - d;
        q[Oe] = t + u;
        q[Oo] = t - u;
      }
      for (int s = S0; s < S1; ++s) acc[s - S0][j] += loadv<W>(g3[S.k[s]] + o) * q[S.combo[s]];
    }
  }
  for (int s = S0; s < S1; ++s)
    for (int j = 0; j < 3; ++j) pa.acc[s][j] = acc[s - S0][j];
}

// One row pair of the six faces (top[f], bottom[f]: row y and row n - 1 - y, or a zero row for the middle
// row of an odd n): chunk by chunk, the weights expanded once and each face pair's chunk summed over them;
// then out[P][s][ch], pair P's sum s (PairSums) of channel ch: the lanes added in ascending float index,
// then the texels x >= n / W * W that no whole step covers, texel by texel. next_top / next_bottom: the
// next row pair when it is this thread's too (the prefetch runs ahead into it), else nullptr. OnePass: both
// passes at once (W = 16 under AVX-512; on 16 registers the 24 accumulators would spill).
template <int W, bool OnePass>
SHADELAB_INLINE void pair_rows_impl(const float* const top[6], const float* const bottom[6], const float* w, const float* c,
                                    const float* sc, int n, float* const chunk3[5], float out[3][8][3],
                                    const float* const* next_top, const float* const* next_bottom) {
  PairAccumulators<W> pa[3] = {};
  const int whole = n / W * W;
  const int chunks = (whole + cube_chunk - 1) / cube_chunk;
  for (int x0 = 0; x0 < whole; x0 += cube_chunk) {
    const int count = std::min(cube_chunk, whole - x0);
    expand_weights<W>(w + x0, c + x0, sc + x0, count, chunk3);
    for (int p = 0; p < 3; ++p) {
      const float* const src[4] = {top[2 * p] + 3 * x0, top[2 * p + 1] + 3 * x0, bottom[2 * p] + 3 * x0,
                                   bottom[2 * p + 1] + 3 * x0};
      int q = (x0 / cube_chunk) * 3 + p + prefetch_ahead;
      const float* const* rows = nullptr;
      if (q < 3 * chunks) {
        rows = top;  // this row pair
      } else if (next_top != nullptr && (q -= 3 * chunks) < 3 * chunks) {
        rows = next_top;
      }
      const float* next[4] = {};
      if (rows != nullptr) {
        const float* const* rows_b = rows == top ? bottom : next_bottom;
        const int np = q % 3, nx = 3 * (q / 3 * cube_chunk);
        next[0] = rows[2 * np] + nx;
        next[1] = rows[2 * np + 1] + nx;
        next[2] = rows_b[2 * np] + nx;
        next[3] = rows_b[2 * np + 1] + nx;
      }
      const float* const* pf = rows != nullptr ? next : nullptr;
      const int steps = count / W;
      if (OnePass) {
        if (p == 1) {
          pair_pass<W, pair_sums_y, 0, 8>(src, steps, chunk3, pa[p], pf);
        } else {
          pair_pass<W, pair_sums_xz, 0, 8>(src, steps, chunk3, pa[p], pf);
        }
      } else if (p == 1) {
        pair_pass<W, pair_sums_y, 0, 4>(src, steps, chunk3, pa[p], pf);
        pair_pass<W, pair_sums_y, 4, 8>(src, steps, chunk3, pa[p], nullptr);
      } else {
        pair_pass<W, pair_sums_xz, 0, 4>(src, steps, chunk3, pa[p], pf);
        pair_pass<W, pair_sums_xz, 4, 8>(src, steps, chunk3, pa[p], nullptr);
      }
    }
  }
  for (int p = 0; p < 3; ++p) {
    const PairSums& S = p == 1 ? pair_sums_y : pair_sums_xz;
    for (int s = 0; s < 8; ++s) {
      float lanes[3 * W];
      for (int j = 0; j < 3; ++j) storev<W>(lanes + W * j, pa[p].acc[s][j]);
      for (int ch = 0; ch < 3; ++ch) {
        float sum = 0.0f;
        for (int i = 0; i < W; ++i) sum += lanes[ch + 3 * i];
        out[p][s][ch] = sum;
      }
    }
    for (int x = whole; x < n; ++x) {
      const float g1 = w[x] * c[x], g2 = g1 * c[x];
      const float g[5] = {w[x], g1, g2, g1 * sc[x], g2 * sc[x]};
      for (int ch = 0; ch < 3; ++ch) {
        const int o = 3 * x + ch;
        const float a = top[2 * p][o], b = top[2 * p + 1][o], cc = bottom[2 * p][o], d = bottom[2 * p + 1][o];
        const float e_t = a + b, e_b = cc + d, o_t = a - b, o_b = cc - d;
        const float q[4] = {e_t + e_b, e_t - e_b, o_t + o_b, o_t - o_b};
        for (int s = 0; s < 8; ++s) out[p][s][ch] += g[S.k[s]] * q[S.combo[s]];
      }
    }
  }
}

SHADELAB_TARGET_AVX2 void pair_rows_avx2(const float* const top[6], const float* const bottom[6], const float* w, const float* c,
                                         const float* sc, int n, float* const chunk3[5], float out[3][8][3],
                                         const float* const* next_top, const float* const* next_bottom) {
  pair_rows_impl<8, false>(top, bottom, w, c, sc, n, chunk3, out, next_top, next_bottom);
}
SHADELAB_TARGET_AVX512 void pair_rows_avx512(const float* const top[6], const float* const bottom[6], const float* w,
                                             const float* c, const float* sc, int n, float* const chunk3[5],
                                             float out[3][8][3], const float* const* next_top,
                                             const float* const* next_bottom) {
  pair_rows_impl<16, true>(top, bottom, w, c, sc, n, chunk3, out, next_top, next_bottom);
}
void pair_rows_base(const float* const top[6], const float* const bottom[6], const float* w, const float* c, const float* sc,
                    int n, float* const chunk3[5], float out[3][8][3], const float* const* next_top,
                    const float* const* next_bottom) {
  pair_rows_impl<8, false>(top, bottom, w, c, sc, n, chunk3, out, next_top, next_bottom);
}

// The nine SH9 coefficients from the ten second-order moments sum L w d_i d_j, sum L w d_i, sum L w
// (per channel): index 0 = 1; 1, 2, 3 = x, y, z; 4 xy, 5 yz, 6 xz, 7 xx, 8 yy, 9 zz.
using Moments = std::array<Rgb, 10>;

// Each Y_i of kernels/sh9.sl is a quadratic polynomial in (x, y, z); P[i][k] is its coefficient of moment k,
// read off the kernel itself (the one source of the basis) by finite differences that are exact for a
// quadratic: constant Y(0); x: (Y(e) - Y(-e))/2; xx: (Y(e) + Y(-e))/2 - Y(0); xy: Y(e1 + e2) - Y(e1) - Y(e2) + Y(0).
using BasisPolynomial = std::array<std::array<double, 10>, 9>;
const BasisPolynomial& basis_polynomial() {
  static const BasisPolynomial p = [] {
    auto y = [](double a, double b, double c) { return kernel::sh9_basis(kernel::vec3(a, b, c)); };
    const Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int cross[3][2] = {{0, 1}, {1, 2}, {0, 2}};  // moments 4 xy, 5 yz, 6 xz
    BasisPolynomial out{};
    const kernel::Sh9Basis y0 = y(0, 0, 0);
    for (std::size_t i = 0; i < 9; ++i) out[i][0] = y0.y[i];
    for (std::size_t a = 0; a < 3; ++a) {
      const kernel::Sh9Basis yp = y(e[a].x, e[a].y, e[a].z), ym = y(-e[a].x, -e[a].y, -e[a].z);
      for (std::size_t i = 0; i < 9; ++i) {
        out[i][1 + a] = 0.5 * (yp.y[i] - ym.y[i]);
        out[i][7 + a] = 0.5 * (yp.y[i] + ym.y[i]) - y0.y[i];
      }
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3 u = e[cross[k][0]], v = e[cross[k][1]], s = u + v;
      const kernel::Sh9Basis ys = y(s.x, s.y, s.z), yu = y(u.x, u.y, u.z), yv = y(v.x, v.y, v.z);
      for (std::size_t i = 0; i < 9; ++i) out[i][4 + k] = ys.y[i] - yu.y[i] - yv.y[i] + y0.y[i];
    }
    return out;
  }();
  return p;
}

Sh9 from_moments(const Moments& m) {
  const BasisPolynomial& p = basis_polynomial();
  Sh9 sh;
  for (std::size_t i = 0; i < 9; ++i)
    for (std::size_t k = 0; k < 10; ++k)
      if (p[i][k] != 0.0) sh.c[i] += m[k] * p[i][k];
  return sh;
}

// Face f's direction is a signed permutation of its local (a, b, c) = (sc, tc, 1) / |(sc, tc, 1)|
// (cubemap.h): world component i = sign[f][i] * local[perm[f][i]].
constexpr int face_perm[6][3] = {{2, 1, 0}, {2, 1, 0}, {0, 2, 1}, {0, 2, 1}, {0, 1, 2}, {0, 1, 2}};
constexpr double face_sign[6][3] = {{1, -1, -1}, {-1, -1, 1}, {1, 1, 1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, -1}};

// Per-(x, y) weights of an N x N face, shared by the six faces: the exact solid angle w and the inverse
// distance c = 1 / sqrt(1 + sc^2 + tc^2), float, row-major. Cached per size.
struct FaceWeights {
  std::vector<float> w, c, sc;
};
const FaceWeights& face_weights(int size) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<FaceWeights>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& entry = cache[size];
  if (!entry) {
    auto t = std::make_unique<FaceWeights>();
    const auto n = static_cast<std::size_t>(size);
    const std::vector<double>& omega = cube_face_solid_angles(size);
    t->w.resize(n * n);
    t->c.resize(n * n);
    t->sc.resize(n + 8);
    for (std::size_t x = 0; x < n; ++x) t->sc[x] = static_cast<float>((2.0 * static_cast<double>(x) + 1.0) / size - 1.0);
    for (std::size_t y = 0; y < n; ++y) {
      const double tc = (2.0 * static_cast<double>(y) + 1.0) / size - 1.0;
      for (std::size_t x = 0; x < n; ++x) {
        const double sc = (2.0 * static_cast<double>(x) + 1.0) / size - 1.0;
        t->w[y * n + x] = static_cast<float>(omega[y * n + x]);
        t->c[y * n + x] = static_cast<float>(1.0 / std::sqrt(1.0 + sc * sc + tc * tc));
      }
    }
    entry = std::move(t);
  }
  return *entry;
}

// The coefficient of S_k in each world moment of one face row at tc (the local moments of project_sh9's
// comment, mapped by the face's signed permutation): C[m][k], m the Moments index.
using MomentCoefficients = std::array<std::array<double, 5>, 10>;
MomentCoefficients face_moment_coefficients(int f, double tc) {
  using K = std::array<double, 5>;
  // Local: 1 = S0; a = S3, b = tc S1, c = S1; aa = S0 - (1 + tc^2) S2, ab = tc S4, ac = S4, bb = tc^2 S2,
  // bc = tc S2, cc = S2.
  const K first[3] = {{0, 0, 0, 1, 0}, {0, tc, 0, 0, 0}, {0, 1, 0, 0, 0}};
  const K second[3][3] = {{K{1, 0, -(1.0 + tc * tc), 0, 0}, K{0, 0, 0, 0, tc}, K{0, 0, 0, 0, 1}},
                          {K{0, 0, 0, 0, tc}, K{0, 0, tc * tc, 0, 0}, K{0, 0, tc, 0, 0}},
                          {K{0, 0, 0, 0, 1}, K{0, 0, tc, 0, 0}, K{0, 0, 1, 0, 0}}};
  auto scaled = [](K v, double s) {
    for (double& x : v) x *= s;
    return v;
  };
  const int* p = face_perm[f];
  const double* sg = face_sign[f];
  MomentCoefficients m{};
  m[0] = K{1, 0, 0, 0, 0};
  for (std::size_t i = 0; i < 3; ++i) m[1 + i] = scaled(first[p[i]], sg[i]);
  m[4] = scaled(second[p[0]][p[1]], sg[0] * sg[1]);
  m[5] = scaled(second[p[1]][p[2]], sg[1] * sg[2]);
  m[6] = scaled(second[p[0]][p[2]], sg[0] * sg[2]);
  m[7] = second[p[0]][p[0]];
  m[8] = second[p[1]][p[1]];
  m[9] = second[p[2]][p[2]];
  return m;
}

// The world moments of a row pair of face pair P (faces 2P, 2P + 1; top row at tc, bottom at -tc) are
// linear in its 8 sums: with f_t = (Ee + Eo + Oe + Oo)/4, f'_t = (Ee + Eo - Oe - Oo)/4, f_b = (Ee - Eo + Oe -
// Oo)/4 and f'_b = (Ee - Eo - Oe + Oo)/4, the coefficient of S_k(q) in moment m is the sum over the four
// rows of sign(row, q) C_row[m][k] / 4 (those of the 12 sums PairSums leaves out cancel exactly). Every
// C_row entry is a polynomial of degree <= 2 in tc, so each coefficient is a + b tc + c tc^2, read off
// exactly from tc = 0, 1, -1 (quarters of small integers) once; a row pair evaluates only the nonzero ones.
struct PairTerm {
  std::size_t m, s;  // moment, sum
  double a, b, c;
};
using PairCoefficients = std::array<std::array<double, 8>, 10>;
PairCoefficients pair_coefficients(int pair, double tc) {
  const MomentCoefficients c[4] = {face_moment_coefficients(2 * pair, tc), face_moment_coefficients(2 * pair + 1, tc),
                                   face_moment_coefficients(2 * pair, -tc), face_moment_coefficients(2 * pair + 1, -tc)};
  constexpr double sign[4][4] = {{1, 1, 1, 1}, {1, 1, -1, -1}, {1, -1, 1, -1}, {1, -1, -1, 1}};  // [combo][row]
  const PairSums& S = pair == 1 ? pair_sums_y : pair_sums_xz;
  PairCoefficients out{};
  for (std::size_t m = 0; m < 10; ++m)
    for (std::size_t s = 0; s < 8; ++s) {
      const auto q = static_cast<std::size_t>(S.combo[s]);
      const auto k = static_cast<std::size_t>(S.k[s]);
      for (std::size_t r = 0; r < 4; ++r) out[m][s] += 0.25 * sign[q][r] * c[r][m][k];
    }
  return out;
}
const std::array<std::vector<PairTerm>, 3>& pair_terms() {
  static const std::array<std::vector<PairTerm>, 3> terms = [] {
    std::array<std::vector<PairTerm>, 3> out;
    for (int pair = 0; pair < 3; ++pair) {
      const PairCoefficients c0 = pair_coefficients(pair, 0.0), cp = pair_coefficients(pair, 1.0),
                             cm = pair_coefficients(pair, -1.0);
      for (std::size_t m = 0; m < 10; ++m)
        for (std::size_t s = 0; s < 8; ++s) {
          const PairTerm t{m, s, c0[m][s], 0.5 * (cp[m][s] - cm[m][s]), 0.5 * (cp[m][s] + cm[m][s]) - c0[m][s]};
          if (t.a != 0.0 || t.b != 0.0 || t.c != 0.0) out[static_cast<std::size_t>(pair)].push_back(t);
        }
    }
    return out;
  }();
  return terms;
}
Moments pair_moments(const std::vector<PairTerm>& terms, double tc, const float sums[8][3]) {
  Moments out{};
  for (const PairTerm& t : terms) out[t.m] += Rgb{static_cast<double>(sums[t.s][0]), static_cast<double>(sums[t.s][1]), static_cast<double>(sums[t.s][2])} * (t.a + tc * (t.b + tc * t.c));
  return out;
}

}  // namespace

// The cube projection. In a face row (tc fixed) the local direction is (a, b, c) = (sc c, tc c, c), so every
// second-order moment of the row is a row constant times one of five per-texel weights
//   g0 = w, g1 = w c, g2 = w c^2, g3 = w c sc, g4 = w c^2 sc:
//   sum w = S0, sum w a = S3, sum w b = tc S1, sum w c = S1, sum w ab = tc S4, sum w ac = S4, sum w bc = tc S2,
//   sum w b^2 = tc^2 S2, sum w c^2 = S2, sum w a^2 = S0 - (1 + tc^2) S2 (a^2 + b^2 + c^2 = 1),
// with S_k = sum L g_k. The weights depend on (x, y) only and are the same in row n - 1 - y, so they are
// formed once per row pair and serve its twelve face rows, summed four at a time (pair_rows_impl); each
// face's world moments are its signed permutation of the local ones (face_moment_coefficients).
Sh9 project_sh9(const CubeMap& cube) { return detail::project_sh9_simd(cube, 2); }

Sh9 detail::project_sh9_simd(const CubeMap& cube, int widest) {
  const int n = cube.size;
  const auto nn = static_cast<std::size_t>(n);
  const FaceWeights& fw = face_weights(n);
  const bool avx = widest >= 1 && cpu_has_avx2_fma();
  const bool avx512 = widest >= 2 && cpu_has_avx512();
  const int pairs = (n + 1) / 2;
  const std::array<std::vector<PairTerm>, 3>& terms = pair_terms();
  // The middle row of an odd n pairs with a row of zeros (its tc is 0).
  const FloatBuffer zero_row(3 * nn, 0.0f);
  // World moments per (row pair, face pair), summed afterwards in a fixed order: the result does not depend
  // on how TBB splits the row pairs, so it is the same for any thread count.
  std::vector<std::array<Moments, 3>> rows(static_cast<std::size_t>(pairs));
  tbb::parallel_for(tbb::blocked_range<int>(0, pairs), [&](const tbb::blocked_range<int>& range) {
    FloatBuffer g(5 * 3 * static_cast<std::size_t>(cube_chunk));  // 64-byte aligned, as the face rows of N % 16 == 0
    float* const chunk3[5] = {g.data(), g.data() + 3 * cube_chunk, g.data() + 6 * cube_chunk, g.data() + 9 * cube_chunk,
                              g.data() + 12 * cube_chunk};
    auto row_pointers = [&](int p, const float* top[6], const float* bottom[6]) {
      const int yb = n - 1 - p;
      for (std::size_t f = 0; f < 6; ++f) {
        const float* face = cube.faces[f].data.data();
        top[f] = face + static_cast<std::size_t>(p) * nn * 3;
        bottom[f] = yb == p ? zero_row.data() : face + static_cast<std::size_t>(yb) * nn * 3;
      }
    };
    for (int p = range.begin(); p != range.end(); ++p) {
      const auto pp = static_cast<std::size_t>(p);
      const float *top[6], *bottom[6], *next_top[6], *next_bottom[6];
      row_pointers(p, top, bottom);
      const bool ahead = p + 1 < range.end();
      if (ahead) row_pointers(p + 1, next_top, next_bottom);
      const float* w = fw.w.data() + pp * nn;
      const float* c = fw.c.data() + pp * nn;
      float sums[3][8][3];
      if (avx512) {
        pair_rows_avx512(top, bottom, w, c, fw.sc.data(), n, chunk3, sums, ahead ? next_top : nullptr, ahead ? next_bottom : nullptr);
      } else if (avx) {
        pair_rows_avx2(top, bottom, w, c, fw.sc.data(), n, chunk3, sums, ahead ? next_top : nullptr, ahead ? next_bottom : nullptr);
      } else {
        pair_rows_base(top, bottom, w, c, fw.sc.data(), n, chunk3, sums, ahead ? next_top : nullptr, ahead ? next_bottom : nullptr);
      }
      const double tc = (2.0 * p + 1.0) / n - 1.0;
      for (std::size_t pair = 0; pair < 3; ++pair) rows[pp][pair] = pair_moments(terms[pair], tc, sums[pair]);
    }
  });
  Moments total{};
  for (const auto& r : rows)
    for (const Moments& m : r)
      for (std::size_t i = 0; i < 10; ++i) total[i] += m[i];
  return from_moments(total);
}

// The lat-long projection, exact for the piecewise-constant map (each texel's integral of Y_i dOmega, not
// its centre value): in (phi, u = cos theta) dOmega = dphi du and d = (s cos phi, u, s sin phi) with
// s = sqrt(1 - u^2), so every moment of a texel is a product of a phi integral over its column (of 1, cos phi,
// sin phi, cos 2 phi, sin 2 phi: cos^2 = (1 + cos 2 phi)/2, sin^2 = (1 - cos 2 phi)/2, cos sin = sin 2 phi / 2)
// and a u integral over its ring (of 1, u, u^2, s, u s, s^2 = 1 - u^2), all in closed form:
//   int cos phi = sin b - sin a, int sin phi = cos a - cos b, int cos 2phi = (sin 2b - sin 2a)/2,
//   int sin 2phi = (cos 2a - cos 2b)/2; int s du = (u s + asin u)/2, int u s du = -(1 - u^2)^(3/2)/3.
// The column weights g_k are those phi integrals divided by the column width, so g_0 = 1.
Sh9 project_sh9(const Image& latlong) {
  const int w = latlong.width;
  const int h = latlong.height;
  const auto ww = static_cast<std::size_t>(w);
  const double dphi = two_pi / w;
  const std::size_t stride = 3 * ww + 24;  // one expanded weight array (row_pass)
  std::vector<float> table(5 * stride, 0.0f);
  for (std::size_t x = 0; x < ww; ++x) {
    const double a = two_pi * (static_cast<double>(x) / w - 0.5), b = a + dphi;  // latlong.h: phi = 2 pi (u - 0.5)
    const double v[5] = {1.0, (std::sin(b) - std::sin(a)) / dphi, (std::cos(a) - std::cos(b)) / dphi,
                         0.5 * (std::sin(2.0 * b) - std::sin(2.0 * a)) / dphi, 0.5 * (std::cos(2.0 * a) - std::cos(2.0 * b)) / dphi};
    for (std::size_t k = 0; k < 5; ++k)
      for (std::size_t ch = 0; ch < 3; ++ch) table[k * stride + 3 * x + ch] = static_cast<float>(v[k]);
  }
  const float* const gk[5] = {table.data(), table.data() + stride, table.data() + 2 * stride, table.data() + 3 * stride,
                              table.data() + 4 * stride};
  const bool avx = cpu_has_avx2_fma();
  std::vector<Moments> rows(static_cast<std::size_t>(h));
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& range) {
    for (int y = range.begin(); y != range.end(); ++y) {
      float s[15] = {};
      const float* rgb = latlong.data.data() + static_cast<std::size_t>(y) * ww * 3;
      const float* next = y + 1 < range.end() ? rgb + ww * 3 : nullptr;
      if (avx) {
        row_sums5_avx2(rgb, gk, w, s, next);
      } else {
        row_sums5_base(rgb, gk, w, s, next);
      }
      auto sum = [&](int k) {
        return Rgb{static_cast<double>(s[3 * k]), static_cast<double>(s[3 * k + 1]), static_cast<double>(s[3 * k + 2])};
      };
      const Rgb one = sum(0), cp = sum(1), sp = sum(2), c2 = sum(3), s2 = sum(4);
      // The ring's u integrals, from u1 = cos(pi (y + 1)/h) to u0 = cos(pi y/h).
      const double u0 = y == 0 ? 1.0 : std::cos(pi * y / h), u1 = y + 1 == h ? -1.0 : std::cos(pi * (y + 1) / h);
      auto int_s = [](double u) { return 0.5 * (u * std::sqrt(std::max(0.0, 1.0 - u * u)) + std::asin(u)); };
      auto int_us = [](double u) { return -std::pow(std::max(0.0, 1.0 - u * u), 1.5) / 3.0; };
      const double i1 = u0 - u1, iu = 0.5 * (u0 * u0 - u1 * u1), iuu = (u0 * u0 * u0 - u1 * u1 * u1) / 3.0;
      const double is = int_s(u0) - int_s(u1), ius = int_us(u0) - int_us(u1), iss = i1 - iuu;
      Moments& m = rows[static_cast<std::size_t>(y)];
      m[0] = one * i1;
      m[1] = cp * is;
      m[2] = one * iu;
      m[3] = sp * is;
      m[4] = cp * ius;
      m[5] = sp * ius;
      m[6] = s2 * (0.5 * iss);
      m[7] = (one + c2) * (0.5 * iss);
      m[8] = one * iuu;
      m[9] = (one - c2) * (0.5 * iss);
      for (Rgb& v : m) v *= dphi;
    }
  });
  Moments total{};
  for (const Moments& m : rows)
    for (std::size_t i = 0; i < 10; ++i) total[i] += m[i];
  return from_moments(total);
}

Sh9 project_sh9(const std::function<Rgb(const Vec3&)>& f, int size) {
  const CubeTexelTable& t = CubeTexelTable::get(size);
  Sh9 total;
  for (std::size_t k = 0; k < t.direction.size(); ++k) {
    const ShBasis b = sh9_basis(t.direction[k]);
    const Rgb l = f(t.direction[k]) * t.solid_angle[k];
    for (std::size_t i = 0; i < 9; ++i) total.c[i] += l * b[i];
  }
  return total;
}

Rgb sh9_evaluate(const Sh9& sh, const Vec3& n, const BandFactors& factors) {
  kernel::Sh9Coefficients k;
  for (std::size_t i = 0; i < 9; ++i) k.c[i] = sh.c[i];
  return kernel::sh9_evaluate(k, n, factors[0], factors[1], factors[2]);
}

Sh9 sh9_scale_bands(const Sh9& sh, const BandFactors& factors) {
  Sh9 out;
  for (std::size_t i = 0; i < 9; ++i) out.c[i] = sh.c[i] * factors[static_cast<std::size_t>(sh_band(static_cast<int>(i)))];
  return out;
}

Sh9 sh9_directional_light(const Vec3& to_light, const Rgb& colour_game, bool d3dx_normalize) {
  // The delta function pi c delta(w - d) projects to pi c Y_i(d).
  const double scale = pi * (d3dx_normalize ? 16.0 / 17.0 : 1.0);
  const ShBasis b = sh9_basis(normalize(to_light));
  Sh9 sh;
  for (std::size_t i = 0; i < 9; ++i) sh.c[i] = colour_game * (scale * b[i]);
  return sh;
}

namespace {

// Solves the n x n system A x = y in place by Gaussian elimination with partial pivoting (n <= 5).
template <std::size_t N>
std::array<double, N> solve(std::array<std::array<double, N>, N> a, std::array<double, N> y) {
  for (std::size_t col = 0; col < N; ++col) {
    std::size_t piv = col;
    for (std::size_t r = col + 1; r < N; ++r) {
      if (std::abs(a[r][col]) > std::abs(a[piv][col])) piv = r;
    }
    std::swap(a[col], a[piv]);
    std::swap(y[col], y[piv]);
    for (std::size_t r = col + 1; r < N; ++r) {
      const double f = a[r][col] / a[col][col];
      for (std::size_t k = col; k < N; ++k) a[r][k] -= f * a[col][k];
      y[r] -= f * y[col];
    }
  }
  std::array<double, N> x{};
  for (std::size_t i = N; i-- > 0;) {
    double s = y[i];
    for (std::size_t k = i + 1; k < N; ++k) s -= a[i][k] * x[k];
    x[i] = s / a[i][i];
  }
  return x;
}

// Rotates one band: the rotated coefficients c' satisfy sum_m c'_m Y_m(d_k) = sum_m c_m Y_m(R^-1 d_k) at
// 2l + 1 directions d_k for which the matrix Y_m(d_k) is invertible; band-l functions are closed under
// rotation, so c' is exact.
template <std::size_t N>
void rotate_band(const Sh9& in, Sh9& out, std::size_t first, const Mat3& inverse, const std::array<Vec3, N>& dirs) {
  std::array<std::array<double, N>, N> a{};
  std::array<std::array<double, N>, N> b{};
  for (std::size_t k = 0; k < N; ++k) {
    const ShBasis yd = sh9_basis(normalize(dirs[k]));
    const ShBasis yr = sh9_basis(inverse.apply(normalize(dirs[k])));
    for (std::size_t m = 0; m < N; ++m) {
      a[k][m] = yd[first + m];
      b[k][m] = yr[first + m];
    }
  }
  for (int ch = 0; ch < 3; ++ch) {
    std::array<double, N> rhs{};
    for (std::size_t k = 0; k < N; ++k) {
      for (std::size_t m = 0; m < N; ++m) rhs[k] += b[k][m] * in.c[first + m][ch];
    }
    const auto x = solve<N>(a, rhs);
    for (std::size_t m = 0; m < N; ++m) out.c[first + m][ch] = x[m];
  }
}

}  // namespace

Sh9 sh9_rotate(const Sh9& sh, const Mat3& rotation) {
  const Mat3 inverse = rotation.transposed();
  Sh9 out;
  out.c[0] = sh.c[0];
  rotate_band<3>(sh, out, 1, inverse, {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}});
  rotate_band<5>(sh, out, 4, inverse,
                 {Vec3{1, 0, 0}, Vec3{0, 0, 1}, Vec3{1, 1, 0}, Vec3{1, 0, 1}, Vec3{0, 1, 1}});
  return out;
}

Rgb sh9_irradiance_error_bound(const CubeMap& env, const Sh9& sh) {
  const CubeTexelTable& t = CubeTexelTable::get(env.size);
  const auto n = static_cast<std::size_t>(env.size);
  Rgb energy;
  for (std::size_t k = 0; k < t.direction.size(); ++k) {
    const std::size_t p = k % (n * n);
    const Rgb l = env.faces[k / (n * n)].at(static_cast<int>(p % n), static_cast<int>(p / n));
    energy += l * l * t.solid_angle[k];
  }
  Rgb captured;
  for (const Rgb& c : sh.c) captured += c * c;
  const Rgb r = energy - captured;
  return {sh9_truncation_constant * std::sqrt(std::max(0.0, r.r)), sh9_truncation_constant * std::sqrt(std::max(0.0, r.g)),
          sh9_truncation_constant * std::sqrt(std::max(0.0, r.b))};
}

}  // namespace shadelab
