#include "shadelab/envmap/base/cubemap.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/core/constants.h"

namespace shadelab {
namespace {

TEST(CubeMap, FaceCentresAreTheAxesInOpenGLOrder) {
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    const Vec3 d = cube_direction(f, 0.5, 0.5);
    EXPECT_NEAR(dot(d, axes[f]), 1.0, 1e-15) << cube_face_names[static_cast<std::size_t>(f)];
  }
}

TEST(CubeMap, OrientationFollowsTable819) {
  // +X: s grows toward -Z, t grows toward -Y. +Y: s toward +X, t toward +Z. -Z: s toward -X, t toward -Y.
  EXPECT_GT(cube_direction(0, 0.9, 0.5).z * -1, 0.0);
  EXPECT_LT(cube_direction(0, 0.5, 0.9).y, 0.0);
  EXPECT_GT(cube_direction(2, 0.9, 0.5).x, 0.0);
  EXPECT_GT(cube_direction(2, 0.5, 0.9).z, 0.0);
  EXPECT_LT(cube_direction(3, 0.5, 0.9).z, 0.0);
  EXPECT_LT(cube_direction(5, 0.9, 0.5).x, 0.0);
  EXPECT_LT(cube_direction(4, 0.5, 0.9).y, 0.0);
}

TEST(CubeMap, CoordinatesRoundTrip) {
  for (int f = 0; f < 6; ++f) {
    for (double s : {0.01, 0.3, 0.77, 0.99}) {
      for (double t : {0.02, 0.5, 0.93}) {
        const CubeCoord c = cube_coord(cube_direction(f, s, t));
        EXPECT_EQ(c.face, f);
        EXPECT_NEAR(c.s, s, 1e-14);
        EXPECT_NEAR(c.t, t, 1e-14);
      }
    }
  }
}

TEST(CubeMap, TexelSolidAnglesTotalFourPi) {
  for (int n : {1, 2, 7, 64, 512}) {
    double total = 0.0;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) total += cube_texel_solid_angle(x, y, n);
    EXPECT_NEAR(6.0 * total, 4.0 * pi, 1e-10) << n;
  }
  // One face of a 1 x 1 cube is a sixth of the sphere.
  EXPECT_NEAR(cube_texel_solid_angle(0, 0, 1), 4.0 * pi / 6.0, 1e-14);
}

TEST(CubeMap, TexelSolidAngleMatchesNumericIntegral) {
  // Integral of (1 + x^2 + y^2)^(-3/2) over the texel's face-plane square, midpoint rule.
  const int n = 16;
  for (auto [x, y] : {std::pair{0, 0}, std::pair{5, 11}, std::pair{8, 8}}) {
    const int sub = 800;
    const double h = 2.0 / n / sub;
    double sum = 0.0;
    for (int j = 0; j < sub; ++j) {
      for (int i = 0; i < sub; ++i) {
        const double px = -1.0 + 2.0 * x / n + (i + 0.5) * h;
        const double py = -1.0 + 2.0 * y / n + (j + 0.5) * h;
        sum += std::pow(1.0 + px * px + py * py, -1.5);
      }
    }
    EXPECT_NEAR(cube_texel_solid_angle(x, y, n), sum * h * h, 1e-9) << x << " " << y;
  }
}

TEST(CubeMap, TablesMatchTheDirectFunctions) {
  const int n = 9;
  const auto& t = CubeTexelTable::get(n);
  const auto& ft = cube_face_table(n);
  for (int f = 0; f < 6; ++f) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const auto i = static_cast<std::size_t>((f * n + y) * n + x);
        const Vec3 d = texel_direction(f, x, y, n);
        EXPECT_NEAR(dot(t.direction[i], d), 1.0, 1e-15);
        EXPECT_DOUBLE_EQ(t.solid_angle[i], cube_texel_solid_angle(x, y, n));
        const auto& e = ft[static_cast<std::size_t>(y * n + x)];
        EXPECT_NEAR(e.w, cube_texel_solid_angle(x, y, n), 1e-7);
      }
    }
  }
}

TEST(CubeMap, BilinearSampleOfConstantIsConstant) {
  CubeMap c(4);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) c.set(f, x, y, {0.5, 0.25, 2.0});
  const Rgb v = c.sample(normalize(Vec3{0.3, -0.8, 0.1}));
  EXPECT_NEAR(v.b, 2.0, 1e-7);
}

}  // namespace
}  // namespace shadelab
