// shadelab environment inputs: the cube map an environment image stands for, shared by the front ends (the
// Python module; the CLI's `bake` does the same). The diffuse bakes of such an image are
// envmap/diffuse/environment_bakes.h.
//
// Contract:
// - environment_cube(image, face_size): a 2:1 image is a lat-long, resampled to a cube of face_size with
//   latlong_to_cube; face_size -1 means default_latlong_face_size(width). Any other shape must be a cube
//   cross (4:3 or 3:4, cube_from_cross). Errors: a face_size outside [1, 2048], a shape that is neither
//   ("... ; expected a 2:1 lat-long or a cube cross"), an invalid image. The message names no file: the
//   caller adds the file or argument name in front.
// - default_latlong_face_size(width): the largest power of two <= min(512, width / 4), at least 1 (a cube
//   face spans a quarter of the lat-long's width, so this keeps about the input's resolution).
#pragma once

#include "shadelab/core/error.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/image/image.h"

namespace shadelab {

inline constexpr int max_environment_face_size = 2048;

int default_latlong_face_size(int width);
Result<CubeMap> environment_cube(const Image& image, int face_size = -1);

}  // namespace shadelab
