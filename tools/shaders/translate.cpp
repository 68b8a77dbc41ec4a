#include "translate.h"

#include <vector>

#include "sl_lexer.h"

namespace shadelab::shaders {

const char* lang_name(Lang lang) {
  switch (lang) {
    case Lang::glsl: return "glsl";
    case Lang::essl: return "essl";
    case Lang::hlsl: return "hlsl";
  }
  return "glsl";
}

const char* lang_display_name(Lang lang) {
  switch (lang) {
    case Lang::glsl: return "GLSL 4.50";
    case Lang::essl: return "GLSL ES 3.00";
    case Lang::hlsl: return "HLSL (Shader Model 5.0)";
  }
  return "GLSL 4.50";
}

Result<Lang> parse_lang(std::string_view text) {
  if (text == "glsl") return Lang::glsl;
  if (text == "essl") return Lang::essl;
  if (text == "hlsl") return Lang::hlsl;
  return make_error("--lang: unknown language '" + std::string(text) + "' (languages: glsl, essl, hlsl)");
}

std::string type_name(std::string_view t, Lang lang) {
  const bool hlsl = lang == Lang::hlsl;
  if (t == "real") return "float";
  if (t == "rgb" || t == "vec3") return hlsl ? "float3" : "vec3";
  return std::string(t);
}

namespace {

std::string map_identifier(const std::string& id, Lang lang) {
  const bool hlsl = lang == Lang::hlsl;
  if (id == "real" || id == "rgb" || id == "vec3") return type_name(id, lang);
  if (id == "mix" && hlsl) return "lerp";
  if (id == "atan2" && !hlsl) return "atan";
  return id;
}

// Index of the next code token at or after k, or tokens.size().
std::size_t next_code(const std::vector<Token>& t, std::size_t k) {
  while (k < t.size() && is_trivia(t[k])) ++k;
  return k;
}

}  // namespace

Result<std::string> translate(std::string_view text, Lang lang, const std::string& what) {
  std::vector<Token> t = lex(text);
  const bool hlsl = lang == Lang::hlsl;
  int depth = 0;  // braces
  // For a file-scope constant array in GLSL: the '{' and its matching '}' become TYPE[N]( and ).
  std::size_t array_open = std::string::npos;
  for (std::size_t k = 0; k < t.size(); ++k) {
    Token& tok = t[k];
    if (tok.kind == TokenKind::identifier) {
      if (tok.text == "inline") {
        tok.text.clear();
        if (k + 1 < t.size() && t[k + 1].kind == TokenKind::whitespace) t[k + 1].text.clear();
        continue;
      }
      if (tok.text == "const" && depth == 0) {
        // const TYPE NAME [ N ] = { ... } ;
        const std::size_t ty = next_code(t, k + 1);
        const std::size_t name = next_code(t, ty + 1);
        const std::size_t br = next_code(t, name + 1);
        if (br < t.size() && t[br].text == "[") {
          const std::size_t size = next_code(t, br + 1);
          const std::size_t close = next_code(t, size + 1);
          const std::size_t eq = next_code(t, close + 1);
          const std::size_t open = next_code(t, eq + 1);
          if (close >= t.size() || t[close].text != "]" || eq >= t.size() || t[eq].text != "=" || open >= t.size() ||
              t[open].text != "{") {
            return make_error(what + ":" + std::to_string(tok.line) +
                              ": a file-scope constant array must read `const TYPE NAME[N] = {...};`");
          }
          if (!hlsl) {
            t[open].text = type_name(t[ty].text, lang) + "[" + t[size].text + "](";
            array_open = open;
            // In GLSL the table is a global variable, not a const: glslang copies a const array into a function
            // variable wherever it is indexed by a non-constant, and lavapipe then lowers every copy element by
            // element (the 2112-entry GGX energy tables: 7 s to build the pipeline as const, 1 s as a global).
            tok.text.clear();
            if (k + 1 < t.size() && t[k + 1].kind == TokenKind::whitespace) t[k + 1].text.clear();
            continue;
          }
        }
        if (hlsl) tok.text = "static const";
        continue;
      }
      tok.text = map_identifier(tok.text, lang);
      continue;
    }
    if (tok.kind != TokenKind::punctuation) continue;
    if (array_open != std::string::npos && k > array_open) {
      if (tok.text == "{") {
        return make_error(what + ":" + std::to_string(tok.line) + ": nested braces in a constant array");
      }
      if (tok.text == "}") {
        tok.text = ")";
        array_open = std::string::npos;
        continue;
      }
    }
    if (tok.text == "{") ++depth;
    if (tok.text == "}") --depth;
  }
  return join(t);
}

}  // namespace shadelab::shaders
