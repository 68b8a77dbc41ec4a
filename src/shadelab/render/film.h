// shadelab film output: linear HDR images to display-ready ones, and the files a render writes.
//
// Display transform: multiply by 2^exposure, then either clamp to [0, 1] or apply the filmic curve
// f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14) (Narkowicz, "ACES Filmic Tone Mapping Curve", 2015, a
// fit of the ACES reference rendering transform), then the sRGB encoding at PNG write (image/srgb.h).
// EXR files keep the linear radiance untouched.
//
// View transforms (docs/color.md): a PNG is the scene-linear Rec.709 image (the working space) through a named
// view: standard (the clamp), filmic (the curve above), pbr-neutral (Khronos PBR Neutral), agx (Blender 4's AgX
// Base in Filament's closed form), aces (Hill's fit of the ACES RRT + sRGB ODT), all kernels/display.sl's text,
// or an OpenColorIO config's display and view (color/ocio.h).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "shadelab/core/error.h"
#include "shadelab/image/image.h"
#include "shadelab/render/path_tracer.h"

namespace shadelab {

enum class ToneCurve { clamp, filmic };

double filmic_curve(double x);
// Linear display values in [0, 1], ready for sRGB encoding.
Image tonemap(const Image& hdr, double exposure_stops, ToneCurve curve);

// The views; the numbers are kernels/display.sl's VIEW_* (a shader's uniform). ocio: an OpenColorIO display/view.
enum class ViewTransform { standard = 0, filmic = 1, pbr_neutral = 2, agx = 3, aces = 4, ocio = 5 };

struct DisplayView {
  ViewTransform transform = ViewTransform::standard;
  // ocio only: the config file (empty: $OCIO), its display and view, and looks (OCIO's comma-separated list,
  // applied in the scene-linear space before the view; empty: the view's own).
  std::string ocio_config;
  std::string ocio_display;
  std::string ocio_view;
  std::string looks;
  bool operator==(const DisplayView&) const = default;
};

// The names `--view` takes: standard, filmic, pbr-neutral, agx, aces (and OCIO:<config>:<display>:<view>).
const char* view_name(ViewTransform view);
// Parses `standard | filmic | pbr-neutral | agx | aces | OCIO:<config>:<display>:<view>` (the config may be empty:
// then $OCIO; it may hold ':', the display and view are the last two fields). The error names the value.
Result<DisplayView> parse_view(std::string_view text);
// The view of ToneCurve (clamp: standard; filmic: filmic).
DisplayView view_of(ToneCurve curve);

// Linear display values in [0, 1] (for the PNG writer's sRGB encoding) of the scene-linear image after
// 2^exposure_stops, through `view`. For an OCIO view, the config's output code values are decoded with the sRGB
// inverse, so the PNG holds exactly the config's output; the errors (config not found or invalid, unknown
// display, view or look) are one line naming the config, display and view.
Result<Image> apply_view(const Image& hdr, double exposure_stops, const DisplayView& view);

struct FilmOutputs {
  std::filesystem::path exr;           // linear beauty (required)
  std::filesystem::path png;           // tone-mapped beauty (empty: none)
  double exposure_stops = 0.0;
  ToneCurve curve = ToneCurve::clamp;  // used when `view` is not set
  std::optional<DisplayView> view;     // the PNG's view (overrides curve)
  bool aovs = false;                   // also <exr stem>.albedo.exr, .normal.exr, .depth.exr
};

// Writes every output as one output set (write_files_atomically: together or not at all, concurrent writers
// serialised); returns the paths written.
Result<std::vector<std::filesystem::path>> write_film(const RenderResult& result, const FilmOutputs& outputs);

}  // namespace shadelab
