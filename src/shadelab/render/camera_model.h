// shadelab pinhole camera: the primary ray through an image position, as both renderers and the IBL error
// maps (ibl_error.h) compute it. Image position (px, py) in pixels, (0, 0) the top-left corner; the ray
// leaves the camera position through the point (sx, sy) of the image plane at distance 1 along `forward`,
//   sx = (2 px / W - 1) tan(vfov / 2) (W / H),   sy = (1 - 2 py / H) tan(vfov / 2),
// right = normalize(forward x up), up' = right x forward (the scene format's camera, docs/scene-format.md).
#pragma once

#include <cmath>

#include "shadelab/core/constants.h"
#include "shadelab/render/accel.h"  // Ray
#include "shadelab/scene/scene.h"

namespace shadelab {

struct CameraModel {
  Vec3 origin, forward, right, up;
  double tan_half = 0.0;
  double aspect = 1.0;
  int width = 1, height = 1;
  explicit CameraModel(const Camera& c) : origin(c.position), width(c.width), height(c.height) {
    forward = normalize(c.look_at - c.position);
    right = normalize(cross(forward, c.up));
    up = cross(right, forward);
    tan_half = std::tan(0.5 * deg_to_rad(c.vfov_deg));
    aspect = static_cast<double>(c.width) / c.height;
  }
  Ray ray(double px, double py) const {
    const double sx = (2.0 * px / width - 1.0) * tan_half * aspect;
    const double sy = (1.0 - 2.0 * py / height) * tan_half;
    return {origin, normalize(forward + right * sx + up * sy)};
  }
};

}  // namespace shadelab
