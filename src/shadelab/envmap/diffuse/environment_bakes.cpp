#include "shadelab/envmap/diffuse/environment_bakes.h"

#include "shadelab/envmap/base/environment.h"

namespace shadelab {

Result<Sh9> environment_sh9(const Image& image, int face_size) {
  if (image.is_valid() && image.width == 2 * image.height && face_size == -1) return project_sh9(image);
  auto cube = environment_cube(image, face_size);
  if (!cube) return make_error(cube.error().message);
  return project_sh9(*cube);
}

Result<CubeMap> environment_irradiance(const Image& image, int size, RadianceUnits units, int face_size) {
  if (image.is_valid() && image.width == 2 * image.height && face_size == -1) return irradiance_cube(image, size, units);
  auto cube = environment_cube(image, face_size);
  if (!cube) return make_error(cube.error().message);
  return irradiance_cube(*cube, size, units);
}

BandFactors sh9_irradiance_factors(RadianceUnits units, ShWindow window) {
  const BandFactors w = sh_window_factors(window);
  const BandFactors& base = units == RadianceUnits::game ? cosine_band_factors_over_pi : cosine_band_factors;
  return {w[0] * base[0], w[1] * base[1], w[2] * base[2]};
}

}  // namespace shadelab
