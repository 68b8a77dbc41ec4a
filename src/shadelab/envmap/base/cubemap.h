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
#include "shadelab/kernels/kernels.h"

namespace shadelab {

enum class CubeFace : int { pos_x = 0, neg_x = 1, pos_y = 2, neg_y = 3, pos_z = 4, neg_z = 5 };
inline constexpr std::array<const char*, 6> cube_face_names = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

struct CubeCoord {
  int face = 0;
  double s = 0.0;  // [0, 1] across the face
  double t = 0.0;  // [0, 1] down the face
};

// Direction (not necessarily unit) -> face and coordinates: OpenGL table 8.19, ties to X, then Y (any choice is
// consistent on the shared edge), the kernel text kernels/cube.sl cube_face_coord that the shaders and the
// explorer read too. Inline: the GGX prefilter calls it for every sample of every texel.
inline CubeCoord cube_coord(const Vec3& r) {
  const kernel::CubeFaceCoord c = kernel::cube_face_coord(r);
  return {c.face, c.s, c.t};
}

// Face and coordinates -> unit direction (kernels/cube.sl cube_face_direction, the inverse of table 8.19).
inline Vec3 cube_direction(int face, double s, double t) { return kernel::cube_face_direction(face, s, t); }
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

// The cube's texels as the kernels' fetches read them (kernels.h CubeTexels): pointers into its face images,
// valid while the cube lives unchanged. Bind them (kernel::IblTexels, kernel::IblBinding) around the call of a
// kernel that reads cubes (kernels/cube.sl, game_ibl.sl).
kernel::CubeTexels cube_texels(const CubeMap& cube);

// A bilinear lookup at direction dir that crosses face edges (the reads of prefilter_ggx): the kernel text
// kernels/cube.sl cube_sample_seamless on this cube. Black for an empty cube.
Rgb sample_cube_seamless(const CubeMap& cube, const Vec3& dir);
// Texel (x, y) of a face, where x or y may be one texel outside [0, N): the kernel text's
// cube_texel_across_edges (kernels/cube.sl) on this cube.
Rgb texel_across_edges(const CubeMap& c, int face, int x, int y);

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
