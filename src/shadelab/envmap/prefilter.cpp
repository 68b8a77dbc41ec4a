#include "shadelab/envmap/prefilter.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/simd.h"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace shadelab {

double prefilter_exponent(int level, int mip_count, double gloss_scale, double gloss_bias) {
  const double t = mip_count > 1 ? static_cast<double>(level) / (mip_count - 1) : 0.0;
  return std::exp2(gloss_scale * (1.0 - t) + gloss_bias);  // cmft-style gloss scale and bias
}

Rgb prefilter_brute_force(const CubeMap& radiance, const Vec3& r, double n) {
  const CubeTexelTable& t = CubeTexelTable::get(radiance.size);
  const auto size = static_cast<std::size_t>(radiance.size);
  Rgb sum;
  double weight = 0.0;
  for (std::size_t k = 0; k < t.direction.size(); ++k) {
    const double c = dot(r, t.direction[k]);
    if (c <= 0.0) continue;
    const double w = std::pow(c, n) * t.solid_angle[k];  // (n+1)/(2pi) cancels in the ratio
    const std::size_t face = k / (size * size);
    const std::size_t p = k % (size * size);
    sum += radiance.faces[face].at(static_cast<int>(p % size), static_cast<int>(p / size)) * w;
    weight += w;
  }
  return weight > 0.0 ? sum / weight : Rgb{};
}

namespace {

using namespace simd;

// Lobes: the weight K(t) up to a constant factor as a function of d = 1 - t (8 lanes), and the cosine
// below which K < 1e-9 K(1).
struct PhongLobe {
  float n_log2e = 0.0f;  // n / ln 2: t^n = 2^(n log2(e) ln t)
  int terms = 10;        // terms of the series of ln(1 - d) (narrow caps), 0: range-reduced log (wide caps)
  double cos_cutoff = 0.0;

  // ln t = ln(1 - d). Narrow caps (d <= 1/4) use the series -(d + d^2/2 + ... + d^K/K), no division, with the
  // fewest terms K (4 .. 10) whose remainder, below d^(K+1)/(K+1) / (1 - d), changes n ln t by less than 1e-6
  // at the cap's edge (a relative weight error of 1e-6 where the weight is 1e-9 of its peak, less nearer R).
  explicit PhongLobe(double n) : n_log2e(static_cast<float>(n / 0.69314718055994531)), cos_cutoff(std::pow(1e-9, 1.0 / n)) {
    const double d_max = 1.0 - cos_cutoff;
    if (d_max > 0.25) {
      terms = 0;
    } else {
      terms = 4;
      while (terms < 10 && n * std::pow(d_max, terms + 1) / ((terms + 1) * (1.0 - d_max)) > 1e-6) ++terms;
    }
  }

  template <int K>
  SHADELAB_INLINE static f8 log1m_series(const f8& d) {
    f8 p = splat8(1.0f / K);
    for (int k = K - 1; k >= 1; --k) p = p * d + 1.0f / static_cast<float>(k);
    return -(p * d);
  }
  template <int K>
  SHADELAB_INLINE f8 weight(const f8& d) const {
    if constexpr (K == 0) {
      return exp2_8(n_log2e * log1m_8(d));
    } else {
      return exp2_8(n_log2e * log1m_series<K>(d));
    }
  }
};

// One input level in planar float form, and the per-(x, y) tables shared by its six faces: the local
// direction (a, b, c) = (sc, tc, 1) / |(sc, tc, 1)| and the exact solid angle. Arrays are padded by 8.
struct Input {
  const CubeMap* cube = nullptr;
  int n = 0;
  std::vector<float> rgb[6][3];
  std::vector<float> rgb_reversed[6][3];  // each row's texels in reverse order: [y][x] = rgb[y][n - 1 - x]
  std::vector<float> a, b, c, w;
};

Input make_input(const CubeMap& cube) {
  Input in;
  in.cube = &cube;
  in.n = cube.size;
  const auto nn = static_cast<std::size_t>(cube.size) * static_cast<std::size_t>(cube.size);
  const auto n = static_cast<std::size_t>(cube.size);
  for (std::size_t f = 0; f < 6; ++f) {
    for (auto& plane : in.rgb[f]) plane.assign(nn + 8, 0.0f);
    for (auto& plane : in.rgb_reversed[f]) plane.assign(nn + 8, 0.0f);
    const auto& data = cube.faces[f].data;
    for (std::size_t i = 0; i < nn; ++i)
      for (std::size_t ch = 0; ch < 3; ++ch) {
        in.rgb[f][ch][i] = data[3 * i + ch];
        in.rgb_reversed[f][ch][i - i % n + (n - 1 - i % n)] = data[3 * i + ch];
      }
  }
  const std::vector<double>& omega = cube_face_solid_angles(cube.size);
  for (auto* v : {&in.a, &in.b, &in.c, &in.w}) v->assign(nn + 8, 0.0f);
  for (int y = 0; y < cube.size; ++y) {
    for (int x = 0; x < cube.size; ++x) {
      const double sc = (2.0 * x + 1.0) / cube.size - 1.0;
      const double tc = (2.0 * y + 1.0) / cube.size - 1.0;
      const double inv = 1.0 / std::sqrt(1.0 + sc * sc + tc * tc);
      const auto i = static_cast<std::size_t>(y) * static_cast<std::size_t>(cube.size) + static_cast<std::size_t>(x);
      in.a[i] = static_cast<float>(sc * inv);
      in.b[i] = static_cast<float>(tc * inv);
      in.c[i] = static_cast<float>(inv);
      in.w[i] = static_cast<float>(omega[i]);
    }
  }
  return in;
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
int face_axis_of_local(int face, int local) {
  for (int i = 0; i < 3; ++i)
    if (face_perm[face][i] == local) return i;
  return 0;
}
// The image of texel p's partner under the reflection of world axis `axis`.
Partner reflect(int axis, const Partner& p) {
  const int g = p.face;
  Partner m = p;
  m.face = face_axis_of_local(g, 2) == axis ? (g ^ 1) : g;  // faces +X -X +Y -Y +Z -Z: g ^ 1 is the opposite face, same perm
  const int ia = face_axis_of_local(g, 0);
  const bool flips_x = face_sign[m.face][ia] * face_sign[g][ia] * (ia == axis ? -1.0 : 1.0) < 0.0;
  (flips_x ? m.flip_x : m.flip_y) ^= true;
  return m;
}
// The texel index range [lo, hi] whose centres (2k + 1)/N - 1 can lie where the quadratic
// q2 s^2 + 2 q1 s + q0 <= 0 (s in [-1, 1]); false if none. Conservative: one texel of margin.
bool index_range(double q2, double q1, double q0, int n, int& lo, int& hi) {
  double s0 = -1.0, s1 = 1.0;
  if (q2 > 1e-12) {
    const double disc = q1 * q1 - q2 * q0;
    if (disc < 0.0) return false;
    const double root = std::sqrt(disc);
    s0 = std::max(-1.0, (-q1 - root) / q2);
    s1 = std::min(1.0, (-q1 + root) / q2);
    if (s0 > s1) return false;
  }
  lo = std::max(0, static_cast<int>(std::floor(((s0 + 1.0) * n - 1.0) * 0.5)) - 1);
  hi = std::min(n - 1, static_cast<int>(std::ceil(((s1 + 1.0) * n - 1.0) * 0.5)) + 1);
  return lo <= hi;
}

// The x range of row tc inside the cap r.p >= kappa |p|, p = (sc, tc, 1) (face-local): squaring,
// (ra^2 - kappa^2) sc^2 + 2 ra beta sc + beta^2 - kappa^2 (1 + tc^2) >= 0 with beta = rb tc + rc. When
// ra^2 < kappa^2 that is one interval (the cap's side is where ra sc + beta > 0); otherwise the row can meet
// the cap in a ray, and the face-wide column range is kept. Narrows [lo, hi]; false if the row misses.
bool row_range(double ra, double rb, double rc, double kappa, double tc, int n, int& lo, int& hi) {
  const double beta = rb * tc + rc;
  const double a2 = ra * ra - kappa * kappa;
  if (a2 >= -1e-9) return true;
  const double b1 = ra * beta;
  const double c0 = beta * beta - kappa * kappa * (1.0 + tc * tc);
  const double disc = b1 * b1 - a2 * c0;
  if (disc < 0.0) return false;
  const double root = std::sqrt(disc);
  const double s0 = (-b1 + root) / a2, s1 = (-b1 - root) / a2;  // a2 < 0: s0 <= s1
  if (ra * 0.5 * (s0 + s1) + beta <= 0.0) return false;          // the antipodal nappe
  lo = std::max(lo, static_cast<int>(std::floor(((s0 + 1.0) * n - 1.0) * 0.5)) - 1);
  hi = std::min(hi, static_cast<int>(std::ceil(((s1 + 1.0) * n - 1.0) * 0.5)) + 1);
  return lo <= hi;
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
    for (int o = 0; o < M; ++o) {
      part[o].face = f;
      if (o & 1) part[o] = reflect(axes[0], part[o]);
      if (o & 2) part[o] = reflect(axes[1], part[o]);
      const auto& src = part[o].flip_x ? in.rgb_reversed[static_cast<std::size_t>(part[o].face)] : in.rgb[static_cast<std::size_t>(part[o].face)];
      for (int c = 0; c < 3; ++c) planes[o][c] = src[static_cast<std::size_t>(c)].data();
    }
    for (int y = y0; y <= y1; ++y) {
      int lo = x0, hi = x1;
      if (!row_range(ra, rb, rc, kappa, (2.0 * y + 1.0) / n - 1.0, n, lo, hi)) continue;
      const std::size_t row = static_cast<std::size_t>(y) * nn;
      std::size_t rows[M];
      for (int o = 0; o < M; ++o) rows[o] = (part[o].flip_y ? nn - 1 - static_cast<std::size_t>(y) : static_cast<std::size_t>(y)) * nn;
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
  }
  const double sw = hsum(acc_w);
  for (int o = 0; o < M; ++o) {
    // A lobe narrower than the texels: the texel each direction points at.
    out[o] = sw > 0.0 ? Rgb{hsum(acc[o][0]), hsum(acc[o][1]), hsum(acc[o][2])} / sw : in.cube->sample(r[o]);
  }
}

struct LevelJob {
  const Input* in = nullptr;
  CubeMap* out = nullptr;
  double kappa = 0.0, sin2_cap = 1.0, cap_angle = pi / 2;
  float d_max = 1.0f;
};

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

SHADELAB_INLINE void convolve_rows_phong(const LevelJob& job, const PhongLobe& lobe, int begin, int end) {
  switch (lobe.terms) {
    case 0: convolve_rows_k<0>(job, lobe, begin, end); break;
    case 4: convolve_rows_k<4>(job, lobe, begin, end); break;
    case 5: convolve_rows_k<5>(job, lobe, begin, end); break;
    case 6: convolve_rows_k<6>(job, lobe, begin, end); break;
    case 7: convolve_rows_k<7>(job, lobe, begin, end); break;
    case 8: convolve_rows_k<8>(job, lobe, begin, end); break;
    case 9: convolve_rows_k<9>(job, lobe, begin, end); break;
    default: convolve_rows_k<10>(job, lobe, begin, end); break;
  }
}
SHADELAB_TARGET_AVX2 void convolve_rows_phong_avx2(const LevelJob& job, const PhongLobe& lobe, int begin, int end) {
  convolve_rows_phong(job, lobe, begin, end);
}
void convolve_rows_phong_base(const LevelJob& job, const PhongLobe& lobe, int begin, int end) {
  convolve_rows_phong(job, lobe, begin, end);
}

}  // namespace

Result<PrefilteredCube> prefilter_specular(const CubeMap& radiance, const PrefilterOptions& o) {
  if (o.size < 1 || (o.size & (o.size - 1)) != 0) {
    return make_error("prefilter: size " + std::to_string(o.size) + " is not a power of two");
  }
  int max_levels = 1;
  while ((o.size >> (max_levels - 1)) > 1) ++max_levels;
  const int levels = o.mip_count == 0 ? max_levels : o.mip_count;
  if (levels < 1 || levels > max_levels) {
    return make_error("prefilter: mip count " + std::to_string(o.mip_count) + " is out of range [1, " +
                      std::to_string(max_levels) + "] for size " + std::to_string(o.size));
  }
  if (!std::isfinite(o.gloss_scale) || !std::isfinite(o.gloss_bias) || o.gloss_scale < 0.0) {
    return make_error("prefilter: gloss scale must be finite and >= 0, gloss bias finite");
  }
  if (radiance.size < 1) return make_error("prefilter: the input cube map is empty");

  // The input pyramid, finest first: sizes now, levels halved on demand.
  std::vector<int> sizes{radiance.size};
  while (sizes.back() % 2 == 0 && sizes.back() > 1) sizes.push_back(sizes.back() / 2);
  std::vector<CubeMap> pyramid(sizes.size());
  std::vector<Input> prepared(sizes.size());
  const bool avx = cpu_has_avx2_fma();

  PrefilteredCube out;
  long long total_rows = 0;
  for (int i = 0; i < levels; ++i) total_rows += 6LL * ((std::max(1, o.size >> i) + 1) / 2);
  long long rows_done = 0;
  for (int i = 0; i < levels; ++i) {
    const int size = std::max(1, o.size >> i);
    const double n = prefilter_exponent(i, levels, o.gloss_scale, o.gloss_bias);
    const PhongLobe lobe(n);
    const double kappa = std::max(0.0, lobe.cos_cutoff);  // caps wider than a hemisphere are cut at t = 0
    // The finest input level within 2e9 weight evaluations (outputs x texels in the cap, a (1 - kappa)/2
    // fraction of the sphere), but never one whose texels (about (pi/2)/N) exceed half the lobe width.
    const double outputs = 6.0 * size * size;
    std::size_t pick = sizes.size() - 1;
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      const double texels = 6.0 * sizes[k] * sizes[k] * (1.0 - kappa) / 2.0;
      if (outputs * texels <= 2e9) {
        pick = k;
        break;
      }
    }
    while (pick > 0 && (pi / 2.0) / sizes[pick] > 0.5 / std::sqrt(n)) --pick;
    if (prepared[pick].cube == nullptr) {
      for (std::size_t k = 1; k <= pick; ++k) {
        if (pyramid[k].size == 0) pyramid[k] = downsample_cube(k == 1 ? radiance : pyramid[k - 1]);
      }
      prepared[pick] = make_input(pick == 0 ? radiance : pyramid[pick]);
    }

    CubeMap level(size);
    LevelJob job;
    job.in = &prepared[pick];
    job.out = &level;
    job.kappa = kappa;
    job.cap_angle = std::acos(kappa);
    job.sin2_cap = 1.0 - kappa * kappa;
    job.d_max = static_cast<float>(1.0 - kappa);
    const int rows = 6 * ((size + 1) / 2);  // work items: pairs of rows (convolve_rows_k)
    const int chunk = std::max(1, rows / 20);
    for (int start = 0; start < rows; start += chunk) {
      const int end = std::min(rows, start + chunk);
      tbb::parallel_for(tbb::blocked_range<int>(start, end), [&](const tbb::blocked_range<int>& range) {
        if (avx) {
          convolve_rows_phong_avx2(job, lobe, range.begin(), range.end());
        } else {
          convolve_rows_phong_base(job, lobe, range.begin(), range.end());
        }
      });
      rows_done += end - start;
      if (o.progress) o.progress(static_cast<double>(rows_done) / static_cast<double>(total_rows));
    }
    out.levels.push_back(std::move(level));
    out.exponents.push_back(n);
  }
  return out;
}

}  // namespace shadelab
