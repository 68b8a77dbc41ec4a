// The irradiance error of each SH-family encoding of an environment, against its exact irradiance.
//
// exact E(n) = sum over the environment's texels of L dOmega max(0, n . w): irradiance_cube (brute force, the
// discrete cosine convolution of the map as given) at the texel centres of an N x N evaluation cube. Each
// encoding is projected from the same cube map, so the error is the encoding's own (truncation, windowing,
// ZH3's single zonal term), not a resampling error. Per direction, with Y the Rec. 709 luminance:
//   relative error = |Y(E_enc(n)) - Y(E(n))| / Y(E(n)); mean = solid-angle weighted mean over the sphere;
//   max = its maximum over the evaluation texels;
//   negative solid angle = the total exact solid angle of the evaluation texels where any channel of
//   E_enc(n) < 0 (ringing: the reconstruction goes below zero), in steradians (of 4 pi).
// Encodings: L1 .. L4 (2 .. 5 bands), each with no window, hanning and lanczos (sh_bands.h), and ZH3 stored
// and hallucinated (zh3.h).
#pragma once

#include <string>
#include <vector>

#include "shadelab/envmap/base/cubemap.h"

namespace shadelab {

struct ShEncodingError {
  std::string encoding;      // "L2", "L2 hanning", "ZH3 stored", ...
  int coefficients = 0;      // per channel
  double mean_relative = 0;  // of luminance
  double max_relative = 0;
  double negative_solid_angle = 0;  // sr
};

std::vector<ShEncodingError> sh_encoding_errors(const CubeMap& env, int eval_size);

}  // namespace shadelab
