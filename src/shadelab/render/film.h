// shadelab film output: linear HDR images to display-ready ones, and the files a render writes.
//
// Display transform: multiply by 2^exposure, then either clamp to [0, 1] or apply the filmic curve
// f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) (Narkowicz, "ACES Filmic Tone Mapping Curve", 2015, a
// fit of the ACES reference rendering transform), then the sRGB encoding at PNG write (image/srgb.h).
// EXR files keep the linear radiance untouched.
#pragma once

#include <filesystem>

#include "shadelab/core/error.h"
#include "shadelab/image/image.h"
#include "shadelab/render/path_tracer.h"

namespace shadelab {

enum class ToneCurve { clamp, filmic };

double filmic_curve(double x);
// Linear display values in [0, 1], ready for sRGB encoding.
Image tonemap(const Image& hdr, double exposure_stops, ToneCurve curve);

struct FilmOutputs {
  std::filesystem::path exr;           // linear beauty (required)
  std::filesystem::path png;           // tone-mapped beauty (empty: none)
  double exposure_stops = 0.0;
  ToneCurve curve = ToneCurve::clamp;
  bool aovs = false;                   // also <exr stem>.albedo.exr, .normal.exr, .depth.exr
};

// Writes every output as one output set (write_files_atomically: together or not at all, concurrent writers
// serialised); returns the paths written.
Result<std::vector<std::filesystem::path>> write_film(const RenderResult& result, const FilmOutputs& outputs);

}  // namespace shadelab
