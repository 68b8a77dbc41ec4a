// shadelab irradiance maps: the cosine convolution of the PI-or-not article's GetIrradiance, normalised by
// the discrete cosine weights of the same texels so that a constant bakes to itself exactly:
//
//   S(n) = sum over input texels of L(w) max(0, n.w) dOmega(w),   W(n) = the same sum with L = 1
//   E(n) = pi S(n) / W(n)                                               (radiometric, W/m^2)
//   game convention: E(n) / pi = S(n) / W(n), the exit radiance of a white Lambert surface, so that a
//   constant environment of 0.5 bakes to exactly 0.5 (the AMD CubeMapGen / HDRShop check).
//
// W(n) is pi for the continuous integral but not over texel centres: 1.2e-4 off at a 128 x 64 lat-long
// (6 x 16^2 out; 3e-4 at odd output sizes), 2.2e-3 at a 6 x 15^2 cube, shrinking as 1/N^2; the plain sum
// S(n) carried that error into every constant. On real maps the normalisation is neutral to slightly
// worse: on Blender's eight 1024 x 512 HDRIs, against the exact integral of each piecewise-constant map,
// the mean relative error grows by 0.3e-6 .. 0.7e-6 on seven (from 4e-6 .. 2.6e-5; studio's falls by
// 0.2e-6) and the max (1.4e-5 .. 2.7e-3, texels cut by the horizon next to a bright source, which no
// per-normal factor can fix) by at most 2.6e-6, the largest |pi / W - 1| at that input size; the exact
// constant was taken for that (docs/envmap.md).
//
// S and W are exact for the input as given (cube texels, or lat-long texels with their exact solid
// angles), and they are computed without visiting every texel for every normal. The texels lie on lines (cube face rows,
// lat-long latitude rings) along which the set {w : n.w > 0} is one contiguous run:
//   - a cube face row is an arc of a great circle, and n.w changes sign once along it: n_f.(sc, tc, 1) > 0
//     is a linear condition in sc (a prefix or a suffix of the row);
//   - a latitude ring at polar angle theta meets the hemisphere n.w > 0 in the arc
//     |phi - phi_n| < acos(-n_y cot(theta) / sqrt(n_x^2 + n_z^2)).
// On that run max(0, n.w) = n.w, so the run contributes n . (sum of L dOmega w over the run), a difference
// of two prefix sums of the moment vectors L dOmega w (per colour channel, and for W a fourth channel with
// L = 1 over the same runs: a constant's S is L W step by step, so S / W is L; exactly for L = 0.5). Per normal the work is one
// run per line (6N or H lines) instead of one term per texel (6N^2 or WH), and the result equals the
// brute-force sum: no truncation, no error bound needed. The only difference from the per-texel sum is
// in texels within float rounding (1e-6 rad) of the normal's horizon, whose weight n.w is below 1e-6.
// Antipodes halve the work twice (irradiance.cpp has the identities): of each pair of output normals
// (n, -n) one is summed and the other follows from E(-n) = E(n) - n.M (M = sum L dOmega w); a lat-long's
// rings y and H - 1 - y share one line, since each texel of one is the antipode of a texel of the other.
// (Band-limited shortcuts, e.g. a higher-order SH, would need a truncation bound and fail it on maps whose
// brightest texel holds 7% of all flux next to the horizon, as Blender's night.exr does.)
//
// Work is split over blocks of output texels with TBB; each output texel is computed by one thread in a
// fixed order, so the result is the same for any thread count.
#pragma once

#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/base/progress.h"
#include "shadelab/image/image.h"

namespace shadelab {

enum class RadianceUnits { game, radiometric };

struct ConvolveOptions {
  // Cube inputs with faces larger than this, and lat-long inputs wider than 4x this, are first halved
  // (flux-preserving, solid-angle weighted) until they fit, to bound the prefix tables (36 bytes per input
  // texel: 57 MB at 6 x 512^2 or 2048 x 1024). 0: never halve. Blender's HDRIs (1024 x 512) and their
  // 6 x 256^2 cubes are used as given.
  int max_input_size = 512;
  ProgressFn progress;  // called on the calling thread between blocks of output texels
};

// E(n) = pi S(n) / W(n) at one direction by per-texel sums (radiometric). For tests and spot checks.
Rgb irradiance_brute_force(const CubeMap& radiance, const Vec3& n);
Rgb irradiance_brute_force(const Image& latlong, const Vec3& n);

// Irradiance cube (face size `size`) or lat-long (width x width/2) of a cube-map or a lat-long input.
CubeMap irradiance_cube(const CubeMap& radiance, int size, RadianceUnits units, const ConvolveOptions& options = {});
CubeMap irradiance_cube(const Image& latlong, int size, RadianceUnits units, const ConvolveOptions& options = {});
Image irradiance_latlong(const CubeMap& radiance, int width, RadianceUnits units,
                         const ConvolveOptions& options = {});
Image irradiance_latlong(const Image& latlong, int width, RadianceUnits units, const ConvolveOptions& options = {});

}  // namespace shadelab
