// shadelab envmap internals: the exact sum of a radially symmetric lobe K(R.w) over every texel of an input
// cube, for every texel of an output cube (prefilter.h's Phong chain, prefilter_ggx.h's exact GGX levels).
// The lobe is a template parameter with weight<K>(d): K up to a constant factor as a function of
// d = 1 - R.w, 8 lanes (K: a lobe-specific compile-time variant, e.g. the terms of a series), and
// row_sums_in_double: false to sum each lane in float over the whole cap, true to add each row's float
// lane sums into double totals (wide lobes: long float sums would lose digits). Input texels
// are read 8 at a time in float (simd.h) inside the cap d <= d_max, rows and columns bounded per face, and
// output texels are summed in groups of four mirror images (below). Not a public header: no stable API.
#pragma once

#include <cmath>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "shadelab/core/constants.h"
#include "shadelab/core/vec.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/base/simd.h"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace shadelab::lobe_sum {

using namespace simd;

// One input level in planar float form, and the per-(x, y) tables shared by its six faces: the local
// direction (a, b, c) = (sc, tc, 1) / |(sc, tc, 1)| and the exact solid angle. Arrays are padded by 8.
struct Input {
  const CubeMap* cube = nullptr;
  int n = 0;
  std::vector<float> rgb[6][3];
  std::vector<float> rgb_reversed[6][3];  // each row's texels in reverse order: [y][x] = rgb[y][n - 1 - x]
  std::vector<float> a, b, c, w;
};

Input make_input(const CubeMap& cube);

// The eight lanes added in double, in lane order.
SHADELAB_INLINE double hsum_double(const f8& v) {
  double s = 0.0;
  for (int k = 0; k < 8; ++k) s += static_cast<double>(v[k]);
  return s;
}

// Face f's direction is a signed permutation of its local (a, b, c): world_i = sign[f][i] local[perm[f][i]].
constexpr int face_perm[6][3] = {{2, 1, 0}, {2, 1, 0}, {0, 2, 1}, {0, 2, 1}, {0, 1, 2}, {0, 1, 2}};
constexpr double face_sign[6][3] = {{1, -1, -1}, {-1, -1, 1}, {1, 1, 1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, -1}};

// The mirror groups of output texels. Output texel (f, x, y) and (f, N - 1 - x, y) are mirror images under
// the reflection of world axis A_f (the axis of face f's local a), (f, x, N - 1 - y) under that of B_f (local
// b), and (f, N - 1 - x, N - 1 - y) under both. A reflection maps every input texel p to an input texel p'
// with the same solid angle and r'.p' = r.p, so one weight K(r.p) w(p) serves the whole group: r against
// L(p), its images against L(p'). The reflection of axis A maps input face g to g' = g, or to the opposite
// face g ^ 1 when A is g's own axis, and flips exactly one of its local coordinates: (x, y) -> (N - 1 - x, y)
// or (x, N - 1 - y) (prefilter_test holds every output texel to the brute force). The image texel is read
// from the reversed planes when x flips, from row N - 1 - y when y flips, at the same index in the row.
struct Partner {
  int face = 0;
  bool flip_x = false, flip_y = false;
};
// The index i of face f's world axis that its local coordinate `local` (0 a, 1 b, 2 c) runs along.
int face_axis_of_local(int face, int local);
// The image of texel p's partner under the reflection of world axis `axis`.
Partner reflect(int axis, const Partner& p);

// The texel index range [lo, hi] whose centres (2k + 1)/N - 1 can lie where the quadratic
// q2 s^2 + 2 q1 s + q0 <= 0 (s in [-1, 1]); false if none. Conservative: one texel of margin.
bool index_range(double q2, double q1, double q0, int n, int& lo, int& hi);
// The x range of row tc inside the cap r.p >= kappa |p|, p = (sc, tc, 1) (face-local): squaring,
// (ra^2 - kappa^2) sc^2 + 2 ra beta sc + beta^2 - kappa^2 (1 + tc^2) >= 0 with beta = rb tc + rc. When
// ra^2 < kappa^2 that is one interval (the cap's side is where ra sc + beta > 0); otherwise the row can meet
// the cap in a ray, and the face-wide column range is kept. Narrows [lo, hi]; false if the row misses.
bool row_range(double ra, double rb, double rc, double kappa, double tc, int n, int& lo, int& hi);

// Texels lo..hi of one row of a face (row: the index of its first texel; rows[o]: image o's row, read from
// planes[o]) added into the accumulators: weight K(r.p) dOmega_p for r[0]'s face-local direction (va, vb,
// vc), 0 where d > d_max, summed against each image's texels.
template <int K, int M, class Lobe>
SHADELAB_INLINE void accumulate_row(const Input& in, const Lobe& lobe, const f8& va, const f8& vb, const f8& vc, float d_max,
                                    std::size_t row, const std::size_t (&rows)[M], const float* (&planes)[M][3], int lo, int hi,
                                    f8& acc_w, f8 (&acc)[M][3]) {
  const f8 last = splat8(static_cast<float>(hi));
  for (int x = lo; x <= hi; x += 8) {
    const std::size_t i = row + static_cast<std::size_t>(x);
    const f8 da = va - load8(in.a.data() + i), db = vb - load8(in.b.data() + i), dc = vc - load8(in.c.data() + i);
    const f8 d = 0.5f * (da * da + db * db + dc * dc);  // 1 - r.w, without the cancellation of 1 - t
    const i8 keep = (d <= d_max) & ((iota8() + static_cast<float>(x)) <= last);
    const f8 wt = select(keep, lobe.template weight<K>(d) * load8(in.w.data() + i), splat8(0.0f));
    acc_w += wt;
    for (int o = 0; o < M; ++o) {
      const std::size_t j = rows[o] + static_cast<std::size_t>(x);
      for (int c = 0; c < 3; ++c) acc[o][c] += wt * load8(planes[o][c] + j);
    }
  }
}

// Image o of face f's group (the reflection of axes[0] where o & 1, of axes[1] where o & 2: the face it
// reads and its flips) and the input planes it reads (rows reversed where it flips x).
template <int M>
SHADELAB_INLINE void group_images(const Input& in, int f, const int (&axes)[2], Partner (&part)[M], const float* (&planes)[M][3]) {
  for (int o = 0; o < M; ++o) {
    part[o].face = f;
    if (o & 1) part[o] = reflect(axes[0], part[o]);
    if (o & 2) part[o] = reflect(axes[1], part[o]);
    const auto g = static_cast<std::size_t>(part[o].face);
    const auto& src = part[o].flip_x ? in.rgb_reversed[g] : in.rgb[g];
    for (int c = 0; c < 3; ++c) planes[o][c] = src[static_cast<std::size_t>(c)].data();
  }
}

// The first index of row y of each image in arrays of n x n (row y read as n - 1 - y where it flips y).
template <int M>
SHADELAB_INLINE void image_rows(const Partner (&part)[M], std::size_t y, std::size_t n, std::size_t (&rows)[M]) {
  for (int o = 0; o < M; ++o) rows[o] = (part[o].flip_y ? n - 1 - y : y) * n;
}

// The lobe about r[0] and its M - 1 mirror images (M = 1 or 4): r[o] is the image of r[0] under the
// reflections of axes[0] (o & 1) and axes[1] (o & 2). The weights are computed once, for r[0]'s cap, and
// summed against each image's texels.
template <int K, int M, class Lobe>
SHADELAB_INLINE void convolve_group(const Input& in, const Lobe& lobe, const Vec3 (&r)[M], const int (&axes)[2], double kappa,
                                    double sin2_cap, double cap_angle, float d_max, Rgb (&out)[M]) {
  const int n = in.n;
  const auto nn = static_cast<std::size_t>(n);
  f8 acc_w = {};
  f8 acc[M][3] = {};
  double total_w = 0.0;
  double total[M][3] = {};
  for (int f = 0; f < 6; ++f) {
    double local[3];
    for (int i = 0; i < 3; ++i) local[face_perm[f][i]] = face_sign[f][i] * r[0][i];
    const double ra = local[0], rb = local[1], rc = local[2];
    // Every point of a face is within acos(1/sqrt(3)) of its axis.
    if (std::acos(std::clamp(rc, -1.0, 1.0)) > cap_angle + 0.9553166181245093) continue;
    // Rows (columns) whose great circle, through the face's s (t) axis, passes within the cap's angle of r:
    // the distance from r to the circle of row tc is asin(|rc tc - rb| / sqrt(1 + tc^2)).
    int y0 = 0, y1 = 0, x0 = 0, x1 = 0;
    if (!index_range(rc * rc - sin2_cap, -rb * rc, rb * rb - sin2_cap, n, y0, y1)) continue;
    if (!index_range(rc * rc - sin2_cap, -ra * rc, ra * ra - sin2_cap, n, x0, x1)) continue;
    const f8 va = splat8(static_cast<float>(ra)), vb = splat8(static_cast<float>(rb)), vc = splat8(static_cast<float>(rc));
    Partner part[M];
    const float* planes[M][3];
    group_images<M>(in, f, axes, part, planes);
    for (int y = y0; y <= y1; ++y) {
      int lo = x0, hi = x1;
      if (!row_range(ra, rb, rc, kappa, (2.0 * y + 1.0) / n - 1.0, n, lo, hi)) continue;
      const std::size_t row = static_cast<std::size_t>(y) * nn;
      std::size_t rows[M];
      image_rows<M>(part, static_cast<std::size_t>(y), nn, rows);
      accumulate_row<K, M>(in, lobe, va, vb, vc, d_max, row, rows, planes, lo, hi, acc_w, acc);
      if constexpr (Lobe::row_sums_in_double) {
        // Each row's float lanes added into double totals: float sums over a row at most, not the whole cap.
        total_w += hsum_double(acc_w);
        acc_w = f8{};
        for (int o = 0; o < M; ++o)
          for (int c = 0; c < 3; ++c) {
            total[o][c] += hsum_double(acc[o][c]);
            acc[o][c] = f8{};
          }
      }
    }
  }
  if constexpr (!Lobe::row_sums_in_double) {
    total_w = static_cast<double>(hsum(acc_w));
    for (int o = 0; o < M; ++o)
      for (int c = 0; c < 3; ++c) total[o][c] = static_cast<double>(hsum(acc[o][c]));
  }
  for (int o = 0; o < M; ++o) {
    // A lobe narrower than the texels: the texel each direction points at.
    out[o] = total_w > 0.0 ? Rgb{total[o][0], total[o][1], total[o][2]} / total_w : in.cube->sample(r[o]);
  }
}

// One output level: the input, the output cube, and the cap R.w >= kappa (kappa >= 0) outside which the
// lobe's weight is taken as 0.
struct LevelJob {
  const Input* in = nullptr;
  CubeMap* out = nullptr;
  double kappa = 0.0, sin2_cap = 1.0, cap_angle = pi / 2;
  float d_max = 1.0f;
};
LevelJob level_job(const Input& in, CubeMap& out, double kappa);
// The work items of a level of face `size` (pairs of rows, convolve_rows_k).
inline int level_items(int size) { return 6 * ((size + 1) / 2); }

// Work item `item` of a level: face item / h, rows y = item % h and size - 1 - y (h = (size + 1) / 2 rows
// per face), every texel in a group of four mirror images. Level sizes are powers of two (prefilter_specular
// checks), so only the 1 x 1 level has a texel that is its own image: it is summed alone.
template <int K, class Lobe>
SHADELAB_INLINE void convolve_rows_k(const LevelJob& job, const Lobe& lobe, int begin, int end) {
  const int size = job.out->size;
  const int h = (size + 1) / 2;
  // Texels (xs[o], ys[o]), o < M: xs[0], ys[0] and its images (convolve_group's order).
  auto run = [&](auto m, int face, const int (&xs)[4], const int (&ys)[4], const int (&axes)[2]) SHADELAB_INLINE_LAMBDA {
    constexpr int M = decltype(m)::value;
    Vec3 r[M];
    Rgb out[M];
    for (int o = 0; o < M; ++o) r[o] = texel_direction(face, xs[o], ys[o], size);
    convolve_group<K, M>(*job.in, lobe, r, axes, job.kappa, job.sin2_cap, job.cap_angle, job.d_max, out);
    for (int o = 0; o < M; ++o) job.out->set(face, xs[o], ys[o], out[o]);
  };
  for (int item = begin; item < end; ++item) {
    const int face = item / h;
    const int y = item % h;
    const int ax = face_axis_of_local(face, 0), ay = face_axis_of_local(face, 1);
    const int y2 = size - 1 - y;
    for (int x = 0; x < h; ++x) {
      const int x2 = size - 1 - x;
      if (size > 1) {
        run(std::integral_constant<int, 4>{}, face, {x, x2, x, x2}, {y, y, y2, y2}, {ax, ay});
      } else {
        run(std::integral_constant<int, 1>{}, face, {x, 0, 0, 0}, {y, 0, 0, 0}, {ax, ay});
      }
    }
  }
}

}  // namespace shadelab::lobe_sum

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
