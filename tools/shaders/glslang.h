// shadelab shader tools: glslang (Debian's glslang-tools, the Khronos reference front end for GLSL, GLSL ES
// and, through its HLSL front end, HLSL) compiling verification harnesses to SPIR-V, and the compute harness
// that wraps a function file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shadelab/core/error.h"
#include "translate.h"

namespace shadelab::shaders {

// A compute shader around `code` (a function file, included after `#line 1` so the compiler's line numbers
// are the file's): for case i it reads vec3 wi, wo from a storage buffer at binding 1 (two vec4 per case),
// evaluates `expression` (written in terms of wi and wo, of type vec3/float3) and writes vec4(expression, 0)
// to the storage buffer at binding 2. 64 invocations per work group. GLSL ES runs as ESSL 3.10 (compute needs
// 3.10; the code itself is checked as ESSL 3.00 by validate_essl300).
// `prelude`, when given, goes before the code's `#line 1` (the IBL verification's fetches over the storage
// buffer at binding 4).
std::string compute_harness(Lang lang, const std::string& code, const std::string& expression, const std::string& prelude = {});

// glslangValidator's path: $SHADELAB_GLSLANG, else glslangValidator on PATH; empty if neither.
std::string glslang_program();

// Compiles a complete compute shader to SPIR-V for Vulkan 1.1 (HLSL with -D -e main). Unbound uniform blocks
// get bindings automatically (the parameter block of an export gets binding 0). Errors: the compiler's first
// error line, the temporary file's name replaced by `display_name`.
Result<std::vector<std::uint32_t>> compile_compute(Lang lang, const std::string& source, const std::string& display_name);

// Checks `code` (a function file) as GLSL ES 3.00 in a fragment shader that calls `expression`, with glslang's
// OpenGL ES rules (what WebGL 2 and GLES 3.0 drivers accept). Errors as compile_compute.
Result<bool> validate_essl300(const std::string& code, const std::string& expression, const std::string& display_name);

// The first "ERROR: ..." line of a glslang log, with `path` replaced by `display_name` and the "ERROR: "
// prefix dropped; the first non-empty line if there is none.
std::string first_error_line(const std::string& log, const std::string& path, const std::string& display_name);

}  // namespace shadelab::shaders
