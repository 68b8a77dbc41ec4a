// shadelab OpenColorIO: a config's display/view or colour-space conversion applied to packed float32 RGB
// (3 floats a pixel, in place) with OpenColorIO 2's CPU processor (Debian's libopencolorio-dev; docs/color.md).
//
// Contract: the config is the file given, else $OCIO; every error (no config, a config OCIO refuses, an unknown
// display, view, look or colour space, an OCIO exception) is one printable line naming the config and what was
// asked for. Nothing here changes the buffer unless the call succeeds. Processors are built per call; applying one
// is deterministic and independent of threads (OCIO's CPU path has no randomness).
// Target shadelab_ocio (this folder's ocio.cpp alone: the rest of color/ is header-only).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "shadelab/core/error.h"

namespace shadelab::ocio {

// The config file to use: `path` if it is not empty, else $OCIO; an error naming both when neither is set.
Result<std::string> resolve_config(const std::string& path);

struct DisplayViewRequest {
  std::string config;       // a file; empty: $OCIO
  std::string display;
  std::string view;
  std::string looks;        // OCIO's look list ("a, +b, -c"); empty: the view's own looks
  std::string input_space;  // the input's colour space; empty: the config's scene_linear role
};

// The display/view of `request` applied to `pixels` RGB pixels of `rgb`, in place: display code values out.
Result<bool> apply_display_view(const DisplayViewRequest& request, float* rgb, std::size_t pixels);

// Colour space `from` -> `to` of the config (`config` empty: $OCIO), in place.
Result<bool> convert(const std::string& config, const std::string& from, const std::string& to, float* rgb,
                     std::size_t pixels);

// The config's displays, and the views of one display (for messages and --help).
Result<std::vector<std::string>> displays(const std::string& config);
Result<std::vector<std::string>> views(const std::string& config, const std::string& display);

}  // namespace shadelab::ocio
