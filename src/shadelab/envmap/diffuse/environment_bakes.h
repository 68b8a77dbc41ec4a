// shadelab diffuse bakes of an environment image: the SH9 projection and the irradiance cube that
// `shadelab bake sh` / `bake irradiance` make of an image, and the SH band factors of such a bake, shared by
// the front ends (the Python module; the CLI's `bake` does the same). The image's cube is
// envmap/base/environment.h's.
//
// Contract:
// - environment_sh9(image, face_size), environment_irradiance(image, size, units, face_size): the bakes of
//   `shadelab bake sh` / `bake irradiance`: a lat-long with face_size -1 is used over its own texels (no
//   resampling: project_sh9(Image), irradiance_cube(Image)); otherwise the bake of environment_cube(image,
//   face_size). Errors as environment_cube.
// - sh9_irradiance_factors(units, window): per-band factors that turn projected radiance coefficients
//   into irradiance coefficients: (pi, 2pi/3, pi/4) radiometric (E), (1, 2/3, 1/4) game (E/pi), each times
//   the window's factor (sh_window_factors).
#pragma once

#include "shadelab/core/error.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/diffuse/irradiance.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/image/image.h"

namespace shadelab {

Result<Sh9> environment_sh9(const Image& image, int face_size = -1);
Result<CubeMap> environment_irradiance(const Image& image, int size, RadianceUnits units, int face_size = -1);
BandFactors sh9_irradiance_factors(RadianceUnits units, ShWindow window);

}  // namespace shadelab
