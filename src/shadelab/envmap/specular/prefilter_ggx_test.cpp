#include "shadelab/envmap/specular/prefilter_ggx.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/image/image_io.h"
#include "shadelab/envmap/base/cube_test_util.h"

namespace shadelab {
namespace {

using test_cubes::make_cube;

// The reference, written here independently of the library: every input texel with its exact solid angle and
// the GGX lobe D(h) max(R.l, 0), D = alpha^2 / (pi ((alpha^2 - 1) (R.h)^2 + 1)^2), h = (R + l)/|R + l|.
Rgb brute_force(const CubeMap& env, const Vec3& r, double roughness) {
  const double a2 = std::pow(roughness, 4.0);
  Rgb sum;
  double weight = 0.0;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < env.size; ++y)
      for (int x = 0; x < env.size; ++x) {
        const Vec3 l = texel_direction(f, x, y, env.size);
        const double rl = dot(r, l);
        if (rl <= 0.0) continue;
        const Vec3 sum_rl = r + l;
        const double c = dot(r, sum_rl) / std::sqrt(dot(sum_rl, sum_rl));
        const double d = (a2 - 1.0) * c * c + 1.0;
        const double w = a2 / (pi * d * d) * rl * cube_texel_solid_angle(x, y, env.size);
        sum += env.texel(f, x, y) * w;
        weight += w;
      }
  return sum / weight;
}

// A smooth analytic sky plus a deterministic per-texel pattern (a hash), so both low and high frequencies count.
CubeMap test_environment(int n) {
  CubeMap c = make_cube(n, [](const Vec3& d) {
    return Rgb{1.0 + 0.8 * d.z + 0.5 * d.x * d.y, 0.6 + 0.5 * std::max(0.0, d.y) + 0.3 * d.x, 1.2 - 0.4 * d.y * d.y};
  });
  std::uint32_t h = 12345u;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        h = h * 1664525u + 1013904223u;
        const double noise = 0.5 * static_cast<double>(h >> 8) / static_cast<double>(1u << 24);
        c.set(f, x, y, c.texel(f, x, y) * (0.75 + noise));
      }
  return c;
}

double rel(const Rgb& a, const Rgb& b) {
  return std::max({std::abs(a.r - b.r) / b.r, std::abs(a.g - b.g) / b.g, std::abs(a.b - b.b) / b.b});
}

TEST(PrefilterGgx, Mapping) {
  const GgxMipMapping lin{GgxRoughnessMapping::linear, 5};
  EXPECT_DOUBLE_EQ(lin.roughness(0), 0.0);
  EXPECT_DOUBLE_EQ(lin.roughness(2), 0.5);
  EXPECT_DOUBLE_EQ(lin.roughness(4), 1.0);
  EXPECT_DOUBLE_EQ(lin.lod(0.5), 2.0);
  EXPECT_EQ(lin.formula(), "lod = r * 4");
  const GgxMipMapping fil{GgxRoughnessMapping::filament, 6};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(fil.lod(fil.roughness(i)), i, 1e-12) << i;  // lod is the inverse
  EXPECT_NEAR(fil.lod(0.5), 5 * 0.75, 1e-12);
  EXPECT_STREQ(fil.name(), "filament");
  EXPECT_EQ(parse_ggx_roughness_mapping("filament"), GgxRoughnessMapping::filament);
  EXPECT_THROW(parse_ggx_roughness_mapping("cubic"), std::invalid_argument);
}

TEST(PrefilterGgx, ConstantStaysConstantAtEveryLevel) {
  // Both methods: sampled (64 samples) on a 16^2 input; sum on a 128^2 input, whose level 1 is near-far
  // (every texel of every level checked). Not powers of two, so that float rounding shows: measured 4.0e-8
  // (sampled) and 1.4e-7 (sum), both float rounding.
  for (const bool sampled : {true, false}) {
    const int size = sampled ? 16 : 128;
    const CubeMap env = make_cube(size, [](const Vec3&) { return Rgb{0.3, 0.7, 1.9}; });
    GgxPrefilterOptions o;
    o.method = sampled ? GgxFilterMethod::sampled : GgxFilterMethod::sum;
    o.samples = 64;
    const GgxPrefilteredCube p = prefilter_ggx(env, o);
    ASSERT_EQ(p.levels.size(), sampled ? 5u : 8u);
    if (!sampled) {
      EXPECT_EQ(p.method[1], GgxLevelMethod::near_far);
    }
    double worst = 0.0;
    for (std::size_t i = 0; i < p.levels.size(); ++i) {
      const CubeMap& level = p.levels[i];
      EXPECT_EQ(level.size, size >> i);
      for (int f = 0; f < 6; ++f)
        for (int y = 0; y < level.size; ++y)
          for (int x = 0; x < level.size; ++x) worst = std::max(worst, rel(level.texel(f, x, y), Rgb{0.3, 0.7, 1.9}));
    }
    std::printf("%s: worst relative deviation from the constant %.3g\n", sampled ? "sampled" : "sum", worst);
    EXPECT_LE(worst, sampled ? 1e-3 : 1e-6);
  }
}

TEST(PrefilterGgx, LevelZeroIsTheInputBitForBit) {
  const CubeMap env = test_environment(16);
  for (const GgxFilterMethod method : {GgxFilterMethod::sum, GgxFilterMethod::sampled}) {
    GgxPrefilterOptions o;
    o.levels = 3;
    o.method = method;
    o.samples = 16;
    const GgxPrefilteredCube p = prefilter_ggx(env, o);
    ASSERT_EQ(p.levels.size(), 3u);
    EXPECT_EQ(p.roughness[0], 0.0);
    EXPECT_EQ(p.method[0], GgxLevelMethod::input);
    for (int f = 0; f < 6; ++f) {
      const auto& a = p.levels[0].faces[static_cast<std::size_t>(f)].data;
      const auto& b = env.faces[static_cast<std::size_t>(f)].data;
      ASSERT_EQ(a.size(), b.size());
      EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "face " << f;
    }
  }
}

TEST(PrefilterGgx, LibraryBruteForceMatchesTheTestsOwn) {
  const CubeMap env = test_environment(8);
  for (const Vec3& r : {Vec3{0.3, -0.5, 0.8}, Vec3{1.0, 0.0, 0.0}, Vec3{-0.2, 0.9, -0.1}}) {
    const Vec3 u = normalize(r);
    EXPECT_LE(rel(prefilter_ggx_brute_force(env, u, 0.5), brute_force(env, u, 0.5)), 1e-12);
  }
}

TEST(PrefilterGgx, MidLevelAgainstBruteForce) {
  // r = 0.5 (level 2 of 5, face 8) of a 32^2-per-face environment, every texel.
  const CubeMap env = test_environment(32);
  GgxPrefilterOptions o;
  o.levels = 5;
  const GgxPrefilteredCube p = prefilter_ggx(env, o);
  ASSERT_DOUBLE_EQ(p.roughness[2], 0.5);
  const int n = 8;
  std::vector<Rgb> ref;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) ref.push_back(brute_force(env, texel_direction(f, x, y, n), 0.5));
  const auto errors = [&](const CubeMap& level, double& mean, double& worst) {
    mean = worst = 0.0;
    std::size_t k = 0;
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const double e = rel(level.texel(f, x, y), ref[k++]);
          worst = std::max(worst, e);
          mean += e / (6.0 * n * n);
        }
  };
  double mean = 0.0;
  double worst = 0.0;
  // With the default method (sum; n^2 N^2 = 8^2 32^2 <= 2^24) the level is the exact sum over the input:
  // the reference up to the float storage of the level (so it is with sampled's 1024 samples: 3 x 8^2 <= 1024).
  ASSERT_TRUE(p.exact[2]);
  errors(p.levels[2], mean, worst);
  std::printf("r = 0.5 on 32^2, default options (exact sum): mean relative error %.3g, max %.3g\n", mean, worst);
  EXPECT_LE(worst, 1e-6);
  // The filtered importance sampling alone (as on the fine levels of a large input), asserted at 1024
  // samples; the effect of the sample count and the lod bias printed for docs/envmap.md.
  for (const int samples : {256, 1024, 4096}) {
    for (const double bias : {0.0, 0.5, 1.0}) {
      const GgxFilter filter(env, samples, bias);
      const auto set = filter.make_samples(0.5);
      CubeMap level(n);
      for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x) level.set(f, x, y, filter.eval(texel_direction(f, x, y, n), set));
      errors(level, mean, worst);
      std::printf("  sampled, samples %d lod_bias %.1f: mean %.3g max %.3g\n", samples, bias, mean, worst);
      if (samples == 1024 && bias == 0.0) {
        EXPECT_LE(worst, 0.01);
      }
    }
  }
}

TEST(PrefilterGgx, CoarseLevelsAreSummedExactlyAndHoldASmallBrightSource) {
  // A 64^2 environment with a "sun" (one texel 2000 times the sky, 17 degrees from the +Y pole): with 512
  // samples (the game renderer's) the levels of face 8 and below (3 n^2 <= 512) are summed exactly, the
  // finer ones are sampled. Every texel of every exact level against the test's own brute force: equal up to
  // the float storage; sampling the same levels misses the sun by percents (printed, asserted to be above 1%
  // on the level of face 4, so the exact sum is what holds it).
  CubeMap env = test_environment(64);
  const Vec3 sun = normalize(Vec3{0.3, 1.0, 0.1});
  const CubeCoord c = cube_coord(sun);
  env.set(c.face, static_cast<int>(c.s * 64), static_cast<int>(c.t * 64), Rgb::gray(2000.0));
  GgxPrefilterOptions o;  // 7 levels, linear mapping
  o.method = GgxFilterMethod::sampled;
  o.samples = 512;
  const GgxPrefilteredCube p = prefilter_ggx(env, o);
  ASSERT_EQ(p.levels.size(), 7u);
  const std::vector<bool> want{false, false, false, true, true, true, true};
  EXPECT_EQ(p.exact, want);
  double worst_sampled_face4 = 0.0;
  double worst_exact_face4 = 0.0;
  for (int i = 3; i < 7; ++i) {
    const int n = p.levels[static_cast<std::size_t>(i)].size;
    const double r = p.roughness[static_cast<std::size_t>(i)];
    const GgxFilter filter(env, 512, 0.0);
    const auto set = filter.make_samples(r);
    double worst = 0.0;
    double worst_sampled = 0.0;
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const Vec3 d = texel_direction(f, x, y, n);
          const Rgb ref = brute_force(env, d, r);
          worst = std::max(worst, rel(p.levels[static_cast<std::size_t>(i)].texel(f, x, y), ref));
          worst_sampled = std::max(worst_sampled, rel(filter.eval(d, set), ref));
        }
    std::printf("level %d (face %d, r %.3f): exact sum max %.3g; sampled max %.3g\n", i, n, r, worst, worst_sampled);
    EXPECT_LE(worst, 1e-6) << "level " << i;
    if (n == 4) worst_sampled_face4 = worst_sampled, worst_exact_face4 = worst;
  }
  EXPECT_GT(worst_sampled_face4, 0.01);
  EXPECT_GT(worst_sampled_face4, 1000.0 * worst_exact_face4);
}

// A 128^2 environment for the near-far levels (faces 64 and 32 of the default sum; 16 and below exact): the
// test environment, a "sun" of 4 texels at 3000 times the sky and a bright 12 x 5 texel "softbox" (red),
// both placed across cell boundaries (cells of 4 x 4 texels).
CubeMap near_far_environment() {
  CubeMap env = test_environment(128);
  const CubeCoord c = cube_coord(normalize(Vec3{0.3, 1.0, 0.1}));
  const int sx = static_cast<int>(c.s * 128) / 4 * 4 + 3, sy = static_cast<int>(c.t * 128) / 4 * 4 + 3;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) env.set(c.face, sx + dx, sy + dy, Rgb::gray(3000.0));
  for (int y = 70; y < 75; ++y)
    for (int x = 30; x < 42; ++x) env.set(0, x, y, Rgb{60.0, 20.0, 15.0});
  return env;
}

// The worst and mean relative error (rel) of `level` against the brute force over a fixed set of texels: every
// `stride`-th texel of each face (offset by the face) and every texel within `radius` texels of a direction in
// `around`.
void near_far_errors(const CubeMap& env, const CubeMap& level, double r, int stride, const std::vector<Vec3>& around, int radius,
                     double& mean, double& worst) {
  const int n = level.size;
  mean = worst = 0.0;
  int count = 0;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        bool take = (y * n + x + 7 * f) % stride == 0;
        for (const Vec3& a : around) {
          const CubeCoord c = cube_coord(a);
          take = take || (c.face == f && std::abs(static_cast<int>(c.s * n) - x) <= radius && std::abs(static_cast<int>(c.t * n) - y) <= radius);
        }
        if (!take) continue;
        const double e = rel(level.texel(f, x, y), brute_force(env, texel_direction(f, x, y, n), r));
        worst = std::max(worst, e);
        mean += e;
        ++count;
      }
  mean /= count;
}

TEST(PrefilterGgx, NearFarLevelsAgainstBruteForce) {
  // The sum method on a 128^2 input: face 64 summed near and far (mid cells of 4 x 4 texels, coarse of 16 x 16;
  // the near field max(near_cells x 4 texels, 3 lobe widths), the mid field max(4 coarse cells, 8 lobe widths)),
  // 32 and below exactly (n^2 N^2 <= 2^24). Texels of face 64 against the test's own brute force: a fixed
  // spread of texels, and every texel around the sun, the softbox and the directions that mirror the sun
  // into other faces' texels. Measured: mean 8.0e-6, max 2.9e-5 (near_cells 8); mean 6.2e-4, max 7.6e-3
  // (near_cells 2); r = 0.5 (near field 3 lobe widths, 86 degrees): mean 1.1e-5, max 1.0e-4. The error falls
  // with the near field's radius (second order in cell size / angle, lobe_near_far.h): near_cells 2 is held
  // to a 10x looser bound and must be 10x worse. Cells read at their geometric centres instead of their
  // radiance centroids (a bright cell's flux moved by up to half a cell) fail the near_cells 8 bounds.
  const CubeMap env = near_far_environment();
  const Vec3 sun = normalize(Vec3{0.3, 1.0, 0.1});
  const std::vector<Vec3> around{sun, Vec3{1.0, -0.35, 0.22}, normalize(Vec3{-0.3, 1.0, 0.1}), normalize(Vec3{0.3, -1.0, -0.1})};
  // Runs: near_cells 8 and 2 on the default 8 levels (level 1: r = 1/7), near_cells 8 on 3 levels (level 1:
  // r = 0.5, a wide lobe whose far field does most of the sum).
  double means[3] = {}, worsts[3] = {};
  for (int k = 0; k < 3; ++k) {
    GgxPrefilterOptions o;
    o.levels = k == 2 ? 3 : 0;
    o.near_cells = k == 1 ? 2.0 : 8.0;
    const GgxPrefilteredCube p = prefilter_ggx(env, o);
    ASSERT_EQ(p.levels.size(), k == 2 ? 3u : 8u);
    EXPECT_EQ(p.method[0], GgxLevelMethod::input);
    EXPECT_EQ(p.method[1], GgxLevelMethod::near_far);
    for (std::size_t i = 2; i < p.levels.size(); ++i) EXPECT_EQ(p.method[i], GgxLevelMethod::exact) << "level " << i;
    EXPECT_EQ(p.far_block, 4);
    EXPECT_EQ(p.coarse_block, 16);
    const double width = 2.0 * p.roughness[1] * p.roughness[1];  // 2 alpha
    EXPECT_NEAR(p.near_angle[1], std::max(o.near_cells * 2.0 * 4.0 / 128.0, 3.0 * width), 1e-15);
    EXPECT_NEAR(p.mid_angle[1], std::max({4.0 * 2.0 * 16.0 / 128.0, 8.0 * width, p.near_angle[1] + 2.0 * 16.0 / 128.0}), 1e-15);
    near_far_errors(env, p.levels[1], p.roughness[1], 97, around, 2, means[k], worsts[k]);
    std::printf("near_cells %.0f, level 1 (face 64, r %.3f): mean %.3g max %.3g\n", o.near_cells, p.roughness[1], means[k], worsts[k]);
  }
  EXPECT_LE(worsts[0], 1e-4);
  EXPECT_LE(means[0], 1e-5);
  EXPECT_LE(worsts[1], 1e-2);
  EXPECT_LE(means[1], 1e-3);
  EXPECT_GT(worsts[1], 10.0 * worsts[0]);
  EXPECT_GT(means[1], 10.0 * means[0]);
  EXPECT_LE(worsts[2], 1e-3);
  EXPECT_LE(means[2], 3e-4);
}

TEST(PrefilterGgx, NearFieldOverTheWholeSphereIsTheExactSum) {
  // near_cells large enough that every cell is near: the near-far level is the exact sum (every 61st texel
  // checked; measured max 1.3e-7, float storage): the near rows read every input texel once.
  const CubeMap env = near_far_environment();
  GgxPrefilterOptions o;
  o.levels = 2;
  o.near_cells = 1000.0;
  const GgxPrefilteredCube p = prefilter_ggx(env, o);
  ASSERT_EQ(p.method[1], GgxLevelMethod::near_far);
  double mean = 0.0, worst = 0.0;
  near_far_errors(env, p.levels[1], p.roughness[1], 61, {}, 0, mean, worst);
  std::printf("whole-sphere near field: mean %.3g max %.3g\n", mean, worst);
  EXPECT_LE(worst, 2e-6);
}

TEST(PrefilterGgx, MirroredEstimatesAreTheEstimatesOfTheMirroredEnvironment) {
  // prefilter_ggx samples four mirror-image texels at once (GgxFilter::eval_mirrored): out[o] reads r's
  // sample set at the mirror images of r's taps. So out[o] on an environment must be eval(r) on that
  // environment's mirror image env_o(d) = env(M_o d), M_o the reflections of world axes axes[0] (o & 1) and
  // axes[1] (o & 2). env_o is built here from directions (texel_direction and cube_coord), not from the
  // library's face tables; an asymmetric environment with a bright texel on each face, a level whose
  // samples read two pyramid levels and cross face edges, texels of every face and both sides of each.
  const int n = 32;
  CubeMap env = test_environment(n);
  for (int f = 0; f < 6; ++f) env.set(f, 2 + 5 * f, 30 - 4 * f, Rgb{400.0, 30.0, 2.0});
  const int axis_of[6][2] = {{2, 1}, {2, 1}, {0, 2}, {0, 2}, {0, 1}, {0, 1}};  // world axes of each face's s and t
  auto mirrored = [&](int o, const int (&axes)[2]) {
    CubeMap m(n);
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          Vec3 d = texel_direction(f, x, y, n);
          double* c[3] = {&d.x, &d.y, &d.z};
          if (o & 1) *c[axes[0]] = -*c[axes[0]];
          if (o & 2) *c[axes[1]] = -*c[axes[1]];
          const CubeCoord q = cube_coord(d);
          m.set(f, x, y, env.texel(q.face, std::min(n - 1, static_cast<int>(q.s * n)), std::min(n - 1, static_cast<int>(q.t * n))));
        }
    return m;
  };
  const GgxFilter filter(env, 256, 0.0);
  const auto samples = filter.make_samples(0.35);
  double worst = 0.0;
  for (int f = 0; f < 6; ++f) {
    const int axes[2] = {axis_of[f][0], axis_of[f][1]};
    std::vector<GgxFilter> images;
    for (int o = 1; o < 4; ++o) images.emplace_back(mirrored(o, axes), 256, 0.0);
    for (const auto& [x, y] : {std::pair{0, 0}, std::pair{3, 9}, std::pair{7, 1}}) {
      const Vec3 r = texel_direction(f, x, y, 16);
      Rgb out[4];
      filter.eval_mirrored(r, samples, axes, out);
      const Rgb base = filter.eval(r, samples);
      EXPECT_EQ(std::memcmp(&out[0], &base, sizeof(Rgb)), 0) << "face " << f;  // out[0] is eval, bit for bit
      for (int o = 1; o < 4; ++o) {
        const Rgb want = images[static_cast<std::size_t>(o - 1)].eval(r, samples);
        worst = std::max(worst, rel(out[o], want));
        EXPECT_LE(rel(out[o], want), 1e-6) << "face " << f << " texel (" << x << ", " << y << ") image " << o;
      }
    }
  }
  std::printf("mirrored estimates against the mirrored environment's: max relative difference %.3g\n", worst);
}

TEST(PrefilterGgx, BrightTexelSpreadsSymmetricallyAcrossAnEdge) {
  // One bright texel on +X next to its edge with -Z (s = 1 on +X, sc = -rz = 1). Its response at directions
  // rotated by +-theta about the y axis (one into +X, one across the edge onto -Z) must be the same, as it is
  // for the brute force (the lobe depends only on the angle to the texel).
  const int n = 32;
  CubeMap env = make_cube(n, [](const Vec3&) { return Rgb::gray(0.01); });
  const int y = n / 2;
  env.set(0, n - 1, y, Rgb::gray(1000.0));
  const Vec3 d0 = texel_direction(0, n - 1, y, n);
  const GgxFilter filter(env, 1024, 0.0);
  const auto rotate = [](const Vec3& v, double a) {
    return Vec3{v.x * std::cos(a) + v.z * std::sin(a), v.y, -v.x * std::sin(a) + v.z * std::cos(a)};
  };
  // The difference of the two responses relative to the response at the texel itself (the peak), within the
  // lobe (theta up to 0.18 rad).
  double worst = 0.0;
  double worst_brute = 0.0;
  for (const double r : {0.25, 0.5}) {
    const auto samples = filter.make_samples(r);
    const double peak = filter.eval(d0, samples).g;
    const double peak_brute = brute_force(env, d0, r).g;
    for (int k = 1; k <= 6; ++k) {
      const double theta = k * 0.03;
      const Vec3 in = rotate(d0, -theta);  // toward +X's centre
      const Vec3 out = rotate(d0, theta);  // across the edge onto -Z
      ASSERT_EQ(cube_coord(in).face, 0);
      ASSERT_EQ(cube_coord(out).face, 5);
      const double a = filter.eval(in, samples).g;
      const double b = filter.eval(out, samples).g;
      std::printf("  r %.2f theta %.2f: +X %.4g -Z %.4g (brute %.4g %.4g)\n", r, theta, a, b, brute_force(env, in, r).g,
                  brute_force(env, out, r).g);
      // Asserted at r = 0.25; at r = 0.5 the filter's own error for a single hot texel (~15% of the peak,
      // against the brute force, on both sides alike) is printed and exceeds any seam effect.
      if (r == 0.25) worst = std::max(worst, std::abs(a - b) / peak);
      worst_brute = std::max(worst_brute, std::abs(brute_force(env, in, r).g - brute_force(env, out, r).g) / peak_brute);
    }
  }
  std::printf("edge asymmetry: filter %.3g, brute force %.3g\n", worst, worst_brute);
  EXPECT_LE(worst_brute, 0.01);  // the reference is symmetric to this
  EXPECT_LE(worst, 0.03);
}

TEST(PrefilterGgx, BadOptionsNameTheOption) {
  const CubeMap env = make_cube(16, [](const Vec3&) { return Rgb::gray(1.0); });
  const auto message = [](const CubeMap& cube, const GgxPrefilterOptions& options) {
    try {
      prefilter_ggx(cube, options);
    } catch (const std::invalid_argument& ex) {
      return std::string(ex.what());
    }
    return std::string("no exception");
  };
  GgxPrefilterOptions o;
  o.levels = 6;  // log2(16) + 1 = 5
  EXPECT_EQ(message(env, o).rfind("levels:", 0), 0u) << message(env, o);
  o.levels = -1;
  EXPECT_EQ(message(env, o).rfind("levels:", 0), 0u);
  o.levels = 5;
  EXPECT_EQ(message(env, o), "no exception");
  o.levels = 0;
  o.samples = 0;
  EXPECT_EQ(message(env, o).rfind("samples:", 0), 0u) << message(env, o);
  o.samples = 16;
  o.lod_bias = std::nan("");
  EXPECT_EQ(message(env, o).rfind("lod_bias:", 0), 0u);
  o.lod_bias = 1.0;
  o.near_cells = std::nan("");
  EXPECT_EQ(message(env, o).rfind("near_cells:", 0), 0u);
  o.near_cells = 12.0;
  o.coarse_cells = 0.0;
  EXPECT_EQ(message(env, o).rfind("coarse_cells:", 0), 0u);
  o.coarse_cells = 4.0;
  const CubeMap odd = make_cube(12, [](const Vec3&) { return Rgb::gray(1.0); });
  o.levels = 2;
  EXPECT_EQ(message(odd, o).rfind("size:", 0), 0u) << message(odd, o);
  o.levels = 1;
  EXPECT_EQ(message(odd, o), "no exception");  // no mips asked: any size
  EXPECT_EQ(message(CubeMap{}, o).rfind("radiance:", 0), 0u);
}

TEST(PrefilterGgx, SameBitsForAnyThreadCount) {
  // Both methods: sampled on a 16^2 input, sum on a 128^2 one (its level 1 near-far).
  for (const bool sampled : {true, false}) {
    const CubeMap env = sampled ? test_environment(16) : near_far_environment();
    GgxPrefilterOptions o;
    o.method = sampled ? GgxFilterMethod::sampled : GgxFilterMethod::sum;
    o.samples = 64;
    o.levels = sampled ? 0 : 2;
    const GgxPrefilteredCube a = prefilter_ggx(env, o);
    if (!sampled) {
      EXPECT_EQ(a.method[1], GgxLevelMethod::near_far);
    }
    GgxPrefilteredCube b;
    {
      tbb::task_arena one(1);
      one.execute([&] { b = prefilter_ggx(env, o); });
    }
    for (std::size_t i = 0; i < a.levels.size(); ++i)
      for (int f = 0; f < 6; ++f)
        EXPECT_EQ(a.levels[i].faces[static_cast<std::size_t>(f)].data, b.levels[i].faces[static_cast<std::size_t>(f)].data);
  }
}

TEST(PrefilterGgx, BlenderWorldAgainstBruteForce) {
  // The measured error of the default bake on a real HDRI (blender-data's courtyard, CC0), 32^2 per face.
  const std::filesystem::path dir = SHADELAB_BLENDER_WORLDS;
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir << " is missing: scripts/setup.sh installs blender-data";
  const auto img = read_image(dir / "courtyard.exr");
  ASSERT_TRUE(img.has_value()) << img.error().message;
  const CubeMap env = latlong_to_cube(*img, 32, 2);
  const auto t0 = std::chrono::steady_clock::now();
  const GgxPrefilteredCube p = prefilter_ggx(env, GgxPrefilterOptions{});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("courtyard 32^2, %zu levels, %d samples: %.3f s\n", p.levels.size(), p.samples, seconds);
  for (std::size_t i = 1; i < p.levels.size(); ++i) {
    const CubeMap& level = p.levels[i];
    double worst = 0.0;
    double mean = 0.0;
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < level.size; ++y)
        for (int x = 0; x < level.size; ++x) {
          const Rgb ref = brute_force(env, texel_direction(f, x, y, level.size), p.roughness[i]);
          const double e = std::abs(level.texel(f, x, y).average() - ref.average()) / ref.average();
          worst = std::max(worst, e);
          mean += e / (6.0 * level.size * level.size);
        }
    std::printf("  level %zu r = %.2f: mean %.4f max %.4f\n", i, p.roughness[i], mean, worst);
    EXPECT_LE(mean, 0.08) << "level " << i;  // regression bounds above the figures measured in docs/envmap.md
    EXPECT_LE(worst, 0.5) << "level " << i;
  }
}

TEST(PrefilterGgx, NearFarOnSunriseAgainstBruteForce) {
  // The default method on a real HDRI with a sun (blender-data's sunrise, CC0) at 128^2 per face: level 1
  // (face 64, r = 1/7) is near-far. Against the brute force at every 241st texel and every texel within 2 of
  // the sun's direction.
  const std::filesystem::path dir = SHADELAB_BLENDER_WORLDS;
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir << " is missing: scripts/setup.sh installs blender-data";
  const auto img = read_image(dir / "sunrise.exr");
  ASSERT_TRUE(img.has_value()) << img.error().message;
  const CubeMap env = latlong_to_cube(*img, 128, 2);
  Vec3 sun;
  double brightest = 0.0;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x)
        if (env.texel(f, x, y).average() > brightest) {
          brightest = env.texel(f, x, y).average();
          sun = texel_direction(f, x, y, 128);
        }
  GgxPrefilterOptions o;
  o.levels = 0;
  const GgxPrefilteredCube p = prefilter_ggx(env, o);
  ASSERT_EQ(p.method[1], GgxLevelMethod::near_far);
  double mean = 0.0, worst = 0.0;
  near_far_errors(env, p.levels[1], p.roughness[1], 241, {sun}, 2, mean, worst);
  std::printf("sunrise 128^2, level 1 (r %.3f), sun %.0f: mean %.3g max %.3g\n", p.roughness[1], brightest, mean, worst);
  EXPECT_LE(mean, 2e-4);  // measured 8.9e-5 and 6.7e-4 (a sun texel at 17089)
  EXPECT_LE(worst, 2e-3);
}

}  // namespace
}  // namespace shadelab
