// shadelab shader tools: running a GLSL ES 3.00 function file in headless Chromium's WebGL 2 (Debian's chromium;
// WebGL through ANGLE on SwiftShader, its CPU Vulkan device, so no GPU is needed). One fragment per case: the
// direction pairs go in as two RGBA32F textures, the results come back from an RGBA32F render target
// (EXT_color_buffer_float) read with readPixels. The page is a local file; Chromium prints it back with
// --dump-dom, so no server, driver protocol or npm browser download is involved.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shadelab/core/error.h"

namespace shadelab::shaders {

struct WebglResult {
  std::string renderer;       // WEBGL_debug_renderer_info's unmasked renderer
  std::vector<float> output;  // 4 floats per case
};

// RFC 4648 base64 (with '=' padding) of n bytes; the explorer embeds its baked environments with it.
std::string base64(const std::uint8_t* data, std::size_t n);

// $SHADELAB_CHROMIUM, else chromium (or chromium-browser) on PATH; empty if none.
std::string chromium_program();

// The textures of the exported IBL fetches (export.h ibl_fetch_declarations), RGBA32F, bound to texture units
// 3, 4, 5 as shadelab_ggx_chain (a 2D array texture of 6 layers and chain_levels mip levels), shadelab_dfg and
// shadelab_split_sum_lobes. Texels: chain level by level, each face by face, rows top to bottom, 4 floats each.
struct WebglIblTextures {
  int chain_size = 0;  // 0: no IBL textures
  int chain_levels = 0;
  std::vector<float> chain;
  int dfg_size = 0;
  std::vector<float> dfg;
  int lobe_size = 0;
  std::vector<float> lobes;
};

struct WebglProgram {
  std::string code;        // a GLSL ES 3.00 function file
  std::string expression;  // in terms of vec3 wi, wo
  std::vector<std::uint8_t> uniform;  // non-empty: the std140 bytes of uniform block `block_name`
  std::string block_name;
  std::string display_name;  // names the code in compiler errors
  std::vector<std::uint8_t> tables;  // non-empty: the bytes of the GGX energy tables' block (ShadelabGgxEnergy)
  WebglIblTextures ibl;
};

// Runs several programs over the same cases in one browser start (a start costs seconds); one result each.
Result<std::vector<Result<WebglResult>>> run_webgl_batch(const std::vector<WebglProgram>& programs,
                                                         const std::vector<float>& input);

// Evaluates `expression` (in terms of vec3 wi, wo) over the cases (8 floats each: wi.xyz, 0, wo.xyz, 0). With
// a non-empty `uniform`, the bytes fill the uniform block `block_name` (std140), and a non-empty `tables` the
// GGX energy tables' block. Errors: the shader compiler's
// first error line ("DISPLAY:LINE: ..."), or why the browser could not run it.
Result<WebglResult> run_webgl(const std::string& code, const std::string& expression, const std::vector<float>& input,
                              const std::vector<std::uint8_t>& uniform, const std::string& block_name,
                              const std::string& display_name, const std::vector<std::uint8_t>& tables = {});

}  // namespace shadelab::shaders
