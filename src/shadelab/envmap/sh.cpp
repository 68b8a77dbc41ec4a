#include "shadelab/envmap/sh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "shadelab/envmap/latlong.h"
#include "shadelab/envmap/simd.h"
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

// Texels per chunk of the cube projection (of each half row): its five expanded weight arrays (7.5 KiB)
// stay in L1 while the six faces' chunks are folded and summed over them.
constexpr int cube_chunk = 128;
constexpr int prefetch_ahead = 6;  // (face, chunk) items ahead, into L2: 6-12 measured 10% faster from memory than 1 into L1

// Expands the five weights g_k (w, w c, w c^2, w c sc, w c^2 sc) of texels [x0, x0 + count) of one face row
// into g3 (count a multiple of 8): g3[k][3 i + ch] = g_k(x0 + i), 8 texels a step, the products computed in
// float lane by lane (the same products as texel by texel) and spread to the interleaved layout by lane
// shuffles.
SHADELAB_INLINE void expand_weights(const float* w, const float* c, const float* sc, int count, float* const g3[5]) {
  for (int i = 0; i < count; i += 8) {
    const f8 wv = load8(w + i), cv = load8(c + i), sv = load8(sc + i);
    const f8 g1 = wv * cv;
    const f8 g2 = g1 * cv;
    const f8 v[5] = {wv, g1, g2, g1 * sv, g2 * sv};
    for (int k = 0; k < 5; ++k) {
      float* out = g3[k] + 3 * i;
      // __builtin_shufflevector (GCC >= 12 and clang): constant lane indices, 0-7 the first operand's.
      store8(out, __builtin_shufflevector(v[k], v[k], 0, 0, 0, 1, 1, 1, 2, 2));
      store8(out + 8, __builtin_shufflevector(v[k], v[k], 2, 3, 3, 3, 4, 4, 4, 5));
      store8(out + 16, __builtin_shufflevector(v[k], v[k], 5, 5, 6, 6, 6, 7, 7, 7));
    }
  }
}

// The mirror fold of a face row: texel x and its mirror x' = n - 1 - x have sc' = -sc and the same w and c,
// so g0, g1, g2 are even and g3, g4 odd, and sum_x L(x) g_k(x) over the row is sum over the left half of
// g_k(x) (L(x) + L(x')) for k = 0, 1, 2 and g_k(x) (L(x) - L(x')) for k = 3, 4: half the multiply-adds
// (the left texel's float weights serve both; the mirror's own differ from them by rounding only).
// For `steps` blocks of 8 texels, block i at left + 24 i and its mirror texels, which lie reversed in the
// 24 floats ending at mirror_end - 24 i: even = left + mirror and odd = left - mirror, texel by texel, the
// mirror block reversed texel-wise (channels kept) by two-register lane shuffles, and each summed at once
// against the chunk's expanded weights g3 into `ra` (lane l of accumulator (k, j) adds its products in
// ascending i, as chunk_pass does). next_left / next_mirror_end: the chunk folded prefetch_ahead items
// later (prefetched into L2), or nullptr.
SHADELAB_INLINE void fold_accumulate(const float* left, const float* mirror_end, int steps, const float* const g3[5],
                                     RowAccumulators& ra, const float* next_left, const float* next_mirror_end) {
  // Float j of the reversed block is float 3 (7 - j / 3) + j % 3 of the mirror block (registers m0 m1 m2;
  // shuffle index 0-7: the first operand's lanes, 8-15: the second's).
  f8 acc[5][3];
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 3; ++j) acc[k][j] = ra.acc[k][j];
  for (int i = 0; i < steps; ++i) {
    if (next_left != nullptr) {
      __builtin_prefetch(next_left + 24 * i, 0, 1);
      __builtin_prefetch(next_left + 24 * i + 16, 0, 1);
      __builtin_prefetch(next_mirror_end - 24 * (i + 1), 0, 1);
      __builtin_prefetch(next_mirror_end - 24 * (i + 1) + 16, 0, 1);
    }
    const float* l = left + 24 * i;
    const float* m = mirror_end - 24 * (i + 1);
    const f8 m0 = load8(m), m1 = load8(m + 8), m2 = load8(m + 16);
    const f8 q[3] = {__builtin_shufflevector(m1, m2, 13, 14, 15, 10, 11, 12, 7, 8),
                     __builtin_shufflevector(__builtin_shufflevector(m1, m2, 9, 4, 5, 6, 1, 2, 3, 0), m0, 0, 1, 2, 3, 4, 5, 6, 14),
                     __builtin_shufflevector(m0, m1, 7, 8, 3, 4, 5, 0, 1, 2)};
    for (int j = 0; j < 3; ++j) {
      const f8 lj = load8(l + 8 * j);
      const f8 even = lj + q[j], odd = lj - q[j];
      for (int k = 0; k < 3; ++k) acc[k][j] += load8(g3[k] + 24 * i + 8 * j) * even;
      for (int k = 3; k < 5; ++k) acc[k][j] += load8(g3[k] + 24 * i + 8 * j) * odd;
    }
  }
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 3; ++j) ra.acc[k][j] = acc[k][j];
}

// One row y of all six faces: chunk by chunk over the left half, the weights expanded once, each face's
// chunk folded with its mirror and summed over them; then each face's 15 sums, with the middle texels no
// whole mirrored block covers summed texel by texel (weights from `middle`, expanded by x as in the row).
// `next_row`: non-null when the next row (3 n floats further in each face) is this thread's too, so that the
// prefetch may run ahead into it.
SHADELAB_INLINE void cube_row_impl(const float* const faces[6], const float* w, const float* c, const float* sc, int n,
                                   float* const chunk3[5], float* const middle3[5], float out[6][15],
                                   const float* next_row) {
  RowAccumulators ra[6] = {};
  const int folded = n / 2 / 8 * 8;  // texels of each half summed through the fold
  const int chunks = (folded + cube_chunk - 1) / cube_chunk;
  for (int x0 = 0; x0 < folded; x0 += cube_chunk) {
    const int count = std::min(cube_chunk, folded - x0);
    expand_weights(w + x0, c + x0, sc + x0, count, chunk3);
    for (int f = 0; f < 6; ++f) {
      // The (face, chunk) folded prefetch_ahead items later, in this row or the next.
      int q = (x0 / cube_chunk) * 6 + f + prefetch_ahead;
      const float* next = nullptr;
      int next_x0 = 0;
      if (q < 6 * chunks) {
        next = faces[q % 6] + 0;
        next_x0 = q / 6 * cube_chunk;
      } else if (next_row != nullptr && (q -= 6 * chunks) < 6 * chunks) {
        next = faces[q % 6] + 3 * n;
        next_x0 = q / 6 * cube_chunk;
      }
      fold_accumulate(faces[f] + 3 * x0, faces[f] + 3 * (n - x0), count / 8, chunk3, ra[f],
                      next == nullptr ? nullptr : next + 3 * next_x0, next == nullptr ? nullptr : next + 3 * (n - next_x0));
    }
  }
  for (int x = folded; x < n - folded; ++x) {
    const float g1 = w[x] * c[x], g2 = g1 * c[x];
    const float v[5] = {w[x], g1, g2, g1 * sc[x], g2 * sc[x]};
    for (int k = 0; k < 5; ++k)
      for (int ch = 0; ch < 3; ++ch) middle3[k][3 * x + ch] = v[k];
  }
  for (int f = 0; f < 6; ++f) finish_row(ra[f], faces[f], middle3, folded, n - folded, out[f]);
}

SHADELAB_TARGET_AVX2 void cube_row_avx2(const float* const faces[6], const float* w, const float* c, const float* sc, int n,
                                        float* const chunk3[5], float* const middle3[5], float out[6][15],
                                        const float* next_row) {
  cube_row_impl(faces, w, c, sc, n, chunk3, middle3, out, next_row);
}
void cube_row_base(const float* const faces[6], const float* w, const float* c, const float* sc, int n,
                   float* const chunk3[5], float* const middle3[5], float out[6][15], const float* next_row) {
  cube_row_impl(faces, w, c, sc, n, chunk3, middle3, out, next_row);
}

using RowSums5 = std::array<double, 15>;

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

}  // namespace

// The cube projection. In a face row (tc fixed) the local direction is (a, b, c) = (sc c, tc c, c), so every
// second-order moment of the row is a row constant times one of five per-texel weights
//   g0 = w, g1 = w c, g2 = w c^2, g3 = w c sc, g4 = w c^2 sc:
//   sum w = S0, sum w a = S3, sum w b = tc S1, sum w c = S1, sum w ab = tc S4, sum w ac = S4, sum w bc = tc S2,
//   sum w b^2 = tc^2 S2, sum w c^2 = S2, sum w a^2 = S0 - (1 + tc^2) S2 (a^2 + b^2 + c^2 = 1),
// with S_k = sum L g_k. The weights depend on (x, y) only, so they are formed once per row and serve all
// six faces; each face's world moments are its signed permutation of the local ones. Each row is summed
// through its mirror fold (fold_accumulate): the left half's weights against L(x) +- L(n - 1 - x).
Sh9 project_sh9(const CubeMap& cube) {
  const int n = cube.size;
  const auto nn = static_cast<std::size_t>(n);
  const FaceWeights& fw = face_weights(n);
  const bool avx = cpu_has_avx2_fma();
  // Local moments per (row, face), summed afterwards in a fixed order: the result does not depend on how
  // TBB splits the rows, so it is the same for any thread count.
  std::vector<std::array<Moments, 6>> rows(nn);
  tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& range) {
    // Expanded weights: one chunk's and the row's middle texels' (indexed by x as in the row; cube_row_impl).
    const std::size_t chunk_stride = 3 * static_cast<std::size_t>(cube_chunk);
    const std::size_t tail_stride = 3 * nn;
    std::vector<float> g(5 * (chunk_stride + tail_stride));
    float* const chunk3[5] = {g.data(), g.data() + chunk_stride, g.data() + 2 * chunk_stride, g.data() + 3 * chunk_stride,
                              g.data() + 4 * chunk_stride};
    float* const tail_base = g.data() + 5 * chunk_stride;
    float* const tail3[5] = {tail_base, tail_base + tail_stride, tail_base + 2 * tail_stride, tail_base + 3 * tail_stride,
                             tail_base + 4 * tail_stride};
    for (int y = range.begin(); y != range.end(); ++y) {
      const auto yy = static_cast<std::size_t>(y);
      const float* w = fw.w.data() + yy * nn;
      const float* c = fw.c.data() + yy * nn;
      const float* faces[6];
      for (std::size_t f = 0; f < 6; ++f) faces[f] = cube.faces[f].data.data() + yy * nn * 3;
      const float* next_row = y + 1 < range.end() ? cube.faces[0].data.data() + (yy + 1) * nn * 3 : nullptr;
      float sums[6][15];
      if (avx) {
        cube_row_avx2(faces, w, c, fw.sc.data(), n, chunk3, tail3, sums, next_row);
      } else {
        cube_row_base(faces, w, c, fw.sc.data(), n, chunk3, tail3, sums, next_row);
      }
      const double tc = (2.0 * y + 1.0) / n - 1.0;
      for (int f = 0; f < 6; ++f) {
        const float* s = sums[f];
        auto sum = [&](int k) { return Rgb{s[3 * k], s[3 * k + 1], s[3 * k + 2]}; };
        const Rgb s0 = sum(0), s1 = sum(1), s2 = sum(2), s3 = sum(3), s4 = sum(4);
        // Local moments: index 0 = 1, 1 a, 2 b, 3 c, then the products of local axes (i, j).
        const Rgb first[3] = {s3, s1 * tc, s1};
        const Rgb second[3][3] = {{s0 - s2 * (1.0 + tc * tc), s4 * tc, s4},
                                  {s4 * tc, s2 * (tc * tc), s2 * tc},
                                  {s4, s2 * tc, s2}};
        Moments& m = rows[yy][static_cast<std::size_t>(f)];
        const int* p = face_perm[f];
        const double* sg = face_sign[f];
        m[0] = s0;
        for (int i = 0; i < 3; ++i) m[static_cast<std::size_t>(1 + i)] = first[p[i]] * sg[i];
        m[4] = second[p[0]][p[1]] * (sg[0] * sg[1]);
        m[5] = second[p[1]][p[2]] * (sg[1] * sg[2]);
        m[6] = second[p[0]][p[2]] * (sg[0] * sg[2]);
        m[7] = second[p[0]][p[0]];
        m[8] = second[p[1]][p[1]];
        m[9] = second[p[2]][p[2]];
      }
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
      auto sum = [&](int k) { return Rgb{s[3 * k], s[3 * k + 1], s[3 * k + 2]}; };
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
