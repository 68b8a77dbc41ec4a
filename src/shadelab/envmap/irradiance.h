// shadelab irradiance maps by brute-force cosine convolution (the PI-or-not article's GetIrradiance):
//
//   E(n) = sum over input texels of L(w) max(0, n.w) dOmega(w)          (radiometric, W/m^2)
//   game convention: E(n) / pi, the exit radiance of a white Lambert surface, so that a constant
//   environment of 0.5 bakes to 0.5 (the AMD CubeMapGen / HDRShop check).
//
// The sum is exact for the input as given. To bound the cost (outputs x inputs), inputs larger than
// max_input_size per face are first halved with solid-angle weights, which keeps the integral of L over
// every coarse texel; the cosine kernel is smooth, so the difference is small (tested, docs/envmap.md).
// Work is split over output rows with TBB; each output texel is computed by one thread in a fixed order,
// so the result is the same for any thread count.
#pragma once

#include <functional>

#include "shadelab/envmap/cubemap.h"
#include "shadelab/image/image.h"

namespace shadelab {

enum class RadianceUnits { game, radiometric };

using ProgressFn = std::function<void(double fraction_done)>;

struct ConvolveOptions {
  int max_input_size = 128;  // input faces larger than this are halved (solid-angle weighted) first
  ProgressFn progress;       // called on the calling thread between chunks of rows
};

// Halves the face size; each output texel is the solid-angle-weighted mean of its 2 x 2 input texels.
// Odd sizes are not halved (returned unchanged).
CubeMap downsample_cube(const CubeMap& cube);

// E(n) at one direction over every texel of the cube (radiometric). For tests and spot checks.
Rgb irradiance_brute_force(const CubeMap& radiance, const Vec3& n);

CubeMap irradiance_cube(const CubeMap& radiance, int size, RadianceUnits units, const ConvolveOptions& options = {});
Image irradiance_latlong(const CubeMap& radiance, int width, RadianceUnits units,
                         const ConvolveOptions& options = {});

}  // namespace shadelab
