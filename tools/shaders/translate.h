// shadelab shader exporter: the token map from the shading dialect (src/shadelab/kernels/sl.h) to GLSL 4.50,
// GLSL ES 3.00 and HLSL. It works on the lexer's tokens, so comments, whitespace and line structure pass
// through untouched; docs/shaders.md lists the map.
//
//   dialect        GLSL / GLSL ES      HLSL
//   real           float               float
//   rgb            vec3                float3
//   vec3           vec3                float3
//   mix            mix                 lerp
//   atan2          atan                atan2
//   inline         (removed)           (removed)
//   const (file)   const               static const   (a plain HLSL global is a uniform)
//   const real A[N] = {a, b};  ->  GLSL: const float A[N] = float[N](a, b);   HLSL: static const float A[N] = {a, b};
#pragma once

#include <string>
#include <string_view>

#include "shadelab/core/error.h"

namespace shadelab::shaders {

enum class Lang { glsl, essl, hlsl };

// "glsl", "essl", "hlsl" (as the CLI takes them) and their display names ("GLSL 4.50", ...).
const char* lang_name(Lang lang);
const char* lang_display_name(Lang lang);
Result<Lang> parse_lang(std::string_view text);

// The dialect text written in the target language. `what` names the text in errors (a file name).
Result<std::string> translate(std::string_view dialect_text, Lang lang, const std::string& what);

// The target-language spelling of a dialect type name (real, rgb, vec3, int, bool).
std::string type_name(std::string_view dialect_type, Lang lang);

}  // namespace shadelab::shaders
