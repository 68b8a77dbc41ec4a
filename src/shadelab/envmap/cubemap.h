// shadelab cube maps: six square faces in the OpenGL order +X, -X, +Y, -Y, +Z, -Z with the OpenGL
// orientation (OpenGL 4.6 core specification, table 8.19 "Selection of cube map images"), so baked files
// load in engines unchanged. Row 0 of a face image is t = 0 of the table (the first row stored in KTX/DDS).
//
// For a direction r with major axis ma, the face coordinates are s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2:
//   +X: sc = -rz, tc = -ry    -X: sc = +rz, tc = -ry
//   +Y: sc = +rx, tc = +rz    -Y: sc = +rx, tc = -rz
//   +Z: sc = +rx, tc = -ry    -Z: sc = -rx, tc = -ry
// Texel (x, y) of an N x N face covers s in [x/N, (x+1)/N], t in [y/N, (y+1)/N]; its centre direction is
// texel_direction(face, x, y, N).
//
// Exact texel solid angle: the face is the square [-1, 1]^2 on the plane at distance 1, and the solid angle
// of [x0, x1] x [y0, y1] is F(x1, y1) - F(x0, y1) - F(x1, y0) + F(x0, y0) with F(x, y) = atan(x y / sqrt(1 +
// x^2 + y^2)) (the standard closed form of the integral of (1 + x^2 + y^2)^(-3/2) dx dy; e.g. Driscoll,
// "Cubemap texel solid angle", 2012). The six faces total 4 pi.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "shadelab/core/vec.h"
#include "shadelab/image/image.h"

namespace shadelab {

enum class CubeFace : int { pos_x = 0, neg_x = 1, pos_y = 2, neg_y = 3, pos_z = 4, neg_z = 5 };
inline constexpr std::array<const char*, 6> cube_face_names = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

struct CubeCoord {
  int face = 0;
  double s = 0.0;  // [0, 1] across the face
  double t = 0.0;  // [0, 1] down the face
};

// Direction (not necessarily unit) -> face and coordinates. Inline: the GGX prefilter calls it for every
// sample of every texel.
inline CubeCoord cube_coord(const Vec3& r) {
  const double ax = std::abs(r.x);
  const double ay = std::abs(r.y);
  const double az = std::abs(r.z);
  CubeCoord c;
  double sc = 0.0;
  double tc = 0.0;
  double ma = 0.0;
  // OpenGL table 8.19; ties go to X, then Y (any choice is consistent on the shared edge).
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

// Face and coordinates -> unit direction.
Vec3 cube_direction(int face, double s, double t);
inline Vec3 texel_direction(int face, int x, int y, int size) {
  return cube_direction(face, (x + 0.5) / size, (y + 0.5) / size);
}

// Exact solid angle of texel (x, y) of an N x N face (the same on all six faces).
double cube_texel_solid_angle(int x, int y, int size);

struct CubeMap {
  int size = 0;
  std::array<Image, 6> faces;

  CubeMap() = default;
  explicit CubeMap(int n);
  Rgb texel(int face, int x, int y) const { return faces[static_cast<std::size_t>(face)].at(x, y); }
  void set(int face, int x, int y, const Rgb& c) { faces[static_cast<std::size_t>(face)].set(x, y, c); }
  // Bilinear lookup inside the face that contains dir (texel centres; clamped at face edges).
  Rgb sample(const Vec3& dir) const;
};

// Per-texel data of an N x N cube map precomputed once per resolution: unit directions and exact solid
// angles, face-major then row-major, the layout of the face images. Shared by the SH projection and the
// convolutions, so no hot loop recomputes a direction or a solid angle.
struct CubeTexelTable {
  int size = 0;
  std::vector<Vec3> direction;     // 6 N^2 entries
  std::vector<double> solid_angle; // 6 N^2 entries
  static const CubeTexelTable& get(int size);  // cached, thread-safe
};

// Per-(x, y) data shared by the six faces of an N x N cube: the face-plane coordinates of the texel centre
// divided by its distance from the origin (a, b), 1/distance (c), and the exact solid angle w. Each face's
// direction is a signed permutation of (a, b, c) (the inverse of table 8.19), so this table is a sixth of a
// per-texel one and stays in cache while the six faces stream through. Cached per size, thread-safe.
struct CubeFaceTexel {
  float a, b, c, w;
};
const std::vector<CubeFaceTexel>& cube_face_table(int size);

// Exact solid angles of the N x N texels (x, y) of one face (the same on all six), in double, row-major:
// from the (N + 1)^2 corner values of F, so (N + 1)^2 atan calls instead of 4 N^2. Cached per size.
const std::vector<double>& cube_face_solid_angles(int size);

}  // namespace shadelab
