// Test helper for the envmap tests: a cube map whose every texel is f at the texel's centre direction.
#pragma once

#include <functional>

#include "shadelab/envmap/base/cubemap.h"

namespace shadelab::test_cubes {

inline CubeMap make_cube(int n, const std::function<Rgb(const Vec3&)>& f) {
  CubeMap c(n);
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) c.set(face, x, y, f(texel_direction(face, x, y, n)));
  return c;
}

}  // namespace shadelab::test_cubes
