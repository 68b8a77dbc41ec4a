#include "shadelab/envmap/latlong.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "shadelab/core/constants.h"

namespace shadelab {

Vec3 latlong_direction(double u, double v) {
  const double theta = pi * v;
  const double phi = two_pi * (u - 0.5);
  const double st = std::sin(theta);
  return {st * std::cos(phi), std::cos(theta), st * std::sin(phi)};
}

Vec2 latlong_uv(const Vec3& d) {
  const double len = length(d);
  const double y = std::clamp(d.y / len, -1.0, 1.0);
  return {0.5 + std::atan2(d.z, d.x) * inv_two_pi, std::acos(y) * inv_pi};
}

double latlong_texel_solid_angle(int y, int width, int height) {
  // (2 pi / W) (cos theta0 - cos theta1): the ring between two polar angles, split into W texels.
  return two_pi / width * (std::cos(pi * y / height) - std::cos(pi * (y + 1) / height));
}

Rgb sample_latlong(const Image& map, const Vec3& dir) {
  const Vec2 uv = latlong_uv(dir);
  const double fx = uv.x * map.width - 0.5;
  const double fy = std::clamp(uv.y * map.height - 0.5, 0.0, map.height - 1.0);
  const double flx = std::floor(fx);
  const int x0 = static_cast<int>(flx);
  const double ax = fx - flx;
  const int y0 = std::min(static_cast<int>(fy), map.height - 1);
  const int y1 = std::min(y0 + 1, map.height - 1);
  const double ay = fy - y0;
  auto wrap = [&](int x) { return ((x % map.width) + map.width) % map.width; };
  const int xa = wrap(x0);
  const int xb = wrap(x0 + 1);
  return (map.at(xa, y0) * (1 - ax) + map.at(xb, y0) * ax) * (1 - ay) +
         (map.at(xa, y1) * (1 - ax) + map.at(xb, y1) * ax) * ay;
}

CubeMap latlong_to_cube(const Image& latlong, int size, int ss) {
  CubeMap cube(size);
  const double inv = 1.0 / (size * ss);
  for (int f = 0; f < 6; ++f) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        Rgb sum;
        for (int j = 0; j < ss; ++j) {
          for (int i = 0; i < ss; ++i) {
            sum += sample_latlong(latlong, cube_direction(f, (x * ss + i + 0.5) * inv, (y * ss + j + 0.5) * inv));
          }
        }
        cube.set(f, x, y, sum / (ss * ss));
      }
    }
  }
  return cube;
}

Image cube_to_latlong(const CubeMap& cube, int width, int ss) {
  const int height = std::max(1, width / 2);
  Image out(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      Rgb sum;
      for (int j = 0; j < ss; ++j) {
        for (int i = 0; i < ss; ++i) {
          const double u = (x + (i + 0.5) / ss) / width;
          const double v = (y + (j + 0.5) / ss) / height;
          sum += cube.sample(latlong_direction(u, v));
        }
      }
      out.set(x, y, sum / (ss * ss));
    }
  }
  return out;
}

namespace {
struct Slot {
  int face, col, row;
  bool rotate180;
};
constexpr Slot horizontal_slots[6] = {{2, 1, 0, false}, {1, 0, 1, false}, {4, 1, 1, false},
                                      {0, 2, 1, false}, {5, 3, 1, false}, {3, 1, 2, false}};
constexpr Slot vertical_slots[6] = {{2, 1, 0, false}, {1, 0, 1, false}, {4, 1, 1, false},
                                    {0, 2, 1, false}, {3, 1, 2, false}, {5, 1, 3, true}};
}  // namespace

Result<CubeMap> cube_from_cross(const Image& cross) {
  const Slot* slots = nullptr;
  int n = 0;
  if (cross.width * 3 == cross.height * 4 && cross.width % 4 == 0) {
    slots = horizontal_slots;
    n = cross.width / 4;
  } else if (cross.width * 4 == cross.height * 3 && cross.width % 3 == 0) {
    slots = vertical_slots;
    n = cross.width / 3;
  } else {
    return make_error("cube cross: a " + std::to_string(cross.width) + " x " + std::to_string(cross.height) +
                      " image is neither a horizontal (4:3) nor a vertical (3:4) cross of square faces");
  }
  if (n == 0) return make_error("cube cross: the image is empty");
  CubeMap cube(n);
  for (int k = 0; k < 6; ++k) {
    const Slot& s = slots[k];
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const int sx = s.rotate180 ? n - 1 - x : x;
        const int sy = s.rotate180 ? n - 1 - y : y;
        cube.set(s.face, x, y, cross.at(s.col * n + sx, s.row * n + sy));
      }
    }
  }
  return cube;
}

Image cube_to_cross(const CubeMap& cube, CrossLayout layout) {
  const int n = cube.size;
  const Slot* slots = layout == CrossLayout::horizontal ? horizontal_slots : vertical_slots;
  Image out = layout == CrossLayout::horizontal ? Image(4 * n, 3 * n) : Image(3 * n, 4 * n);
  for (int k = 0; k < 6; ++k) {
    const Slot& s = slots[k];
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const int sx = s.rotate180 ? n - 1 - x : x;
        const int sy = s.rotate180 ? n - 1 - y : y;
        out.set(s.col * n + sx, s.row * n + sy, cube.texel(s.face, x, y));
      }
    }
  }
  return out;
}

}  // namespace shadelab
