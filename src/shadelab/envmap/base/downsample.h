// shadelab downsampling: halving a cube map or a lat-long map without moving flux, for the bakes that work
// on a smaller input (irradiance's bound on its prefix tables) or on a pyramid of inputs (the Phong chain's
// and the sampled GGX chain's reads).
#pragma once

#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/image/image.h"

namespace shadelab {

// Halves the face size; each output texel is the solid-angle-weighted mean of its 2 x 2 input texels.
// Odd sizes are not halved (returned unchanged).
CubeMap downsample_cube(const CubeMap& cube);
// Halves a lat-long map (W x H -> W/2 x H/2) keeping the flux of every 2 x 2 block (row solid angles as
// weights). Odd sizes are returned unchanged.
Image downsample_latlong(const Image& latlong);

}  // namespace shadelab
