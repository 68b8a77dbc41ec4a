// shadelab orthonormal frames: the local shading frame (normal = +Z) and frames about any axis.
#pragma once

#include <cmath>

#include "shadelab/core/vec.h"

namespace shadelab {

// An orthonormal basis (s, t, n). to_local maps world to local coordinates, where n is +Z.
struct Frame {
  Vec3 s{1.0, 0.0, 0.0};
  Vec3 t{0.0, 1.0, 0.0};
  Vec3 n{0.0, 0.0, 1.0};

  // A frame whose +Z is the unit vector n; the tangent is chosen without branches on the sign of n.z
  // (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
  static Frame from_normal(const Vec3& n) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    Frame f;
    f.s = {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    f.t = {b, sign + n.y * n.y * a, -n.y};
    f.n = n;
    return f;
  }

  Vec3 to_local(const Vec3& w) const { return {dot(w, s), dot(w, t), dot(w, n)}; }
  Vec3 to_world(const Vec3& w) const { return s * w.x + t * w.y + n * w.z; }
};

}  // namespace shadelab
