#include "shadelab/envmap/base/environment.h"

#include <algorithm>
#include <string>

#include "shadelab/envmap/base/latlong.h"

namespace shadelab {

int default_latlong_face_size(int width) {
  int size = 1;
  while (size * 2 <= std::min(512, width / 4)) size *= 2;
  return size;
}

Result<CubeMap> environment_cube(const Image& image, int face_size) {
  if (!image.is_valid()) return make_error("the environment image is empty or malformed");
  if (image.width == 2 * image.height) {
    const int size = face_size == -1 ? default_latlong_face_size(image.width) : face_size;
    if (size < 1 || size > max_environment_face_size) {
      return make_error("face size " + std::to_string(size) + " is out of range [1, " +
                        std::to_string(max_environment_face_size) + "]");
    }
    return latlong_to_cube(image, size);
  }
  auto cube = cube_from_cross(image);
  if (!cube) return make_error(cube.error().message + "; expected a 2:1 lat-long or a cube cross");
  return std::move(cube).value();
}

}  // namespace shadelab
