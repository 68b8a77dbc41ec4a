#include "shadelab/envmap/sh.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

#include "shadelab/envmap/latlong.h"
#include "shadelab/kernels/kernels.h"

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

// Sums of one face row, in float (at most a few thousand terms), returned as 27 numbers: 9 bases x RGB.
using RowSums = std::array<double, 27>;

template <int Face>
void project_row(const float* rgb, const CubeFaceTexel* t, int n, RowSums& out) {
  std::array<float, 27> acc{};
  for (int x = 0; x < n; ++x) {
    const float a = t[x].a, b = t[x].b, c = t[x].c, w = t[x].w;
    float dx, dy, dz;  // the face's direction: the inverse of table 8.19
    if constexpr (Face == 0) { dx = c; dy = -b; dz = -a; }
    else if constexpr (Face == 1) { dx = -c; dy = -b; dz = a; }
    else if constexpr (Face == 2) { dx = a; dy = c; dz = b; }
    else if constexpr (Face == 3) { dx = a; dy = -c; dz = -b; }
    else if constexpr (Face == 4) { dx = a; dy = -b; dz = c; }
    else { dx = -a; dy = -b; dz = -c; }
    const float basis[9] = {static_cast<float>(sh_c0) * w,
                            static_cast<float>(-sh_c1) * dy * w,
                            static_cast<float>(sh_c1) * dz * w,
                            static_cast<float>(-sh_c1) * dx * w,
                            static_cast<float>(sh_c2) * dx * dy * w,
                            static_cast<float>(-sh_c2) * dy * dz * w,
                            static_cast<float>(sh_c3) * (3.0f * dz * dz - 1.0f) * w,
                            static_cast<float>(-sh_c2) * dx * dz * w,
                            static_cast<float>(sh_c4) * (dx * dx - dy * dy) * w};
    const float r = rgb[3 * x], g = rgb[3 * x + 1], bl = rgb[3 * x + 2];
    for (int i = 0; i < 9; ++i) {
      acc[static_cast<std::size_t>(3 * i)] += basis[i] * r;
      acc[static_cast<std::size_t>(3 * i + 1)] += basis[i] * g;
      acc[static_cast<std::size_t>(3 * i + 2)] += basis[i] * bl;
    }
  }
  for (std::size_t i = 0; i < 27; ++i) out[i] = static_cast<double>(acc[i]);
}

Sh9 from_sums(const RowSums& s) {
  Sh9 sh;
  for (std::size_t i = 0; i < 9; ++i) sh.c[i] = {s[3 * i], s[3 * i + 1], s[3 * i + 2]};
  return sh;
}

}  // namespace

Sh9 project_sh9(const CubeMap& cube) {
  const int n = cube.size;
  const auto& table = cube_face_table(n);
  // One partial sum per (face, row), summed afterwards in a fixed order: the result does not depend on how
  // TBB splits the work, so it is the same for any thread count.
  std::vector<RowSums> rows(static_cast<std::size_t>(6 * n));
  tbb::parallel_for(tbb::blocked_range<int>(0, 6 * n), [&](const tbb::blocked_range<int>& range) {
    for (int k = range.begin(); k != range.end(); ++k) {
      const int face = k / n;
      const int y = k % n;
      const float* rgb = cube.faces[static_cast<std::size_t>(face)].data.data() + static_cast<std::size_t>(y) * n * 3;
      const CubeFaceTexel* t = table.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(n);
      RowSums& out = rows[static_cast<std::size_t>(k)];
      switch (face) {
        case 0: project_row<0>(rgb, t, n, out); break;
        case 1: project_row<1>(rgb, t, n, out); break;
        case 2: project_row<2>(rgb, t, n, out); break;
        case 3: project_row<3>(rgb, t, n, out); break;
        case 4: project_row<4>(rgb, t, n, out); break;
        default: project_row<5>(rgb, t, n, out); break;
      }
    }
  });
  RowSums total{};
  for (const auto& r : rows) {
    for (std::size_t i = 0; i < 27; ++i) total[i] += r[i];
  }
  return from_sums(total);
}

Sh9 project_sh9(const Image& latlong) {
  const int w = latlong.width;
  const int h = latlong.height;
  std::vector<Sh9> rows(static_cast<std::size_t>(h));
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& range) {
    for (int y = range.begin(); y != range.end(); ++y) {
      const double d_omega = latlong_texel_solid_angle(y, w, h);
      Sh9 acc;
      for (int x = 0; x < w; ++x) {
        const Vec3 d = latlong_direction((x + 0.5) / w, (y + 0.5) / h);
        const ShBasis b = sh9_basis(d);
        const Rgb l = latlong.at(x, y) * d_omega;
        for (std::size_t i = 0; i < 9; ++i) acc.c[i] += l * b[i];
      }
      rows[static_cast<std::size_t>(y)] = acc;
    }
  });
  Sh9 total;
  for (const auto& r : rows) total += r;
  return total;
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
