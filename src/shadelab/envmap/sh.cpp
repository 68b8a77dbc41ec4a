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
template <int K0, int K1>
SHADELAB_INLINE void row_pass(const float* rgb, const float* const g3[5], int n, float out[15], const float* next) {
  constexpr int K = K1 - K0;
  f8 acc[K][3] = {};
  int x = 0;
  for (; x + 8 <= n; x += 8) {
    const float* p = rgb + 3 * x;
    if (next != nullptr) {
      // The row to be read next is elsewhere in memory (the next face's row): ask for it now, 96 bytes of it
      // per step as this row is read, so that it arrives before it is needed (a row is too short a stream for
      // the hardware prefetcher to get ahead of).
      __builtin_prefetch(next + 3 * x);
      __builtin_prefetch(next + 3 * x + 16);
    }
    const f8 v0 = load8(p), v1 = load8(p + 8), v2 = load8(p + 16);
    for (int k = 0; k < K; ++k) {
      const float* w = g3[K0 + k] + 3 * x;
      acc[k][0] += load8(w) * v0;
      acc[k][1] += load8(w + 8) * v1;
      acc[k][2] += load8(w + 16) * v2;
    }
  }
  for (int k = 0; k < K; ++k) {
    float lanes[24];
    store8(lanes, acc[k][0]);
    store8(lanes + 8, acc[k][1]);
    store8(lanes + 16, acc[k][2]);
    for (int j = 0; j < 24; ++j) out[3 * (K0 + k) + j % 3] += lanes[j];
  }
  for (; x < n; ++x)
    for (int k = K0; k < K1; ++k)
      for (int c = 0; c < 3; ++c) out[3 * k + c] += g3[k][3 * x + c] * rgb[3 * x + c];
}

SHADELAB_INLINE void row_sums5_impl(const float* rgb, const float* const g3[5], int n, float out[15], const float* next) {
  for (int i = 0; i < 15; ++i) out[i] = 0.0f;
  row_pass<0, 3>(rgb, g3, n, out, next);
  row_pass<3, 5>(rgb, g3, n, out, nullptr);
}

// `next`: the row that will be summed next (prefetched while this one is read), or nullptr.
SHADELAB_TARGET_AVX2 void row_sums5_avx2(const float* rgb, const float* const g[5], int n, float out[15], const float* next) {
  row_sums5_impl(rgb, g, n, out, next);
}
void row_sums5_base(const float* rgb, const float* const g[5], int n, float out[15], const float* next) {
  row_sums5_impl(rgb, g, n, out, next);
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
// six faces; each face's world moments are its signed permutation of the local ones.
Sh9 project_sh9(const CubeMap& cube) {
  const int n = cube.size;
  const auto nn = static_cast<std::size_t>(n);
  const FaceWeights& fw = face_weights(n);
  const bool avx = cpu_has_avx2_fma();
  // Local moments per (row, face), summed afterwards in a fixed order: the result does not depend on how
  // TBB splits the rows, so it is the same for any thread count.
  std::vector<std::array<Moments, 6>> rows(nn);
  tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& range) {
    const std::size_t stride = 3 * nn + 24;  // one expanded weight array (row_pass)
    std::vector<float> g(5 * stride);
    for (int y = range.begin(); y != range.end(); ++y) {
      const auto yy = static_cast<std::size_t>(y);
      const float* w = fw.w.data() + yy * nn;
      const float* c = fw.c.data() + yy * nn;
      for (std::size_t x = 0; x < nn; ++x) {
        const float g1 = w[x] * c[x], g2 = g1 * c[x];
        const float v[5] = {w[x], g1, g2, g1 * fw.sc[x], g2 * fw.sc[x]};
        for (std::size_t k = 0; k < 5; ++k)
          for (std::size_t ch = 0; ch < 3; ++ch) g[k * stride + 3 * x + ch] = v[k];
      }
      const float* const gk[5] = {g.data(), g.data() + stride, g.data() + 2 * stride, g.data() + 3 * stride, g.data() + 4 * stride};
      const double tc = (2.0 * y + 1.0) / n - 1.0;
      for (int f = 0; f < 6; ++f) {
        float s[15] = {};
        const float* rgb = cube.faces[static_cast<std::size_t>(f)].data.data() + yy * nn * 3;
        // Next: the next face's row y, or after the last face the first face's next row of this range.
        const float* next = f < 5 ? cube.faces[static_cast<std::size_t>(f + 1)].data.data() + yy * nn * 3
                            : y + 1 < range.end() ? cube.faces[0].data.data() + (yy + 1) * nn * 3
                                                  : nullptr;
        if (avx) {
          row_sums5_avx2(rgb, gk, n, s, next);
        } else {
          row_sums5_base(rgb, gk, n, s, next);
        }
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
