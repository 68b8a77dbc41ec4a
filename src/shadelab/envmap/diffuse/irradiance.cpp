#include "shadelab/envmap/diffuse/irradiance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/base/downsample.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/envmap/base/simd.h"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace shadelab {

Rgb irradiance_brute_force(const CubeMap& radiance, const Vec3& n) {
  const CubeTexelTable& t = CubeTexelTable::get(radiance.size);
  Rgb sum;
  double weight = 0.0;
  const auto size = static_cast<std::size_t>(radiance.size);
  for (std::size_t k = 0; k < t.direction.size(); ++k) {
    const double c = dot(n, t.direction[k]);
    if (c <= 0.0) continue;
    const std::size_t face = k / (size * size);
    const std::size_t p = k % (size * size);
    sum += radiance.faces[face].at(static_cast<int>(p % size), static_cast<int>(p / size)) * (c * t.solid_angle[k]);
    weight += c * t.solid_angle[k];
  }
  return weight > 0.0 ? sum / weight * pi : Rgb{};
}

Rgb irradiance_brute_force(const Image& latlong, const Vec3& n) {
  const int w = latlong.width;
  const int h = latlong.height;
  Rgb sum;
  double weight = 0.0;
  for (int y = 0; y < h; ++y) {
    const double d_omega = latlong_texel_solid_angle(y, w, h);
    for (int x = 0; x < w; ++x) {
      const double c = dot(n, latlong_direction((x + 0.5) / w, (y + 0.5) / h));
      if (c > 0.0) {
        sum += latlong.at(x, y) * (c * d_omega);
        weight += c * d_omega;
      }
    }
  }
  return weight > 0.0 ? sum / weight * pi : Rgb{};
}

namespace {

using namespace simd;

// Emitters on lines. Entry k of line l is the prefix sum over the line's first k texels of the moment
// vectors L_c dOmega w, 12 floats (x, y, z for R, then G, then B, then W: L = 1), summed in double and
// stored in float. Channel W's sums are the cosine weights W(n) = sum max(0, n.w) dOmega of the same
// texels, computed in the same pass over the same runs, with the arithmetic of the colour channels.
constexpr int channels = 4;
constexpr std::size_t stride = 3 * channels;
struct Lines {
  bool rings = false;   // lat-long latitude rings (wrapping runs) or cube face rows (prefix / suffix runs)
  int count = 0;        // lines
  int length = 0;       // texels per line
  int face_size = 0;    // cube rows: N (line l is row l % N of face l / N)
  std::vector<float> param;   // cube rows: tc of the row; rings: cot(theta) of the ring
  FloatBuffer prefix;  // count * (length + 1) * 12, plus 4 floats of padding for 4-wide loads
  // Added to every normal's sum: sum over the lines of K_l (below), 9 values as a prefix entry.
  std::array<double, stride> constant{};
  // M = sum of L dOmega d over every texel of the map (9 values as a prefix entry), in double.
  std::array<double, stride> first_moment{};

  const float* entry(int line, int k) const {
    return prefix.data() + (static_cast<std::size_t>(line) * static_cast<std::size_t>(length + 1) + static_cast<std::size_t>(k)) * stride;
  }
};

void store_prefix(Lines& lines, int line, const std::vector<double>& moments /* length * stride */) {
  const std::size_t s = stride;
  float* out = lines.prefix.data() + static_cast<std::size_t>(line) * static_cast<std::size_t>(lines.length + 1) * s;
  double acc[stride] = {};
  for (std::size_t i = 0; i < s; ++i) out[i] = 0.0f;
  for (int k = 0; k < lines.length; ++k) {
    for (std::size_t i = 0; i < s; ++i) {
      acc[i] += moments[static_cast<std::size_t>(k) * s + i];
      out[static_cast<std::size_t>(k + 1) * s + i] = static_cast<float>(acc[i]);
    }
  }
}

Lines cube_lines(const CubeMap& cube) {
  const int n = cube.size;
  const std::vector<double>& solid_angle = cube_face_solid_angles(n);
  Lines lines;
  lines.count = 6 * n;
  lines.length = n;
  lines.face_size = n;
  const std::size_t s = stride;
  lines.param.resize(static_cast<std::size_t>(lines.count));
  lines.prefix.assign(static_cast<std::size_t>(lines.count) * static_cast<std::size_t>(n + 1) * s + 4, 0.0f);
  tbb::parallel_for(0, lines.count, [&](int l) {
    const int f = l / n;
    const int y = l % n;
    lines.param[static_cast<std::size_t>(l)] = static_cast<float>((2.0 * y + 1.0) / n - 1.0);
    std::vector<double> m(static_cast<std::size_t>(n) * s);
    for (int x = 0; x < n; ++x) {
      const Vec3 d = texel_direction(f, x, y, n);
      const double omega = solid_angle[static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x)];
      const Rgb radiance = cube.texel(f, x, y);
      const double l_omega[channels] = {radiance.r * omega, radiance.g * omega, radiance.b * omega, omega};
      for (int c = 0; c < channels; ++c) {
        m[static_cast<std::size_t>(x) * s + static_cast<std::size_t>(3 * c)] = l_omega[c] * d.x;
        m[static_cast<std::size_t>(x) * s + static_cast<std::size_t>(3 * c + 1)] = l_omega[c] * d.y;
        m[static_cast<std::size_t>(x) * s + static_cast<std::size_t>(3 * c + 2)] = l_omega[c] * d.z;
      }
    }
    store_prefix(lines, l, m);
  });
  for (int l = 0; l < lines.count; ++l) {
    const float* t = lines.entry(l, lines.length);
    for (std::size_t i = 0; i < s; ++i) lines.first_moment[i] += static_cast<double>(t[i]);
  }
  return lines;
}

// Rings of a lat-long. With an even width and height, ring y and ring y' = h - 1 - y share one line: texel
// (x + w/2 mod w, y') is the antipode of texel (x, y) (phi + pi, pi - theta), so it lies in n's hemisphere
// exactly when (x, y) does not. The pair's sum over n's hemisphere is then
//   sum_{x in run} m_y[x] + sum_{x not in run} m_y'[x + w/2] = K + sum_{x in run} (m_y[x] - m_y'[x + w/2])
// with K = sum_x m_y'[x] (the whole of ring y'), and m_y[x] - m_y'[x + w/2] = (L_y[x] + L_y'[x + w/2]) dOmega
// d(x, y) (d' = -d): a sum, no cancellation. The same texels as two lines, in half the line steps; the run is
// ring y's. The K of all lines are summed once (Lines::constant).
Lines ring_lines(const Image& ll) {
  const int w = ll.width;
  const int h = ll.height;
  const bool paired = w % 2 == 0 && h % 2 == 0;
  Lines lines;
  lines.rings = true;
  lines.count = paired ? h / 2 : h;
  lines.length = w;
  const std::size_t s = stride;
  lines.param.resize(static_cast<std::size_t>(lines.count));
  lines.prefix.assign(static_cast<std::size_t>(lines.count) * static_cast<std::size_t>(w + 1) * s + 4, 0.0f);
  std::vector<double> cos_phi(static_cast<std::size_t>(w)), sin_phi(static_cast<std::size_t>(w));
  for (int x = 0; x < w; ++x) {
    const double phi = two_pi * ((x + 0.5) / w - 0.5);  // latlong.h: phi = 2 pi (u - 0.5)
    cos_phi[static_cast<std::size_t>(x)] = std::cos(phi);
    sin_phi[static_cast<std::size_t>(x)] = std::sin(phi);
  }
  // Per line: K (the partner ring's total) and the line's share of M, summed afterwards in line order.
  std::vector<std::array<double, stride>> k_line(static_cast<std::size_t>(lines.count)), m_line(static_cast<std::size_t>(lines.count));
  const auto ring_moments = [&](int y, std::vector<double>& m) {
    const double theta = pi * (y + 0.5) / h;
    const double st = std::sin(theta);
    const double ct = std::cos(theta);
    const double d_omega = latlong_texel_solid_angle(y, w, h);
    for (int x = 0; x < w; ++x) {
      const Vec3 d{st * cos_phi[static_cast<std::size_t>(x)], ct, st * sin_phi[static_cast<std::size_t>(x)]};
      const Rgb l = ll.at(x, y);
      const double l_omega[channels] = {l.r * d_omega, l.g * d_omega, l.b * d_omega, d_omega};
      for (int c = 0; c < channels; ++c) {
        m[static_cast<std::size_t>(x) * s + static_cast<std::size_t>(3 * c)] = l_omega[c] * d.x;
        m[static_cast<std::size_t>(x) * s + static_cast<std::size_t>(3 * c + 1)] = l_omega[c] * d.y;
        m[static_cast<std::size_t>(x) * s + static_cast<std::size_t>(3 * c + 2)] = l_omega[c] * d.z;
      }
    }
  };
  const auto total = [&](const std::vector<double>& m, std::array<double, stride>& t) {
    for (int x = 0; x < w; ++x)
      for (std::size_t i = 0; i < s; ++i) t[i] += m[static_cast<std::size_t>(x) * s + i];
  };
  tbb::parallel_for(0, lines.count, [&](int y) {
    const double theta = pi * (y + 0.5) / h;
    lines.param[static_cast<std::size_t>(y)] = static_cast<float>(std::cos(theta) / std::sin(theta));
    std::vector<double> m(static_cast<std::size_t>(w) * s);
    ring_moments(y, m);
    std::array<double, stride>& mt = m_line[static_cast<std::size_t>(y)];
    total(m, mt);
    if (paired) {
      std::vector<double> partner(static_cast<std::size_t>(w) * s);
      ring_moments(h - 1 - y, partner);
      std::array<double, stride>& k = k_line[static_cast<std::size_t>(y)];
      total(partner, k);
      for (std::size_t i = 0; i < s; ++i) mt[i] += k[i];
      for (int x = 0; x < w; ++x) {
        const auto xs = static_cast<std::size_t>((x + w / 2) % w);
        for (std::size_t i = 0; i < s; ++i) m[static_cast<std::size_t>(x) * s + i] -= partner[xs * s + i];
      }
    }
    store_prefix(lines, y, m);
  });
  for (std::size_t l = 0; l < k_line.size(); ++l) {
    for (std::size_t i = 0; i < s; ++i) {
      lines.constant[i] += k_line[l][i];
      lines.first_moment[i] += m_line[l][i];
    }
  }
  return lines;
}

// Per-normal data for a block of normals, structure of arrays padded to a multiple of 8.
struct NormalBlock {
  int count = 0;
  int padded = 0;
  std::vector<float> n4;              // (nx, ny, nz, 0) per normal
  std::vector<float> face_local[6][3];  // cube rows: (na, nb, nc) of the normal in each face's (a, b, c) frame
  std::vector<float> phi, q;          // rings: atan2(nz, nx) and -ny / sqrt(nx^2 + nz^2)
};

NormalBlock make_block(const Vec3* normals, int count, bool rings) {
  NormalBlock b;
  b.count = count;
  b.padded = (count + 7) / 8 * 8;
  const auto p = static_cast<std::size_t>(b.padded);
  b.n4.assign(p * 4, 0.0f);
  if (rings) {
    b.phi.assign(p, 0.0f);
    b.q.assign(p, 0.0f);
  } else {
    for (auto& f : b.face_local)
      for (auto& v : f) v.assign(p, 0.0f);
  }
  for (int i = 0; i < count; ++i) {
    const Vec3 n = normals[i];
    const auto k = static_cast<std::size_t>(i);
    b.n4[4 * k] = static_cast<float>(n.x);
    b.n4[4 * k + 1] = static_cast<float>(n.y);
    b.n4[4 * k + 2] = static_cast<float>(n.z);
    if (rings) {
      const double r = std::sqrt(n.x * n.x + n.z * n.z);
      b.phi[k] = static_cast<float>(std::atan2(n.z, n.x));
      b.q[k] = static_cast<float>(std::clamp(-n.y / std::max(r, 1e-30), -1e30, 1e30));
    } else {
      // n.d for d = the face's signed permutation of (a, b, c) (cubemap.h, the inverse of table 8.19).
      const double local[6][3] = {{-n.z, -n.y, n.x}, {n.z, -n.y, -n.x}, {n.x, n.z, n.y},
                                  {n.x, -n.z, -n.y}, {n.x, -n.y, n.z}, {-n.x, -n.y, -n.z}};
      for (int f = 0; f < 6; ++f)
        for (int c = 0; c < 3; ++c)
          b.face_local[f][c][k] = static_cast<float>(local[f][c]);
    }
  }
  return b;
}

// Run [lo, hi) of line `line` for 8 normals starting at i; wrap = 1 where the run wraps past the end.
SHADELAB_INLINE void runs8(const Lines& lines, const NormalBlock& b, int line, int i, int* lo, int* hi, float* wrap) {
  const float len = static_cast<float>(lines.length);
  f8 vlo, vhi, vwrap = splat8(0.0f);
  if (!lines.rings) {
    // Texel x is in the run iff na sc_x + (nb tc + nc) > 0, sc_x = (2x + 1)/N - 1 (linear in x).
    const int f = line / lines.face_size;
    const float tc = lines.param[static_cast<std::size_t>(line)];
    const f8 na = load8(b.face_local[f][0].data() + i);
    const f8 rhs = load8(b.face_local[f][1].data() + i) * tc + load8(b.face_local[f][2].data() + i);
    const i8 tiny = (na < 1e-30f) & (na > -1e-30f);
    f8 theta = select(tiny, select(rhs > 0.0f, splat8(-4.0f), splat8(4.0f)), -rhs / select(tiny, splat8(1.0f), na));
    theta = vmin(vmax(theta, splat8(-4.0f)), splat8(4.0f));
    const f8 q = ((theta + 1.0f) * len - 1.0f) * 0.5f;  // texel x satisfies sc_x = theta at x = q
    const i8 suffix = tiny | (na > 0.0f);               // na > 0: x > q; na < 0: x < q
    const f8 first = vmin(vmax(floor8(q) + 1.0f, splat8(0.0f)), splat8(len));
    const f8 last = vmin(vmax(-floor8(-q), splat8(0.0f)), splat8(len));
    vlo = select(suffix, first, splat8(0.0f));
    vhi = select(suffix, splat8(len), last);
  } else {
    // Texel x (phi_x = -pi + (x + 1/2) dphi) is in the run iff |phi_x - phi_n| < acos(q cot theta) (mod 2 pi).
    const float cot = lines.param[static_cast<std::size_t>(line)];
    const f8 c = load8(b.q.data() + i) * cot;
    const f8 half = acos8(c);
    const f8 phi = load8(b.phi.data() + i);
    const float inv_dphi = len / 6.28318530718f;
    const f8 j0 = floor8((phi - half + 3.14159265359f) * inv_dphi - 0.5f) + 1.0f;
    const f8 j1 = floor8((phi + half + 3.14159265359f) * inv_dphi - 0.5f) + 1.0f;
    f8 count = vmin(vmax(j1 - j0, splat8(0.0f)), splat8(len));
    count = select(c <= -1.0f, splat8(len), select(c >= 1.0f, splat8(0.0f), count));
    f8 start = select(j0 < 0.0f, j0 + len, select(j0 >= len, j0 - len, j0));
    start = select(c <= -1.0f, splat8(0.0f), start);
    f8 end = start + count;
    const i8 wraps = end > len;
    end = select(wraps, end - len, end);
    vlo = start;
    vhi = end;
    vwrap = select(wraps, splat8(1.0f), splat8(0.0f));
  }
  const i8 ilo = to_int8(vlo);
  const i8 ihi = to_int8(vhi);
  for (int k = 0; k < 8; ++k) {
    lo[k] = ilo[k];
    hi[k] = ihi[k];
    wrap[k] = vwrap[k];
  }
}

// The discrete sums of every normal of the block, S_c(n) = sum L_c max(0, n.w) dOmega for R, G, B and
// W(n) (L = 1), written to out[0 .. count).
using Sums = std::array<double, channels>;
SHADELAB_INLINE void convolve_block_impl(const Lines& lines, const NormalBlock& b, Sums* out) {
  const auto p = static_cast<std::size_t>(b.padded);
  std::vector<f4> acc(4 * p, f4{});
  // Runs of up to two lines at a time: the accumulators are read and written once per two lines, and each
  // line's terms are added in line order, so the sums are the same as one line at a time, bit for bit.
  std::vector<int> lo(2 * p), hi(2 * p);
  std::vector<float> wrap(2 * p);
  for (int line = 0; line < lines.count; line += 2) {
    const int pair = std::min(2, lines.count - line);
    for (int j = 0; j < pair; ++j) {
      const auto o = static_cast<std::size_t>(j) * p;
      for (int i = 0; i < b.padded; i += 8) runs8(lines, b, line + j, i, lo.data() + o + i, hi.data() + o + i, wrap.data() + o + i);
    }
    // Line l's term of normal i for channel offset c (0, 3, 6, 9): n . (P[hi] - P[lo] + wrap total). Lane 3
    // of each load reads the next channel's (or the next entry's) x; n's lane 3 is 0, so it adds nothing.
    // Each channel is its own sum in the same order: for a constant L, S_c = L W step by step.
    const auto term = [&](int l, std::size_t o, std::size_t i, const f4& n, int c) SHADELAB_INLINE_LAMBDA {
      const float* e0 = lines.entry(l, lo[o + i]) + c;
      const float* e1 = lines.entry(l, hi[o + i]) + c;
      return n * (load4(e1) - load4(e0) + wrap[o + i] * load4(lines.entry(l, lines.length) + c));
    };
    for (std::size_t i = 0; i < static_cast<std::size_t>(b.count); ++i) {
      const f4 n = load4(b.n4.data() + 4 * i);
      f4 ar = acc[4 * i], ag = acc[4 * i + 1], ab = acc[4 * i + 2], aw = acc[4 * i + 3];
      for (int j = 0; j < pair; ++j) {
        const auto o = static_cast<std::size_t>(j) * p;
        ar += term(line + j, o, i, n, 0);
        ag += term(line + j, o, i, n, 3);
        ab += term(line + j, o, i, n, 6);
        aw += term(line + j, o, i, n, 9);
      }
      acc[4 * i] = ar;
      acc[4 * i + 1] = ag;
      acc[4 * i + 2] = ab;
      acc[4 * i + 3] = aw;
    }
  }
  for (std::size_t i = 0; i < static_cast<std::size_t>(b.count); ++i) {
    Sums e{};
    for (std::size_t c = 0; c < 4; ++c) {
      const f4 a = acc[4 * i + c];
      e[c] = static_cast<double>(a[0]) + static_cast<double>(a[1]) + static_cast<double>(a[2]);
      const std::size_t k = 3 * c;
      e[c] += static_cast<double>(b.n4[4 * i]) * lines.constant[k] + static_cast<double>(b.n4[4 * i + 1]) * lines.constant[k + 1] +
              static_cast<double>(b.n4[4 * i + 2]) * lines.constant[k + 2];
    }
    out[i] = e;
  }
}

SHADELAB_TARGET_AVX2 void convolve_block_avx2(const Lines& lines, const NormalBlock& b, Sums* out) {
  convolve_block_impl(lines, b, out);
}
void convolve_block_base(const Lines& lines, const NormalBlock& b, Sums* out) { convolve_block_impl(lines, b, out); }

// E(n) for every normal, in blocks run in parallel; progress between groups of blocks.
std::vector<Sums> convolve(const Lines& lines, const std::vector<Vec3>& normals, const ProgressFn& progress) {
  const int count = static_cast<int>(normals.size());
  std::vector<Sums> out(normals.size());
  // Large blocks: every block streams all lines once, so fewer blocks mean less memory traffic.
  const int block = std::clamp((count / 8 + 7) / 8 * 8, 512, 4096);
  const int blocks = (count + block - 1) / block;
  const int group = std::max(1, blocks / 20);
  const bool avx = cpu_has_avx2_fma();
  for (int start = 0; start < blocks; start += group) {
    const int end = std::min(blocks, start + group);
    tbb::parallel_for(tbb::blocked_range<int>(start, end, 1), [&](const tbb::blocked_range<int>& r) {
      for (int k = r.begin(); k != r.end(); ++k) {
        const int first = k * block;
        const int n = std::min(block, count - first);
        const NormalBlock b = make_block(normals.data() + first, n, lines.rings);
        if (avx) {
          convolve_block_avx2(lines, b, out.data() + first);
        } else {
          convolve_block_base(lines, b, out.data() + first);
        }
      }
    });
    if (progress) progress(static_cast<double>(end) / blocks);
  }
  return out;
}

// E(n) for every normal, using the antipodes: max(0, x) - max(0, -x) = x, so for the same emitters (every
// texel counts on exactly one side of n's horizon) E(-n) = E(n) - n.M with M = sum L dOmega d, the first
// moment of the whole map (per channel). Of each pair (n, -n) only the side with n.M_c <= 0 in every channel
// is convolved; the other is E(n) + |n.M_c|, a sum of non-negative terms, so it keeps E(n)'s relative
// rounding error (taking it the other way round, E(-n) = E(n) - n.M with n.M > 0, would cancel on the dark
// side). A pair whose channels disagree in sign is convolved on both sides. antipode[i] is the index of
// -normals[i], or -1.
std::vector<Sums> convolve_pairs(const Lines& lines, const std::vector<Vec3>& normals, const std::vector<int>& antipode,
                                const ProgressFn& progress) {
  double m[channels][3] = {};  // m[c] = M of channel c (x, y, z)
  for (std::size_t c = 0; c < static_cast<std::size_t>(channels); ++c)
    for (std::size_t k = 0; k < 3; ++k) m[c][k] = lines.first_moment[3 * c + k];
  const auto n_dot_m = [&](const Vec3& n, int c) { return n.x * m[c][0] + n.y * m[c][1] + n.z * m[c][2]; };
  const auto dark = [&](const Vec3& n) {
    return n_dot_m(n, 0) <= 0.0 && n_dot_m(n, 1) <= 0.0 && n_dot_m(n, 2) <= 0.0;
  };
  std::vector<int> from(normals.size(), -1);  // from[j] = i: E(j) derived from E(i)
  std::vector<Vec3> direct;
  std::vector<std::size_t> direct_index;
  direct.reserve(normals.size() / 2 + 16);
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const int j = antipode[i];
    if (j >= 0 && from[i] < 0) {
      const auto jj = static_cast<std::size_t>(j);
      if (from[jj] < 0 && jj > i) {
        if (dark(normals[i])) {
          from[jj] = static_cast<int>(i);
        } else if (dark(normals[jj])) {
          from[i] = j;
        }
      }
    }
  }
  for (std::size_t i = 0; i < normals.size(); ++i) {
    if (from[i] < 0) {
      direct.push_back(normals[i]);
      direct_index.push_back(i);
    }
  }
  const std::vector<Sums> e_direct = convolve(lines, direct, progress);
  std::vector<Sums> out(normals.size());
  for (std::size_t k = 0; k < direct.size(); ++k) out[direct_index[k]] = e_direct[k];
  for (std::size_t j = 0; j < normals.size(); ++j) {
    if (from[j] < 0) continue;
    const auto i = static_cast<std::size_t>(from[j]);
    // n_i.M_c <= 0 for R, G, B; W's M is the first moment of the texel layout, zero up to rounding (no
    // cancellation either way), and W takes the same path as the colours, so a constant keeps S = L W.
    for (int c = 0; c < channels; ++c) out[j][static_cast<std::size_t>(c)] = out[i][static_cast<std::size_t>(c)] - n_dot_m(normals[i], c);
  }
  return out;
}

// antipode[i] = index of the texel whose centre is -texel_direction(i), or -1 (faces are paired by the
// mirror symmetry of cube_direction; each pairing is checked against the directions).
std::vector<int> cube_antipodes(const std::vector<Vec3>& normals, int size) {
  std::vector<int> a(normals.size(), -1);
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const CubeCoord c = cube_coord(-normals[i]);
    const int x = std::clamp(static_cast<int>(c.s * size), 0, size - 1);
    const int y = std::clamp(static_cast<int>(c.t * size), 0, size - 1);
    const std::size_t j = (static_cast<std::size_t>(c.face) * static_cast<std::size_t>(size) + static_cast<std::size_t>(y)) *
                              static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
    if (j < normals.size() && dot(normals[j], normals[i]) < -1.0 + 1e-12) a[i] = static_cast<int>(j);
  }
  return a;
}

// The same for lat-long texel centres: (x, y) and (x + w/2 mod w, h - 1 - y) when w is even.
std::vector<int> latlong_antipodes(const std::vector<Vec3>& normals, int width, int height) {
  std::vector<int> a(normals.size(), -1);
  if (width % 2 != 0) return a;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      const std::size_t j = static_cast<std::size_t>(height - 1 - y) * static_cast<std::size_t>(width) +
                            static_cast<std::size_t>((x + width / 2) % width);
      if (dot(normals[j], normals[i]) < -1.0 + 1e-12) a[i] = static_cast<int>(j);
    }
  }
  return a;
}

std::vector<Vec3> cube_normals(int size) {
  std::vector<Vec3> n;
  n.reserve(static_cast<std::size_t>(6 * size * size));
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) n.push_back(texel_direction(f, x, y, size));
  return n;
}

std::vector<Vec3> latlong_normals(int width, int height) {
  std::vector<Vec3> n;
  n.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) n.push_back(latlong_direction((x + 0.5) / width, (y + 0.5) / height));
  return n;
}

// E(n) (radiometric) or E(n) / pi (game) from the discrete sums: pi S / W or S / W. S / W is one division,
// so a constant L, whose S(n) is L W(n), gives L exactly when L W(n) is exact (L a power of two such as 0.5:
// every step scales exactly) and to float rounding of the prefix entries otherwise.
Rgb normalise(const Sums& s, RadianceUnits units) {
  const double w = s[3];
  if (!(w > 0.0)) return Rgb{};  // no texel in n's hemisphere: S(n) = 0 too
  const Rgb e{s[0] / w, s[1] / w, s[2] / w};
  return units == RadianceUnits::game ? e : e * pi;
}

CubeMap to_cube(const std::vector<Sums>& s, int size, RadianceUnits units) {
  CubeMap out(size);
  std::size_t k = 0;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) out.set(f, x, y, normalise(s[k++], units));
  return out;
}

Image to_latlong(const std::vector<Sums>& s, int width, int height, RadianceUnits units) {
  Image out(width, height);
  std::size_t k = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) out.set(x, y, normalise(s[k++], units));
  return out;
}

Lines prepared_lines(const CubeMap& radiance, int max_size) {
  if (max_size <= 0 || radiance.size <= max_size) return cube_lines(radiance);
  CubeMap in = radiance;
  while (in.size > max_size && in.size % 2 == 0) in = downsample_cube(in);
  return cube_lines(in);
}

Lines prepared_lines(const Image& latlong, int max_size) {
  if (max_size <= 0 || latlong.width <= 4 * max_size) return ring_lines(latlong);
  Image in = latlong;
  while (in.width > 4 * max_size && in.width % 2 == 0 && in.height % 2 == 0) in = downsample_latlong(in);
  return ring_lines(in);
}

}  // namespace

CubeMap irradiance_cube(const CubeMap& radiance, int size, RadianceUnits units, const ConvolveOptions& options) {
  const Lines lines = prepared_lines(radiance, options.max_input_size);
  const std::vector<Vec3> normals = cube_normals(size);
  return to_cube(convolve_pairs(lines, normals, cube_antipodes(normals, size), options.progress), size, units);
}

CubeMap irradiance_cube(const Image& latlong, int size, RadianceUnits units, const ConvolveOptions& options) {
  const Lines lines = prepared_lines(latlong, options.max_input_size);
  const std::vector<Vec3> normals = cube_normals(size);
  return to_cube(convolve_pairs(lines, normals, cube_antipodes(normals, size), options.progress), size, units);
}

Image irradiance_latlong(const CubeMap& radiance, int width, RadianceUnits units, const ConvolveOptions& options) {
  const int height = std::max(1, width / 2);
  const Lines lines = prepared_lines(radiance, options.max_input_size);
  const std::vector<Vec3> normals = latlong_normals(width, height);
  return to_latlong(convolve_pairs(lines, normals, latlong_antipodes(normals, width, height), options.progress), width,
                    height, units);
}

Image irradiance_latlong(const Image& latlong, int width, RadianceUnits units, const ConvolveOptions& options) {
  const int height = std::max(1, width / 2);
  const Lines lines = prepared_lines(latlong, options.max_input_size);
  const std::vector<Vec3> normals = latlong_normals(width, height);
  return to_latlong(convolve_pairs(lines, normals, latlong_antipodes(normals, width, height), options.progress), width,
                    height, units);
}

}  // namespace shadelab
