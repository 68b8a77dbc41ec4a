// shadelab lat-long (equirectangular) maps, written down once for the whole project:
//
//   u = 0.5 + atan2(z, x) / (2 pi),   v = acos(y) / pi          (world +Y up, row 0 = v = 0 = straight up)
//   x = sin(theta) cos(phi), y = cos(theta), z = sin(theta) sin(phi),  theta = pi v, phi = 2 pi (u - 0.5)
//
// The image centre (u = 0.5, v = 0.5) looks along +X, as in Blender's equirectangular world mapping after its
// Z-up axes are turned to Y-up (Blender X, Y, Z -> X, -Z, Y), so Blender's HDRIs light a scene here as they
// do in Blender. Row y of a W x H map spans theta in [pi y/H, pi (y+1)/H]; each of its texels covers the
// solid angle (2 pi / W)(cos(pi y/H) - cos(pi (y+1)/H)), exactly; all rows total 4 pi.
#pragma once

#include "shadelab/core/error.h"
#include "shadelab/core/vec.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/image/image.h"

namespace shadelab {

Vec3 latlong_direction(double u, double v);
Vec2 latlong_uv(const Vec3& dir);  // dir need not be unit
double latlong_texel_solid_angle(int y, int width, int height);

// Bilinear lookup with horizontal wrap-around and clamping at the poles.
Rgb sample_latlong(const Image& map, const Vec3& dir);

// Lat-long -> cube. supersample = 0 (the default): exact area-weighted resampling, each cube texel the mean
// of the piecewise-constant lat-long map over the texel (every lat-long texel's flux goes to the cube
// texels it overlaps, in proportion to the overlap; a constant comes back exactly; latlong.cpp has the
// Green's-theorem construction). supersample = s > 0: the mean of s x s bilinear point samples per texel
// (the former method, which spreads a bright texel up to one texel beyond its edges).
CubeMap latlong_to_cube(const Image& latlong, int size, int supersample = 0);
// Cube -> lat-long: each output texel averages ss x ss bilinear lookups spread over it.
Image cube_to_latlong(const CubeMap& cube, int width, int supersample = 4);

// Cube maps stored as a cross in one image. Horizontal cross (4 x 3 faces):
//        +Y
//   -X   +Z   +X   -Z
//        -Y
// vertical cross (3 x 4 faces): the same, with -Z below -Y, turned 180 degrees. Faces keep the OpenGL
// orientation of cubemap.h, so every edge meets its neighbour.
enum class CrossLayout { horizontal, vertical };
Result<CubeMap> cube_from_cross(const Image& cross);  // layout from the aspect ratio; errors name the size
Image cube_to_cross(const CubeMap& cube, CrossLayout layout);

}  // namespace shadelab
