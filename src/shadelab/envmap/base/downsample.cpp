#include "shadelab/envmap/base/downsample.h"

#include <vector>

#include "shadelab/envmap/base/latlong.h"

namespace shadelab {

CubeMap downsample_cube(const CubeMap& cube) {
  if (cube.size % 2 != 0 || cube.size < 2) return cube;
  const int n = cube.size / 2;
  const std::vector<double>& omega = cube_face_solid_angles(cube.size);
  CubeMap out(n);
  for (int f = 0; f < 6; ++f) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        Rgb sum;
        double w = 0.0;
        for (int j = 0; j < 2; ++j) {
          for (int i = 0; i < 2; ++i) {
            const double a = omega[static_cast<std::size_t>(2 * y + j) * static_cast<std::size_t>(cube.size) + static_cast<std::size_t>(2 * x + i)];
            sum += cube.texel(f, 2 * x + i, 2 * y + j) * a;
            w += a;
          }
        }
        out.set(f, x, y, sum / w);
      }
    }
  }
  return out;
}

Image downsample_latlong(const Image& ll) {
  if (ll.width % 2 != 0 || ll.height % 2 != 0 || ll.width < 2 || ll.height < 2) return ll;
  Image out(ll.width / 2, ll.height / 2);
  for (int y = 0; y < out.height; ++y) {
    const double w0 = latlong_texel_solid_angle(2 * y, ll.width, ll.height);
    const double w1 = latlong_texel_solid_angle(2 * y + 1, ll.width, ll.height);
    for (int x = 0; x < out.width; ++x) {
      const Rgb sum = (ll.at(2 * x, 2 * y) + ll.at(2 * x + 1, 2 * y)) * w0 + (ll.at(2 * x, 2 * y + 1) + ll.at(2 * x + 1, 2 * y + 1)) * w1;
      out.set(x, y, sum / (2.0 * (w0 + w1)));
    }
  }
  return out;
}

}  // namespace shadelab
