#include "kernel_library.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "shadelab/kernels/kernels.h"
#include "sl_lexer.h"

namespace shadelab::shaders {

int StructField::scalar_count() const {
  const int per = (type == FieldType::rgb || type == FieldType::vec3) ? 3 : 1;
  return per * (array_size > 0 ? array_size : 1);
}

namespace {

std::optional<FieldType> field_type(const std::string& t) {
  if (t == "real") return FieldType::real;
  if (t == "int") return FieldType::integer;
  if (t == "rgb") return FieldType::rgb;
  if (t == "vec3") return FieldType::vec3;
  if (t == "bool") return FieldType::boolean;
  return std::nullopt;
}

// The code tokens of a file (no whitespace, comments or directives).
std::vector<Token> code_tokens(const std::string& text) {
  std::vector<Token> out;
  for (auto& t : lex(text)) {
    if (!is_trivia(t) && t.kind != TokenKind::preprocessor) out.push_back(std::move(t));
  }
  return out;
}

// Words GLSL 4.50, GLSL ES 3.00 or HLSL reserve that are plain identifiers in C++: a kernel that names a
// variable or field so would translate to a file no shader compiler accepts (GLSL 4.50 section 3.6, ES 3.00
// section 3.7, HLSL's keyword list; the ones a formula could plausibly use).
bool reserved_in_shaders(const std::string& w) {
  static const char* const words[] = {
      "in", "out", "inout", "uniform", "buffer", "shared", "layout", "centroid", "flat", "smooth", "sample",
      "patch", "precision", "lowp", "mediump", "highp", "attribute", "varying", "invariant", "precise", "coherent",
      "filter", "input", "output", "discard", "common", "partition", "active", "superp", "texture", "image",
      "subroutine", "half", "fixed", "sampler", "register", "packoffset", "matrix", "vector", "line", "point",
      "triangle", "lineadj", "triangleadj", "snorm", "unorm", "groupshared", "nointerpolation", "linear",
      "noperspective", "row_major", "column_major", "technique", "pass", "string", "cbuffer", "tbuffer"};
  for (const char* r : words) {
    if (w == r) return true;
  }
  return false;
}

}  // namespace

Result<KernelLibrary> KernelLibrary::parse(std::vector<KernelFile> files) {
  KernelLibrary lib;
  lib.m_files = std::move(files);
  for (std::size_t f = 0; f < lib.m_files.size(); ++f) {
    const KernelFile& file = lib.m_files[f];
    const std::vector<Token> t = code_tokens(file.text);
    FileInfo info;
    auto where = [&](std::size_t k) {
      return "kernel " + file.name + ":" + std::to_string(k < t.size() ? t[k].line : 0) + ": ";
    };
    auto text_at = [&](std::size_t k) -> const std::string& {
      static const std::string empty;
      return k < t.size() ? t[k].text : empty;
    };
    auto define = [&](const std::string& name, std::size_t k) -> Result<bool> {
      if (lib.m_defined_in.count(name) != 0 || info.defines.count(name) != 0) {
        return make_error(where(k) + "'" + name + "' is defined twice");
      }
      info.defines.insert(name);
      return true;
    };
    auto resolve_size = [&](std::size_t k) -> Result<int> {
      const std::string& s = text_at(k);
      long long v = 0;
      if (!s.empty() && t[k].kind == TokenKind::number) {
        v = std::stoll(s);
      } else if (auto c = lib.m_int_constants.find(s); c != lib.m_int_constants.end()) {
        v = c->second;
      } else {
        return make_error(where(k) + "array size '" + s + "' is not an int constant defined before it");
      }
      if (v <= 0 || v > 4096) return make_error(where(k) + "array size " + std::to_string(v) + " is out of range");
      return static_cast<int>(v);
    };
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (t[k].kind != TokenKind::identifier) continue;
      if (reserved_in_shaders(t[k].text)) {
        return make_error(where(k) + "'" + t[k].text + "' is a reserved word in GLSL or HLSL: name it otherwise");
      }
      info.uses.insert(t[k].text);
    }
    int depth = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      const std::string& s = t[k].text;
      if (s == "{") {
        ++depth;
        continue;
      }
      if (s == "}") {
        --depth;
        continue;
      }
      if (depth != 0) continue;
      if (s == "struct") {
        StructDecl decl;
        decl.name = text_at(k + 1);
        if (text_at(k + 2) != "{") return make_error(where(k) + "expected '{' after struct " + decl.name);
        if (auto ok = define(decl.name, k); !ok) return ok.error();
        std::size_t j = k + 3;
        while (j < t.size() && t[j].text != "}") {
          StructField field;
          field.type_name = text_at(j);
          const auto type = field_type(field.type_name);
          if (!type) {
            // A struct member of struct type (a State holding its Params) is fine; it is never baked.
            field.type = FieldType::real;
          } else {
            field.type = *type;
          }
          field.name = text_at(j + 1);
          j += 2;
          if (text_at(j) == "[") {
            auto size = resolve_size(j + 1);
            if (!size) return size.error();
            field.array_size = *size;
            if (text_at(j + 2) != "]") return make_error(where(j) + "expected ']'");
            j += 3;
          }
          if (text_at(j) != ";") return make_error(where(j) + "expected ';' after field " + field.name);
          ++j;
          if (!type) field.type_name = "struct:" + field.type_name;
          decl.fields.push_back(std::move(field));
        }
        lib.m_structs[decl.name] = std::move(decl);
        k = j;  // at the closing brace (depth stays 0)
        continue;
      }
      if (s == "const") {
        const std::string& type = text_at(k + 1);
        const std::string& name = text_at(k + 2);
        if (auto ok = define(name, k); !ok) return ok.error();
        if (type == "int" && text_at(k + 3) == "=" && k + 4 < t.size() && t[k + 4].kind == TokenKind::number) {
          lib.m_int_constants[name] = std::stoll(t[k + 4].text);
        }
        while (k < t.size() && t[k].text != ";") {
          if (t[k].text == "{") ++depth;
          if (t[k].text == "}") --depth;
          ++k;
        }
        continue;
      }
      if (s == "inline") continue;
      // A function definition: TYPE NAME ( ... ) { ... }
      if (t[k].kind == TokenKind::identifier && k + 2 < t.size() && t[k + 1].kind == TokenKind::identifier &&
          t[k + 2].text == "(") {
        const std::string& name = t[k + 1].text;
        if (auto ok = define(name, k); !ok) return ok.error();
        const std::string suffix = "_prepare";
        if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
          lib.m_prepare_parameter[name.substr(0, name.size() - suffix.size())] = text_at(k + 3);
        }
        k += 2;
        continue;
      }
    }
    if (depth != 0) return make_error("kernel " + file.name + ": unbalanced braces");
    for (const std::string& name : info.defines) lib.m_defined_in[name] = f;
    lib.m_info.push_back(std::move(info));
  }
  // Dependency order: every name a file uses that another file defines must come from an earlier file.
  for (std::size_t f = 0; f < lib.m_files.size(); ++f) {
    for (const std::string& name : lib.m_info[f].uses) {
      const auto g = lib.defining_file(name);
      if (g && *g > f) {
        return make_error("kernel " + lib.m_files[f].name + " uses '" + name + "', defined in the later file " +
                          lib.m_files[*g].name + " (list the files in dependency order)");
      }
    }
  }
  return lib;
}

KernelFile ggx_energy_table_file() {
  // The C++ fetches (kernels.h) read the tables tables.cpp computes by quadrature at first use; a shader reads
  // the same numbers from the uniform block the exporter declares (ggx_energy_block_declaration). A table of
  // constants in the code would be simpler to use, but lavapipe lowers every dynamically indexed read of a
  // 2048-entry constant or global array on its own: the Kulla-Conty GGX pipeline (some 160 reads) then takes
  // minutes to build, against a second from a uniform block.
  std::string text =
      "// ggx_energy_tables.sl, written by the shader exporter (tools/shaders/kernel_library.cpp): the texel\n"
      "// fetches of ggx_energy.sl from the uniform block " +
      std::string(kGgxEnergyBlock) + " (vec4 " + kGgxEnergyMember + "[" + std::to_string(kGgxEnergyVec4s) +
      "]: the " + std::to_string(kGgxEnergyTexels) + " texels of E(mu, alpha), then the " +
      std::to_string(kGgxEnergyAverages) + " averages E_avg(alpha), four to a vec4).\n";
  text += "inline real ggx_energy_texel(int g, int row, int col) {\n  int i = (g * 32 + row) * 32 + col;\n  return " +
          std::string(kGgxEnergyMember) + "[i / 4][i % 4];\n}\n";
  text += "inline real ggx_energy_average_texel(int g, int row) {\n  int i = " + std::to_string(kGgxEnergyTexels) +
          " + g * 32 + row;\n  return " + std::string(kGgxEnergyMember) + "[i / 4][i % 4];\n}\n";
  return {kGgxEnergyTableFile, text};
}

std::vector<std::uint8_t> ggx_energy_block_data() {
  std::vector<float> v;
  v.reserve(4 * kGgxEnergyVec4s);
  for (int i = 0; i < kGgxEnergyTexels; ++i) v.push_back(static_cast<float>(kernel::ggx_energy_texels()[i]));
  for (int i = 0; i < kGgxEnergyAverages; ++i) v.push_back(static_cast<float>(kernel::ggx_energy_average_texels()[i]));
  v.resize(4 * kGgxEnergyVec4s, 0.0f);
  std::vector<std::uint8_t> bytes(v.size() * sizeof(float));
  std::memcpy(bytes.data(), v.data(), bytes.size());  // little-endian, as every GPU API uploads it
  return bytes;
}

namespace {

// A uniform block of n vec4 named `block` with the one member `member` (std140), declared for lang.
std::string table_block_declaration(Lang lang, const std::string& what, const char* block, const char* member, int vec4s) {
  const std::string n = std::to_string(vec4s);
  std::string s =
      "// " + what + " as a uniform block the application fills once: " + n + " vec4 (std140, " +
      std::to_string(16 * vec4s) + " bytes), the bytes `shadelab shader MODEL --tables-out FILE` writes (docs/shaders.md).\n";
  if (lang == Lang::hlsl) {
    s += "// Define SHADELAB_TABLES_LAYOUT before this file to bind it, e.g. [[vk::binding(3)]] (or add a register).\n"
         "#ifndef SHADELAB_TABLES_LAYOUT\n#define SHADELAB_TABLES_LAYOUT\n#endif\n"
         "SHADELAB_TABLES_LAYOUT cbuffer " + std::string(block) + " {\n  float4 " + member + "[" + n + "];\n};\n";
  } else {
    s += "// Define SHADELAB_TABLES_LAYOUT before this file to add a binding, e.g. layout(std140, binding = 3).\n"
         "#ifndef SHADELAB_TABLES_LAYOUT\n#define SHADELAB_TABLES_LAYOUT layout(std140)\n#endif\n"
         "SHADELAB_TABLES_LAYOUT uniform " + std::string(block) + " {\n  vec4 " + member + "[" + n + "];\n};\n";
  }
  return s;
}

std::vector<std::uint8_t> float_bytes(std::vector<float> v) {
  std::vector<std::uint8_t> bytes(v.size() * sizeof(float));
  std::memcpy(bytes.data(), v.data(), bytes.size());  // little-endian, as every GPU API uploads it
  return bytes;
}

}  // namespace

std::string ggx_energy_block_declaration(Lang lang) {
  return table_block_declaration(lang, "The GGX energy tables", kGgxEnergyBlock, kGgxEnergyMember, kGgxEnergyVec4s);
}

KernelFile sheen_energy_table_file() {
  // As ggx_energy_table_file: the C++ fetch (kernels.h) reads the table tables.cpp computes at first use; a shader
  // reads the same numbers from the uniform block sheen_energy_block_declaration declares.
  std::string text =
      "// sheen_energy_tables.sl, written by the shader exporter (tools/shaders/kernel_library.cpp): the texel\n"
      "// fetch of sheen.sl from the uniform block " +
      std::string(kSheenEnergyBlock) + " (vec4 " + kSheenEnergyMember + "[" + std::to_string(kSheenEnergyVec4s) +
      "]: the " + std::to_string(kSheenEnergyTexels) + " texels of E(mu, r), charlie then ashikhmin, four to a vec4).\n";
  text += "inline real sheen_energy_texel(int v, int row, int col) {\n  int i = (v * 64 + row) * 32 + col;\n  return " +
          std::string(kSheenEnergyMember) + "[i / 4][i % 4];\n}\n";
  return {kSheenEnergyTableFile, text};
}

std::vector<std::uint8_t> sheen_energy_block_data() {
  std::vector<float> v;
  v.reserve(4 * kSheenEnergyVec4s);
  for (int i = 0; i < kSheenEnergyTexels; ++i) v.push_back(static_cast<float>(kernel::sheen_energy_texels()[i]));
  return float_bytes(std::move(v));
}

std::string sheen_energy_block_declaration(Lang lang) {
  return table_block_declaration(lang, "The sheen lobe's albedo table", kSheenEnergyBlock, kSheenEnergyMember,
                                 kSheenEnergyVec4s);
}

const KernelLibrary& KernelLibrary::embedded() {
  static const KernelLibrary lib = [] {
    std::vector<KernelFile> files;
    for (const auto& f : embedded_support_files()) files.push_back(f);
    files.push_back(ggx_energy_table_file());    // before ggx_energy.sl, which fetches from it
    files.push_back(sheen_energy_table_file());  // before sheen.sl
    for (const auto& f : embedded_kernel_files()) files.push_back(f);
    auto parsed = parse(std::move(files));
    if (!parsed) throw std::logic_error("embedded kernels: " + parsed.error().message);
    return std::move(parsed).value();
  }();
  return lib;
}

std::optional<std::size_t> KernelLibrary::defining_file(const std::string& name) const {
  const auto it = m_defined_in.find(name);
  if (it == m_defined_in.end()) return std::nullopt;
  return it->second;
}

std::vector<std::size_t> KernelLibrary::closure(const std::vector<std::string>& names) const {
  std::vector<bool> needed(m_files.size(), false);
  std::vector<std::size_t> stack;
  auto need = [&](const std::string& name) {
    const auto f = defining_file(name);
    if (f && !needed[*f]) {
      needed[*f] = true;
      stack.push_back(*f);
    }
  };
  for (const auto& n : names) need(n);
  while (!stack.empty()) {
    const std::size_t f = stack.back();
    stack.pop_back();
    for (const auto& used : m_info[f].uses) need(used);
  }
  std::vector<std::size_t> out;
  for (std::size_t f = 0; f < needed.size(); ++f) {
    if (needed[f]) out.push_back(f);
  }
  return out;
}

const StructDecl* KernelLibrary::find_struct(const std::string& name) const {
  const auto it = m_structs.find(name);
  return it == m_structs.end() ? nullptr : &it->second;
}

std::optional<std::string> KernelLibrary::prepare_parameter_type(const std::string& kernel) const {
  const auto it = m_prepare_parameter.find(kernel);
  if (it == m_prepare_parameter.end()) return std::nullopt;
  return it->second;
}

std::optional<long long> KernelLibrary::int_constant(const std::string& name) const {
  const auto it = m_int_constants.find(name);
  if (it == m_int_constants.end()) return std::nullopt;
  return it->second;
}

}  // namespace shadelab::shaders
