// Tests of core/vec.h and core/frame.h: vector algebra, reflection, and orthonormal frames about any normal
// (including the neighbourhood of -Z, where the classic Frisvad construction breaks down).
#include "shadelab/core/vec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"

namespace shadelab {
namespace {

void expect_vec_near(const Vec3& a, const Vec3& b, double tol, const char* what = "") {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

// Unit normals: a Fibonacci sphere (golden-angle spiral, even coverage), the axes, and normals within
// 1e-3 ... 1e-15 of -Z and +Z, the hard cases for tangent construction.
std::vector<Vec3> test_normals() {
  std::vector<Vec3> normals;
  constexpr int count = 2000;
  const double golden_angle = pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count;
    const double r = std::sqrt(1.0 - z * z);
    normals.push_back({r * std::cos(golden_angle * i), r * std::sin(golden_angle * i), z});
  }
  // The last one has z = -0.0, for which copysign picks the -Z branch.
  for (const Vec3& axis : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0}, Vec3{0, 0, 1},
                           Vec3{0, 0, -1}, Vec3{1, 0, -0.0}}) {
    normals.push_back(axis);
  }
  for (double eps : {1e-3, 1e-5, 1e-8, 1e-10, 1e-12, 1e-15}) {
    for (double sign : {-1.0, 1.0}) {
      normals.push_back(normalize(Vec3{eps, 0.0, sign}));
      normals.push_back(normalize(Vec3{0.0, -eps, sign}));
      normals.push_back(normalize(Vec3{eps, eps, sign}));
      normals.push_back(normalize(Vec3{-eps, 0.5 * eps, sign}));
    }
  }
  return normals;
}

TEST(Vec, Arithmetic) {
  const Vec3 a{1.0, 2.0, 3.0};
  const Vec3 b{-4.0, 0.5, 2.0};
  expect_vec_near(a + b, {-3.0, 2.5, 5.0}, 0.0);
  expect_vec_near(a - b, {5.0, 1.5, 1.0}, 0.0);
  expect_vec_near(-a, {-1.0, -2.0, -3.0}, 0.0);
  expect_vec_near(a * 2.0, {2.0, 4.0, 6.0}, 0.0);
  expect_vec_near(2.0 * a, {2.0, 4.0, 6.0}, 0.0);
  expect_vec_near(a / 2.0, {0.5, 1.0, 1.5}, 0.0);
  Vec3 c = a;
  c += b;
  expect_vec_near(c, a + b, 0.0);
  EXPECT_EQ(dot(a, b), -4.0 + 1.0 + 6.0);
  EXPECT_EQ(a[0], 1.0);
  EXPECT_EQ(a[1], 2.0);
  EXPECT_EQ(a[2], 3.0);
  EXPECT_DOUBLE_EQ(length(Vec3{3.0, 4.0, 12.0}), 13.0);
  EXPECT_NEAR(length(normalize(b)), 1.0, 1e-15);
  EXPECT_TRUE(is_finite(a));
  EXPECT_FALSE(is_finite(Vec3{0.0, std::nan(""), 0.0}));
  EXPECT_FALSE(is_finite(Vec3{0.0, 0.0, HUGE_VAL}));
}

TEST(Vec, CrossIsRightHanded) {
  expect_vec_near(cross({1, 0, 0}, {0, 1, 0}), {0, 0, 1}, 0.0);
  expect_vec_near(cross({0, 1, 0}, {0, 0, 1}), {1, 0, 0}, 0.0);
  expect_vec_near(cross({0, 0, 1}, {1, 0, 0}), {0, 1, 0}, 0.0);
  const Vec3 a{0.3, -1.2, 2.0};
  const Vec3 b{1.5, 0.4, -0.7};
  const Vec3 c = cross(a, b);
  EXPECT_NEAR(dot(c, a), 0.0, 1e-14);
  EXPECT_NEAR(dot(c, b), 0.0, 1e-14);
  expect_vec_near(cross(b, a), -c, 1e-15);
  // |a x b|^2 = |a|^2 |b|^2 - (a.b)^2 (Lagrange's identity).
  EXPECT_NEAR(dot(c, c), dot(a, a) * dot(b, b) - dot(a, b) * dot(a, b), 1e-13);
}

TEST(Vec, SphericalDirectionAndLocalTrigonometry) {
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j < 12; ++j) {
      const double theta = pi * i / 10.0;
      const double phi = two_pi * j / 12.0;
      const Vec3 w = spherical_direction(std::sin(theta), std::cos(theta), phi);
      EXPECT_NEAR(length(w), 1.0, 1e-15);
      EXPECT_NEAR(cos_theta(w), std::cos(theta), 1e-15);
      EXPECT_NEAR(w.x, std::sin(theta) * std::cos(phi), 1e-15);
      EXPECT_NEAR(w.y, std::sin(theta) * std::sin(phi), 1e-15);
    }
  }
  EXPECT_TRUE(same_hemisphere({0, 0, 1}, {0.5, 0.5, 0.1}));
  EXPECT_TRUE(same_hemisphere({0, 0, -1}, {0.5, 0.5, -0.1}));
  EXPECT_FALSE(same_hemisphere({0, 0, 1}, {0.5, 0.5, -0.1}));
  EXPECT_FALSE(same_hemisphere({0, 0, 1}, {1, 0, 0}));  // the horizon belongs to neither
}

TEST(Vec, Reflect) {
  const Vec3 n{0.0, 0.0, 1.0};
  const double s = std::sqrt(0.5);
  expect_vec_near(reflect({s, 0.0, s}, n), {-s, 0.0, s}, 1e-15);
  expect_vec_near(reflect(n, n), n, 0.0);
  for (const Vec3& axis : test_normals()) {
    const Vec3 w = normalize(Vec3{0.3, -0.5, 0.8});
    const Vec3 r = reflect(w, axis);
    EXPECT_NEAR(length(r), 1.0, 1e-13);                  // lengths are kept
    EXPECT_NEAR(dot(r, axis), dot(w, axis), 1e-13);      // same angle to the axis
    const Vec3 sum_cross = cross(r + w, axis);           // r + w lies along the axis
    EXPECT_NEAR(length(sum_cross), 0.0, 1e-13);
    expect_vec_near(reflect(r, axis), w, 1e-13, "reflecting twice is the identity");
  }
}

TEST(Frame, FromNormalIsOrthonormalAndRightHanded) {
  for (const Vec3& n : test_normals()) {
    const Frame f = Frame::from_normal(n);
    EXPECT_TRUE(is_finite(f.s) && is_finite(f.t)) << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(length(f.s), 1.0, 1e-12) << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(length(f.t), 1.0, 1e-12) << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(dot(f.s, f.t), 0.0, 1e-12) << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(dot(f.s, f.n), 0.0, 1e-12) << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(dot(f.t, f.n), 0.0, 1e-12) << n.x << " " << n.y << " " << n.z;
    expect_vec_near(f.n, n, 0.0, "the frame keeps the normal");
    expect_vec_near(cross(f.s, f.t), n, 1e-12, "s x t = n");
  }
  // The default frame is the identity.
  const Frame identity;
  expect_vec_near(identity.to_local({0.1, 0.2, 0.3}), {0.1, 0.2, 0.3}, 0.0);
}

TEST(Frame, ToLocalAndToWorldAreInverse) {
  const Vec3 vectors[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.3, -0.4, 0.5}, {-2.0, 1.0, 7.0}};
  for (const Vec3& n : test_normals()) {
    const Frame f = Frame::from_normal(n);
    expect_vec_near(f.to_local(n), {0.0, 0.0, 1.0}, 1e-12, "the normal is +Z locally");
    expect_vec_near(f.to_world({0.0, 0.0, 1.0}), n, 1e-12, "+Z is the normal in the world");
    for (const Vec3& v : vectors) {
      const double scale = length(v);
      expect_vec_near(f.to_world(f.to_local(v)), v, 1e-12 * scale, "world -> local -> world");
      expect_vec_near(f.to_local(f.to_world(v)), v, 1e-12 * scale, "local -> world -> local");
      EXPECT_NEAR(length(f.to_local(v)), scale, 1e-12 * scale);  // a rotation keeps lengths
    }
  }
}

}  // namespace
}  // namespace shadelab
