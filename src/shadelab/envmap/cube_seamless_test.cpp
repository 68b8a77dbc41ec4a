// The split sum's per-pixel reads are kernel text now (kernels/cube.sl, kernels/game_ibl.sl), run by the C++
// through the texel fetches of kernels.h: sample_cube_seamless, sample_ggx_chain and dfg_lookup call them.
// Oracles:
// - the C++ these kernels replaced (2026-12-07), kept here as the reference: the kernels give its values bit for
//   bit on random cubes of sizes 1 to 17 and directions drawn near faces' edges and corners as well as anywhere,
//   and on a GGX chain of both mip mappings and a DFG table at random (N.V, r);
// - the seamless read is continuous across each of the 12 edges (the per-face bilinear CubeMap::sample is not:
//   the test's own negative control), reads a constant cube as the constant, and reads each texel centre as the
//   texel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/envmap/specular/prefilter_ggx.h"
#include "shadelab/envmap/specular/split_sum_lobes.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

// ---- The C++ before 2026-12-07 (envmap/base/cubemap.h, prefilter_ggx.cpp, dfg.cpp), the reference. ----
CubeCoord old_cube_coord(const Vec3& r) {
  const double ax = std::abs(r.x), ay = std::abs(r.y), az = std::abs(r.z);
  CubeCoord c;
  double sc = 0.0, tc = 0.0, ma = 0.0;
  if (ax >= ay && ax >= az) {
    ma = ax;
    if (r.x >= 0.0) { c.face = 0; sc = -r.z; tc = -r.y; } else { c.face = 1; sc = r.z; tc = -r.y; }
  } else if (ay >= az) {
    ma = ay;
    if (r.y >= 0.0) { c.face = 2; sc = r.x; tc = r.z; } else { c.face = 3; sc = r.x; tc = -r.z; }
  } else {
    ma = az;
    if (r.z >= 0.0) { c.face = 4; sc = r.x; tc = -r.y; } else { c.face = 5; sc = -r.x; tc = -r.y; }
  }
  c.s = 0.5 * (sc / ma + 1.0);
  c.t = 0.5 * (tc / ma + 1.0);
  return c;
}

Vec3 old_cube_direction(int face, double s, double t) {
  const double sc = 2.0 * s - 1.0, tc = 2.0 * t - 1.0;
  Vec3 r;
  switch (face) {
    case 0: r = {1.0, -tc, -sc}; break;
    case 1: r = {-1.0, -tc, sc}; break;
    case 2: r = {sc, 1.0, tc}; break;
    case 3: r = {sc, -1.0, -tc}; break;
    case 4: r = {sc, -tc, 1.0}; break;
    default: r = {-sc, -tc, -1.0}; break;
  }
  return normalize(r);
}

Rgb old_texel_across_edges(const CubeMap& c, int face, int x, int y) {
  const int n = c.size;
  const bool x_in = x >= 0 && x < n, y_in = y >= 0 && y < n;
  if (x_in && y_in) return c.texel(face, x, y);
  const auto neighbour = [&](int xx, int yy) {
    const CubeCoord q = old_cube_coord(old_cube_direction(face, (xx + 0.5) / n, (yy + 0.5) / n));
    return c.texel(q.face, std::clamp(static_cast<int>(q.s * n), 0, n - 1), std::clamp(static_cast<int>(q.t * n), 0, n - 1));
  };
  if (x_in || y_in) return neighbour(x, y);
  const int cx = std::clamp(x, 0, n - 1), cy = std::clamp(y, 0, n - 1);
  return (c.texel(face, cx, cy) + neighbour(x, cy) + neighbour(cx, y)) / 3.0;
}

Rgb old_sample_cube_seamless(const CubeMap& cube, const Vec3& dir) {
  const CubeCoord c = old_cube_coord(dir);
  const int n = cube.size;
  const double fx = c.s * n - 0.5, fy = c.t * n - 0.5;
  const int x0 = std::clamp(static_cast<int>(std::floor(fx)), -1, n - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor(fy)), -1, n - 1);
  const double ax = std::clamp(fx - x0, 0.0, 1.0), ay = std::clamp(fy - y0, 0.0, 1.0);
  const auto t = [&](int x, int y) { return old_texel_across_edges(cube, c.face, x, y); };
  return (t(x0, y0) * (1 - ax) + t(x0 + 1, y0) * ax) * (1 - ay) + (t(x0, y0 + 1) * (1 - ax) + t(x0 + 1, y0 + 1) * ax) * ay;
}

Rgb old_sample_ggx_chain(const GgxPrefilteredCube& chain, const Vec3& dir, double roughness) {
  const auto levels = static_cast<int>(chain.levels.size());
  const double lod = std::clamp(chain.mapping.lod(std::clamp(roughness, 0.0, 1.0)), 0.0, levels - 1.0);
  const int l0 = std::min(static_cast<int>(lod), levels - 1), l1 = std::min(l0 + 1, levels - 1);
  const double t = lod - l0;
  const Rgb v0 = old_sample_cube_seamless(chain.levels[static_cast<std::size_t>(l0)], dir);
  if (t <= 0.0 || l1 == l0) return v0;
  return v0 * (1.0 - t) + old_sample_cube_seamless(chain.levels[static_cast<std::size_t>(l1)], dir) * t;
}

// The two texels around x in a table of n texel centres (i + 1/2)/n and the weight of the second, clamped.
struct OldLerp {
  int i0, i1;
  double t;
};
OldLerp old_texel_lerp(double x, int n) {
  const double p = std::clamp(x * n - 0.5, 0.0, static_cast<double>(n - 1));
  const int i0 = std::min(static_cast<int>(p), n - 1);
  return {i0, std::min(i0 + 1, n - 1), p - i0};
}

DfgAb old_dfg_lookup(const DfgTable& table, double mu, double roughness) {
  const int n = table.size;
  const OldLerp lx = old_texel_lerp(mu, n), ly = old_texel_lerp(roughness, n);
  const int x0 = lx.i0, x1 = lx.i1, y0 = ly.i0, y1 = ly.i1;
  const double tx = lx.t, ty = ly.t;
  const auto at = [&](int c) {
    return (table.at(x0, y0, c) * (1.0 - tx) + table.at(x1, y0, c) * tx) * (1.0 - ty) +
           (table.at(x0, y1, c) * (1.0 - tx) + table.at(x1, y1, c) * tx) * ty;
  };
  return {at(0), at(1)};
}
SplitSumLobes old_split_sum_lobes(const SplitSumLobeTable& table, double mu, double roughness) {
  const int n = table.size();
  const OldLerp lx = old_texel_lerp(mu, n), ly = old_texel_lerp(roughness, n);
  const int x0 = lx.i0, x1 = lx.i1, y0 = ly.i0, y1 = ly.i1;
  const double tx = lx.t, ty = ly.t;
  const auto lerp2 = [&](auto get) {
    const double lo = get(table.at(x0, y0)) * (1.0 - tx) + get(table.at(x1, y0)) * tx;
    const double hi = get(table.at(x0, y1)) * (1.0 - tx) + get(table.at(x1, y1)) * tx;
    return lo * (1.0 - ty) + hi * ty;
  };
  SplitSumLobes out;
  out.a.angle = lerp2([](const SplitSumLobes& s) { return s.a.angle; });
  out.a.roughness = lerp2([](const SplitSumLobes& s) { return s.a.roughness; });
  out.b.angle = lerp2([](const SplitSumLobes& s) { return s.b.angle; });
  out.b.roughness = lerp2([](const SplitSumLobes& s) { return s.b.roughness; });
  const double r0 = 0.5 / n;
  if (roughness < r0) {
    const double w = std::max(roughness, 0.0) / r0;
    const double mirror_angle = std::acos(std::clamp(mu, 0.0, 1.0));
    for (SplitSumLobe* p : {&out.a, &out.b}) {
      p->angle = mirror_angle + (p->angle - mirror_angle) * w;
      p->roughness *= w;
    }
  }
  return out;
}
// ---- end of the reference ----

CubeMap random_cube(int n, Pcg32& rng) {
  CubeMap c(n);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) c.set(f, x, y, {rng.next_double(), 4.0 * rng.next_double(), rng.next_double() * rng.next_double()});
  return c;
}

// Directions anywhere, and near edges and corners (two or three components of nearly equal size).
Vec3 random_direction(Pcg32& rng, int kind) {
  const auto u = [&] { return 2.0 * rng.next_double() - 1.0; };
  const auto sign = [&] { return rng.next_double() < 0.5 ? -1.0 : 1.0; };
  const double e = 1e-3 * u();
  if (kind == 1) return {sign(), sign() * (1.0 + e), u()};       // the X/Y edges
  if (kind == 2) return {u(), sign(), sign() * (1.0 + e)};       // the Y/Z edges
  if (kind == 3) return {sign() * (1.0 + e), sign(), sign()};    // the corners
  return {u(), u(), u()};
}

void expect_same(const Rgb& a, const Rgb& b, const char* what, int n) {
  EXPECT_EQ(a.r, b.r) << what << " size " << n;
  EXPECT_EQ(a.g, b.g) << what << " size " << n;
  EXPECT_EQ(a.b, b.b) << what << " size " << n;
}

TEST(CubeSeamless, TheKernelsAreTheReadsTheyReplacedBitForBit) {
  Pcg32 rng(7, 11);
  for (const int n : {1, 2, 3, 4, 5, 8, 16, 17}) {
    const CubeMap cube = random_cube(n, rng);
    for (int i = 0; i < 800; ++i) {
      Vec3 d = random_direction(rng, i % 4);
      if (dot(d, d) < 1e-12) continue;
      const CubeCoord k = cube_coord(d), o = old_cube_coord(d);
      ASSERT_EQ(k.face, o.face);
      ASSERT_EQ(k.s, o.s);
      ASSERT_EQ(k.t, o.t);
      expect_same(sample_cube_seamless(cube, d), old_sample_cube_seamless(cube, d), "seamless", n);
    }
    for (int f = 0; f < 6; ++f) {
      const double s = rng.next_double(), t = rng.next_double();
      const Vec3 a = cube_direction(f, s, t), b = old_cube_direction(f, s, t);
      EXPECT_EQ(a.x, b.x);
      EXPECT_EQ(a.y, b.y);
      EXPECT_EQ(a.z, b.z);
    }
  }
  // A chain of random levels (16 down to 1) under both mip mappings, read at random roughness.
  for (const GgxRoughnessMapping mapping : {GgxRoughnessMapping::linear, GgxRoughnessMapping::filament}) {
    GgxPrefilteredCube chain;
    for (int n = 16; n >= 1; n /= 2) chain.levels.push_back(random_cube(n, rng));
    chain.mapping.kind = mapping;
    chain.mapping.levels = static_cast<int>(chain.levels.size());
    for (int i = 0; i < 400; ++i) {
      const Vec3 d = random_direction(rng, i % 4);
      const double r = i == 0 ? 0.0 : (i == 1 ? 1.0 : rng.next_double());
      expect_same(sample_ggx_chain(chain, d, r), old_sample_ggx_chain(chain, d, r), "chain", 16);
    }
  }
  // A DFG table of random texels, read at random (N.V, r) and at and beyond its edges.
  DfgTable table;
  table.size = 7;
  for (int i = 0; i < 7 * 7 * 3; ++i) table.texels.push_back(rng.next_double());
  for (int i = 0; i < 400; ++i) {
    const double mu = 1.2 * rng.next_double() - 0.1, r = 1.2 * rng.next_double() - 0.1;
    const DfgAb k = dfg_lookup(table, mu, r), o = old_dfg_lookup(table, mu, r);
    EXPECT_EQ(k.a, o.a) << mu << " " << r;
    EXPECT_EQ(k.b, o.b) << mu << " " << r;
  }
}

TEST(CubeSeamless, TheLobeTableReadIsTheReadItReplacedBitForBit) {
  // A 5 x 5 lobe table (rows computed at first read, as the renderer's 32 x 32 one), read at random (N.V, r),
  // below its first row's centre (toward the mirror) and beyond its edges.
  const SplitSumLobeTable table(5);
  Pcg32 rng(9, 4);
  for (int i = 0; i < 300; ++i) {
    const double mu = 1.2 * rng.next_double() - 0.1;
    const double r = i % 3 == 0 ? 0.1 * rng.next_double() : 1.2 * rng.next_double() - 0.1;
    const SplitSumLobes k = split_sum_lobes(table, mu, r), o = old_split_sum_lobes(table, mu, r);
    EXPECT_EQ(k.a.angle, o.a.angle) << mu << " " << r;
    EXPECT_EQ(k.a.roughness, o.a.roughness) << mu << " " << r;
    EXPECT_EQ(k.b.angle, o.b.angle) << mu << " " << r;
    EXPECT_EQ(k.b.roughness, o.b.roughness) << mu << " " << r;
  }
}

TEST(CubeSeamless, ContinuousAcrossEveryEdgeWhereThePerFaceReadIsNot) {
  Pcg32 rng(3, 5);
  const int n = 8;
  const CubeMap cube = random_cube(n, rng);
  double worst_seamless = 0.0, worst_per_face = 0.0;
  // Each of the 12 edges: the points where two coordinates have magnitude 1 on the unit cube.
  for (int axis_a = 0; axis_a < 3; ++axis_a)
    for (int axis_b = axis_a + 1; axis_b < 3; ++axis_b)
      for (const double sa : {-1.0, 1.0})
        for (const double sb : {-1.0, 1.0})
          for (int k = 0; k < 20; ++k) {
            const int free = 3 - axis_a - axis_b;
            double p[3];
            p[free] = 1.6 * rng.next_double() - 0.8;  // away from the corners' half texel (n = 8: |p| > 0.875)
            const double eps = 1e-9;
            p[axis_a] = sa;
            p[axis_b] = sb * (1.0 - eps);  // on face axis_a's side
            const Vec3 one{p[0], p[1], p[2]};
            p[axis_a] = sa * (1.0 - eps);
            p[axis_b] = sb;  // on face axis_b's side
            const Vec3 two{p[0], p[1], p[2]};
            ASSERT_NE(cube_coord(one).face, cube_coord(two).face);
            const Rgb a = sample_cube_seamless(cube, one), b = sample_cube_seamless(cube, two);
            worst_seamless = std::max({worst_seamless, std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
            const Rgb c = cube.sample(one), d = cube.sample(two);
            worst_per_face = std::max({worst_per_face, std::abs(c.r - d.r), std::abs(c.g - d.g), std::abs(c.b - d.b)});
          }
  std::printf("largest jump across an edge: seamless %.3g, per-face bilinear %.3g\n", worst_seamless, worst_per_face);
  EXPECT_LE(worst_seamless, 1e-6);
  EXPECT_GE(worst_per_face, 0.1);  // texels of random values in [0, 4]: the per-face read jumps
}

TEST(CubeSeamless, AConstantReadsAsTheConstantAndACentreAsItsTexel) {
  Pcg32 rng(1, 2);
  for (const int n : {1, 3, 8}) {
    CubeMap constant(n);
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) constant.set(f, x, y, {0.5, 0.25, 2.0});
    const CubeMap cube = random_cube(n, rng);
    for (int i = 0; i < 200; ++i) {
      const Vec3 d = random_direction(rng, i % 4);
      const Rgb c = sample_cube_seamless(constant, d);
      EXPECT_NEAR(c.r, 0.5, 1e-15);
      EXPECT_NEAR(c.b, 2.0, 1e-15);
    }
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const Rgb want = cube.texel(f, x, y), got = sample_cube_seamless(cube, texel_direction(f, x, y, n));
          EXPECT_NEAR(got.g, want.g, 1e-12 * (1.0 + want.g)) << f << " " << x << " " << y;
        }
  }
}

}  // namespace
}  // namespace shadelab
