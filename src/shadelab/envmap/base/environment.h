// shadelab environment inputs: the cube map an environment image stands for, and the SH band factors of
// an irradiance bake, shared by the front ends (the Python module; the CLI's `bake` does the same).
//
// Contract:
// - environment_cube(image, face_size): a 2:1 image is a lat-long, resampled to a cube of face_size with
//   latlong_to_cube; face_size -1 means default_latlong_face_size(width). Any other shape must be a cube
//   cross (4:3 or 3:4, cube_from_cross). Errors: a face_size outside [1, 2048], a shape that is neither
//   ("... ; expected a 2:1 lat-long or a cube cross"), an invalid image. The message names no file: the
//   caller adds the file or argument name in front.
// - environment_sh9(image, face_size), environment_irradiance(image, size, units, face_size): the bakes of
//   `shadelab bake sh` / `bake irradiance`: a lat-long with face_size -1 is used over its own texels (no
//   resampling: project_sh9(Image), irradiance_cube(Image)); otherwise the bake of environment_cube(image,
//   face_size). Errors as environment_cube.
// - default_latlong_face_size(width): the largest power of two <= min(512, width / 4), at least 1 (a cube
//   face spans a quarter of the lat-long's width, so this keeps about the input's resolution).
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

inline constexpr int max_environment_face_size = 2048;

int default_latlong_face_size(int width);
Result<CubeMap> environment_cube(const Image& image, int face_size = -1);
Result<Sh9> environment_sh9(const Image& image, int face_size = -1);
Result<CubeMap> environment_irradiance(const Image& image, int size, RadianceUnits units, int face_size = -1);
BandFactors sh9_irradiance_factors(RadianceUnits units, ShWindow window);

}  // namespace shadelab
