// shadelab 3x3 matrices, for rotations of directions and spherical harmonics. Row-major m[row][col];
// apply() computes M v.
#pragma once

#include <array>
#include <cmath>

#include "shadelab/core/vec.h"

namespace shadelab {

struct Mat3 {
  std::array<std::array<double, 3>, 3> m{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

  static Mat3 identity() { return {}; }
  // Rotation by angle (radians) about a unit axis, right-handed (Rodrigues' formula).
  static Mat3 rotation(const Vec3& axis, double angle) {
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    const double t = 1.0 - c;
    const double x = axis.x, y = axis.y, z = axis.z;
    Mat3 r;
    r.m = {{{t * x * x + c, t * x * y - s * z, t * x * z + s * y},
            {t * x * y + s * z, t * y * y + c, t * y * z - s * x},
            {t * x * z - s * y, t * y * z + s * x, t * z * z + c}}};
    return r;
  }
  Vec3 apply(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Mat3 transposed() const {
    Mat3 t;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) t.m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = m[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)];
    return t;
  }
};

}  // namespace shadelab
