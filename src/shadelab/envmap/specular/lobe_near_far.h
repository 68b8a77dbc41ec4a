// shadelab envmap internals: the lobe sum of lobe_sum.h split into a near field, summed over the input texels
// exactly, and a far field, summed over cells of the input (blocks of texels of a face), each cell taken as
// its flux placed at its radiance centroid: the monopole of a hierarchical sum (Barnes & Hut 1986, "A
// hierarchical O(N log N) force-calculation algorithm", a far cell at its centre of mass), with two cell
// sizes (mid B x B and coarse C x C texels, C a multiple of B):
//
//   out(R) = [sum_near K(R.p) L_p dOmega_p + sum_far K(R.c_q) Phi_q] / [sum_near K(R.p) dOmega_p + sum_far K(R.g_q) Omega_q]
//
// with, per cell q: Phi_q = sum_{p in q} L_p dOmega_p (each channel), c_q = normalize(sum_{p in q} (L_p.r + L_p.g +
// L_p.b)^+ dOmega_p p) the radiance centroid, g_q = normalize(sum_{p in q} dOmega_p p) and Omega_q = sum dOmega_p.
// Fields: coarse cells whose centre is within mid_angle of R are refined into their mid cells, and those
// whose centre is within near_angle into their texels (per row of cells an interval: the row's centres lie
// on a great circle). Exact when near_angle covers the sphere; a point source anywhere is exact (its cell's
// centroid is its direction); radiance spread over a cell errs by the lobe's curvature across the cell,
// second order in (cell size / angle to R): a lobe falling as theta^-4 (the GGX tail) gives about
// 1.7 (s / theta)^2 of that cell's share for radiance spread evenly over a cell of side s. A constant
// environment stays constant: c_q = g_q for it. Not a public header: no stable API.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "shadelab/envmap/specular/lobe_sum.h"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace shadelab::lobe_sum {

// The cells of an input cube: blocks of B x B texels of each face, n = N / B per side. Arrays are
// indexed [Y * n + X] and padded by 8.
struct FarInput {
  int block = 0;
  int n = 0;
  std::vector<float> ga, gb, gc, omega;  // per (X, Y), shared by the faces: g_q (face-local) and Omega_q
  std::vector<float> flux[6][3], flux_reversed[6][3];  // Phi_q per channel; _reversed: each row in reverse order
  std::vector<float> cen[6][3], cen_reversed[6][3];    // c_q (face-local a, b, c)
};

// The cells of `cube` (face size a multiple of block, block >= 1).
FarInput make_far_input(const CubeMap& cube, int block);

// The cells [lo, hi] of row y of an n x n grid of cells (centres at sc, tc = (2 i + 1) / n - 1, face-local)
// whose centre direction p has r.p >= cos_t |p|: from the first to the last such cell (the set is an
// interval when the angle is below 90 degrees: the row's centres lie on a great circle). Solved from the
// quadratic of row_range (lobe_sum.h) and settled by the direct test at its ends; a scan where the
// quadratic does not bound the row. False if none.
bool cap_cells(double ra, double rb, double rc, double cos_t, int n, int y, int& lo, int& hi);

// One image's rows of a FarInput, as convolve_group's planes: flux and centroids of the face the image
// reads, rows reversed where it flips x.
template <int M>
struct FarPlanes {
  const float* flux[M][3];
  const float* cen[M][3];
  Partner part[M];
};

template <int M>
SHADELAB_INLINE FarPlanes<M> far_planes(const FarInput& far, const Partner (&part)[M]) {
  FarPlanes<M> p{};
  for (int o = 0; o < M; ++o) {
    const auto g = static_cast<std::size_t>(part[o].face);
    const auto& fsrc = part[o].flip_x ? far.flux_reversed[g] : far.flux[g];
    const auto& csrc = part[o].flip_x ? far.cen_reversed[g] : far.cen[g];
    for (int c = 0; c < 3; ++c) {
      p.flux[o][c] = fsrc[static_cast<std::size_t>(c)].data();
      p.cen[o][c] = csrc[static_cast<std::size_t>(c)].data();
    }
    p.part[o] = part[o];
  }
  return p;
}

// Cells lo..hi of row y of `far`, except ex_lo..ex_hi, added at their centroids: the weight sum at the
// geometric centroid g_q (omega_q), each image's radiance at its own c_q; none beyond r's horizon.
template <int K, int M, class Lobe>
SHADELAB_INLINE void accumulate_far_row(const FarInput& far, const FarPlanes<M>& p, const Lobe& lobe, const f8& va, const f8& vb,
                                        const f8& vc, const f8 (&sa)[M], const f8 (&sb)[M], int y, int lo, int hi, int ex_lo,
                                        int ex_hi, f8& acc_w, f8 (&acc)[M][3]) {
  const auto nc = static_cast<std::size_t>(far.n);
  const std::size_t row = static_cast<std::size_t>(y) * nc;
  std::size_t rows[M];
  image_rows<M>(p.part, static_cast<std::size_t>(y), nc, rows);
  const f8 last = splat8(static_cast<float>(hi));
  const f8 near_lo = splat8(static_cast<float>(ex_lo)), near_hi = splat8(static_cast<float>(ex_hi));
  for (int x = lo; x <= hi; x += 8) {
    const f8 xs = iota8() + static_cast<float>(x);
    const i8 cell = (xs <= last) & ((xs < near_lo) | (xs > near_hi));
    const std::size_t i = row + static_cast<std::size_t>(x);
    const f8 dg = 1.0f - (va * load8(far.ga.data() + i) + vb * load8(far.gb.data() + i) + vc * load8(far.gc.data() + i));
    acc_w += select(cell & (dg <= 1.0f), lobe.template weight<K>(dg) * load8(far.omega.data() + i), splat8(0.0f));
    for (int o = 0; o < M; ++o) {
      const std::size_t j = rows[o] + static_cast<std::size_t>(x);
      const f8 d = 1.0f - (sa[o] * load8(p.cen[o][0] + j) + sb[o] * load8(p.cen[o][1] + j) + vc * load8(p.cen[o][2] + j));
      const f8 wt = select(cell & (d <= 1.0f), lobe.template weight<K>(d), splat8(0.0f));
      for (int c = 0; c < 3; ++c) acc[o][c] += wt * load8(p.flux[o][c] + j);
    }
  }
}

// The lobe about r[0] and its M - 1 mirror images (convolve_group's groups) in three fields: input texels
// within near_angle (radians) of r, cells of `mid` (B x B texels) within mid_angle, cells of `coarse`
// (C x C texels, C a multiple of B) beyond. A coarse cell is refined when its centre is within mid_angle;
// the mid cells of refined coarse cells are refined to texels when their centre is within near_angle
// (clamped to the refined span, so the three fields partition the sphere whatever the angles). The near
// weights serve the whole group, as in convolve_group; a far cell's weight is evaluated for each image at
// that image's centroid.
template <int K, int M, class Lobe>
SHADELAB_INLINE void convolve_group_near_far(const Input& in, const FarInput& mid, const FarInput& coarse, const Lobe& lobe,
                                             const Vec3 (&r)[M], const int (&axes)[2], double near_angle, double mid_angle,
                                             Rgb (&out)[M]) {
  const int ratio = coarse.block / mid.block;
  const int block = mid.block;
  const auto nn = static_cast<std::size_t>(in.n);
  const double cos_near = std::cos(std::min(near_angle, pi));
  const double cos_mid = std::cos(std::min(mid_angle, pi));
  f8 acc_w = {};
  f8 acc[M][3] = {};
  double total_w = 0.0;
  double total[M][3] = {};
  const auto flush = [&]() SHADELAB_INLINE_LAMBDA {
    // Each row's float lanes added into double totals (lobe_sum.h's row_sums_in_double).
    total_w += hsum_double(acc_w);
    acc_w = f8{};
    for (int o = 0; o < M; ++o)
      for (int c = 0; c < 3; ++c) {
        total[o][c] += hsum_double(acc[o][c]);
        acc[o][c] = f8{};
      }
  };
  for (int f = 0; f < 6; ++f) {
    double local[3];
    for (int i = 0; i < 3; ++i) local[face_perm[f][i]] = face_sign[f][i] * r[0][i];
    const double ra = local[0], rb = local[1], rc = local[2];
    // Every point of a face is within acos(1/sqrt(3)) of its axis: a face wholly below r's horizon adds nothing.
    const double to_axis = std::acos(std::clamp(rc, -1.0, 1.0));
    if (to_axis > pi / 2 + 0.9553166181245093) continue;
    const bool any_mid = to_axis <= mid_angle + 0.9553166181245093;
    const f8 va = splat8(static_cast<float>(ra)), vb = splat8(static_cast<float>(rb)), vc = splat8(static_cast<float>(rc));
    Partner part[M];
    const float* planes[M][3];
    group_images<M>(in, f, axes, part, planes);
    f8 sa[M], sb[M];  // r's local a and b as each image's centroids are read (negated where the image flips)
    for (int o = 0; o < M; ++o) {
      sa[o] = part[o].flip_x ? -va : va;
      sb[o] = part[o].flip_y ? -vb : vb;
    }
    const FarPlanes<M> mid_planes = far_planes<M>(mid, part);
    const FarPlanes<M> coarse_planes = far_planes<M>(coarse, part);
    for (int cy = 0; cy < coarse.n; ++cy) {
      // The refined span [cx0, cx1] of this row of coarse cells; the others are summed as coarse cells.
      int cx0 = coarse.n, cx1 = -1;
      if (any_mid && !cap_cells(ra, rb, rc, cos_mid, coarse.n, cy, cx0, cx1)) cx0 = coarse.n, cx1 = -1;
      accumulate_far_row<K, M>(coarse, coarse_planes, lobe, va, vb, vc, sa, sb, cy, 0, coarse.n - 1, cx0, cx1, acc_w, acc);
      flush();
      if (cx0 > cx1) continue;
      const int mlo = cx0 * ratio, mhi = cx1 * ratio + ratio - 1;
      for (int y = cy * ratio; y < (cy + 1) * ratio; ++y) {
        // The near cells [x0, x1] of this row of mid cells, within the refined span.
        int x0 = mid.n, x1 = -1;
        if (cap_cells(ra, rb, rc, cos_near, mid.n, y, x0, x1)) {
          x0 = std::max(x0, mlo);
          x1 = std::min(x1, mhi);
        }
        if (x0 > x1) x0 = mid.n, x1 = -1;
        accumulate_far_row<K, M>(mid, mid_planes, lobe, va, vb, vc, sa, sb, y, mlo, mhi, x0, x1, acc_w, acc);
        // Near: the input texels of cells x0..x1, rows y B .. y B + B - 1, exactly (convolve_group's rows).
        if (x0 <= x1) {
          for (int yy = y * block; yy < (y + 1) * block; ++yy) {
            const std::size_t row = static_cast<std::size_t>(yy) * nn;
            std::size_t rows[M];
            image_rows<M>(part, static_cast<std::size_t>(yy), nn, rows);
            accumulate_row<K, M>(in, lobe, va, vb, vc, 1.0f, row, rows, planes, x0 * block, x1 * block + block - 1, acc_w, acc);
          }
        }
        flush();
      }
    }
  }
  for (int o = 0; o < M; ++o) {
    out[o] = total_w > 0.0 ? Rgb{total[o][0], total[o][1], total[o][2]} / total_w : in.cube->sample(r[o]);
  }
}

// One output level summed near and far: convolve_rows_k's work items (pairs of rows, groups of four mirror
// images) with convolve_group_near_far.
struct NearFarJob {
  const Input* in = nullptr;
  const FarInput* mid = nullptr;
  const FarInput* coarse = nullptr;
  CubeMap* out = nullptr;
  double near_angle = pi;
  double mid_angle = pi;
};

template <int K, class Lobe>
SHADELAB_INLINE void convolve_rows_near_far(const NearFarJob& job, const Lobe& lobe, int begin, int end) {
  const int size = job.out->size;
  const int h = (size + 1) / 2;
  for (int item = begin; item < end; ++item) {
    const int face = item / h;
    const int y = item % h;
    const int axes[2] = {face_axis_of_local(face, 0), face_axis_of_local(face, 1)};
    const int y2 = size - 1 - y;
    for (int x = 0; x < h; ++x) {
      const int x2 = size - 1 - x;
      if (size > 1) {
        const int xs[4] = {x, x2, x, x2}, ys[4] = {y, y, y2, y2};
        Vec3 r[4];
        Rgb v[4];
        for (int o = 0; o < 4; ++o) r[o] = texel_direction(face, xs[o], ys[o], size);
        convolve_group_near_far<K, 4>(*job.in, *job.mid, *job.coarse, lobe, r, axes, job.near_angle, job.mid_angle, v);
        for (int o = 0; o < 4; ++o) job.out->set(face, xs[o], ys[o], v[o]);
      } else {
        Vec3 r[1] = {texel_direction(face, 0, 0, 1)};
        Rgb v[1];
        convolve_group_near_far<K, 1>(*job.in, *job.mid, *job.coarse, lobe, r, axes, job.near_angle, job.mid_angle, v);
        job.out->set(face, 0, 0, v[0]);
      }
    }
  }
}

}  // namespace shadelab::lobe_sum

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
