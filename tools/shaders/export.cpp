#include "export.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace shadelab::shaders {

std::string default_entry(std::string_view model) {
  std::string out = "brdf_";
  for (char c : model) out += c == '-' ? '_' : c;
  return out;
}

bool valid_entry_name(std::string_view name) {
  if (name.empty() || name.size() > 200) return false;
  if (!(std::isalpha(static_cast<unsigned char>(name[0])) != 0 || name[0] == '_')) return false;
  for (char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_')) return false;
  }
  return name.rfind("gl_", 0) != 0 && name.find("__") == std::string_view::npos;
}

std::string float_literal(double v) {
  const auto f = static_cast<float>(v);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(f));
  std::string s = buf;
  if (s.find_first_of(".eEn") == std::string::npos) return s + ".0";  // "50" -> "50.0"
  const auto e = s.find_first_of("eE");
  if (e != std::string::npos && s.find('.') == std::string::npos) s.insert(e, ".0");  // "1e-05" -> "1.0e-05"
  return s;
}

namespace {

std::string upper_identifier(std::string_view s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) != 0 ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : '_';
  return out;
}

std::size_t round_up(std::size_t x, std::size_t a) { return (x + a - 1) / a * a; }

// Checks a binding against the kernel's parameter struct: the same fields, by name, in order, of the same size.
Result<bool> check_binding(const StructDecl& decl, const KernelBinding& binding) {
  if (decl.fields.size() != binding.fields.size()) {
    return make_error("kernel binding of '" + binding.kernel + "' has " + std::to_string(binding.fields.size()) +
                      " fields, struct " + decl.name + " has " + std::to_string(decl.fields.size()));
  }
  for (std::size_t i = 0; i < decl.fields.size(); ++i) {
    const StructField& f = decl.fields[i];
    const KernelField& b = binding.fields[i];
    if (f.type_name.rfind("struct:", 0) == 0) {
      return make_error("struct " + decl.name + " field '" + f.name + "' is a struct: a parameter struct holds numbers only");
    }
    if (f.name != b.name) {
      return make_error("kernel binding of '" + binding.kernel + "' field " + std::to_string(i) + " is '" + b.name +
                        "', struct " + decl.name + " has '" + f.name + "' there");
    }
    if (static_cast<int>(b.values.size()) != f.scalar_count()) {
      return make_error("kernel binding of '" + binding.kernel + "' field '" + b.name + "' has " +
                        std::to_string(b.values.size()) + " values, struct " + decl.name + " needs " +
                        std::to_string(f.scalar_count()));
    }
    for (double v : b.values) {
      if (!std::isfinite(v)) return make_error("parameter field '" + b.name + "' is not finite");
      if ((f.type == FieldType::integer || f.type == FieldType::boolean) && v != std::floor(v)) {
        return make_error("kernel binding of '" + binding.kernel + "' field '" + b.name + "' must be an integer");
      }
    }
  }
  return true;
}

std::string value_text(const StructField& f, const std::vector<double>& v, std::size_t at, Lang lang) {
  switch (f.type) {
    case FieldType::integer: return std::to_string(static_cast<long long>(v[at]));
    case FieldType::boolean: return v[at] != 0.0 ? "true" : "false";
    case FieldType::real: return float_literal(v[at]);
    case FieldType::rgb:
    case FieldType::vec3:
      return type_name(f.type_name, lang) + "(" + float_literal(v[at]) + ", " + float_literal(v[at + 1]) + ", " +
             float_literal(v[at + 2]) + ")";
  }
  return "0";
}

std::string describe_params(const ModelInfo& info, const ParamValues& values) {
  std::ostringstream os;
  bool first = true;
  for (const auto& spec : info.params) {
    os << (first ? "" : ", ") << spec.name << " = ";
    first = false;
    switch (spec.kind) {
      case ParamKind::scalar: os << values.scalar(spec.name); break;
      case ParamKind::color: {
        const Rgb c = values.color(spec.name);
        os << c.r << "," << c.g << "," << c.b;
        break;
      }
      case ParamKind::choice: os << values.choice(spec.name); break;
      case ParamKind::file: os << values.file(spec.name); break;
      case ParamKind::lobes: {
        bool fg = true;
        for (const auto& g : values.lobes(spec.name)) {
          os << (fg ? "" : ";");
          fg = false;
          for (std::size_t i = 0; i < g.size(); ++i) os << (i ? "," : "") << g[i];
        }
        break;
      }
    }
  }
  return os.str();
}

// Wraps comment text to lines of at most ~110 characters, each starting with "// ".
std::string comment_block(const std::string& text) {
  std::string out;
  std::string line = "//";
  std::istringstream words(text);
  std::string w;
  while (words >> w) {
    if (line.size() + 1 + w.size() > 110 && line != "//") {
      out += line + "\n";
      line = "//";
    }
    line += " " + w;
  }
  return out + line + "\n";
}

}  // namespace

Result<std::vector<std::uint8_t>> pack_std140(const StructDecl& decl, const KernelBinding& binding,
                                              std::vector<UniformField>* layout) {
  if (auto ok = check_binding(decl, binding); !ok) return ok.error();
  std::vector<std::uint8_t> bytes;
  std::size_t offset = 0;
  if (layout != nullptr) layout->clear();
  auto put = [&](std::size_t at, const StructField& f, double v) {
    if (bytes.size() < at + 4) bytes.resize(at + 4, 0);
    if (f.type == FieldType::integer || f.type == FieldType::boolean) {
      const auto i = static_cast<std::int32_t>(v);
      std::memcpy(bytes.data() + at, &i, 4);
    } else {
      const auto x = static_cast<float>(v);
      std::memcpy(bytes.data() + at, &x, 4);
    }
  };
  for (std::size_t i = 0; i < decl.fields.size(); ++i) {
    const StructField& f = decl.fields[i];
    const std::vector<double>& v = binding.fields[i].values;
    const bool vector = f.type == FieldType::rgb || f.type == FieldType::vec3;
    const std::size_t components = vector ? 3 : 1;
    // std140 (OpenGL 4.5 core profile, section 7.6.2.2): scalars align to 4, a vec3 to 16 (size 12); array
    // elements have a stride of their size rounded up to 16.
    UniformField placed{f.name, 0, 0};
    if (f.array_size > 0) {
      offset = round_up(offset, 16);
      placed.offset = offset;
      placed.array_stride = 16;
      for (int e = 0; e < f.array_size; ++e) {
        for (std::size_t c = 0; c < components; ++c) put(offset + 16 * static_cast<std::size_t>(e) + 4 * c, f, v[static_cast<std::size_t>(e) * components + c]);
      }
      offset += 16 * static_cast<std::size_t>(f.array_size);
    } else {
      offset = round_up(offset, vector ? 16 : 4);
      placed.offset = offset;
      for (std::size_t c = 0; c < components; ++c) put(offset + 4 * c, f, v[c]);
      offset += 4 * components;
    }
    if (layout != nullptr) layout->push_back(placed);
  }
  bytes.resize(round_up(std::max<std::size_t>(offset, 1), 16), 0);  // a struct's size rounds up to 16
  return bytes;
}

std::string ibl_fetch_declarations(Lang lang) {
  std::string s =
      "// ---- the texel fetches of the split sum's files (`shadelab bake ibl`), read with texelFetch: no filtering,\n"
      "// the kernels below interpolate (seamlessly across cube faces) as the C++ does. Textures:\n"
      "//   shadelab_ggx_chain        specular.ktx2 as a 2D array texture: layer = face (+X, -X, +Y, -Y, +Z, -Z),\n"
      "//                             mip level i = chain level i (upload every level)\n"
      "//   shadelab_dfg              dfg.ktx2: R = A (scale of f0), G = B (bias)\n"
      "//   shadelab_split_sum_lobes  split_sum_lobes.json's texels[j * size + i] at (i, j): RGBA = angle_a,\n"
      "//                             roughness_a, angle_b, roughness_b (RGBA32F)\n"
      "// Define SHADELAB_IBL_FETCHES before this file and define cube_texel, cube_size, dfg_texel,\n"
      "// shadelab_dfg_size, split_sum_lobe_texel and shadelab_split_sum_lobe_size yourself to read other storage.\n";
  if (lang == Lang::hlsl) {
    s += "// Define SHADELAB_IBL_CHAIN_REGISTER, SHADELAB_IBL_DFG_REGISTER, SHADELAB_IBL_LOBES_REGISTER (e.g. : register(t4))\n"
         "// to bind them.\n"
         "#ifndef SHADELAB_IBL_FETCHES\n#define SHADELAB_IBL_FETCHES\n"
         "#ifndef SHADELAB_IBL_CHAIN_REGISTER\n#define SHADELAB_IBL_CHAIN_REGISTER\n#endif\n"
         "#ifndef SHADELAB_IBL_DFG_REGISTER\n#define SHADELAB_IBL_DFG_REGISTER\n#endif\n"
         "#ifndef SHADELAB_IBL_LOBES_REGISTER\n#define SHADELAB_IBL_LOBES_REGISTER\n#endif\n"
         "Texture2DArray<float4> shadelab_ggx_chain SHADELAB_IBL_CHAIN_REGISTER;\n"
         "Texture2D<float4> shadelab_dfg SHADELAB_IBL_DFG_REGISTER;\n"
         "Texture2D<float4> shadelab_split_sum_lobes SHADELAB_IBL_LOBES_REGISTER;\n"
         "float3 cube_texel(int cube, int face, int x, int y) { return shadelab_ggx_chain.Load(int4(x, y, face, cube)).rgb; }\n"
         "int cube_size(int cube) {\n  uint w, h, layers, levels;\n"
         "  shadelab_ggx_chain.GetDimensions(uint(cube), w, h, layers, levels);\n  return int(w);\n}\n"
         "float dfg_texel(int x, int y, int channel) { return shadelab_dfg.Load(int3(x, y, 0))[channel]; }\n"
         "int shadelab_dfg_size() {\n  uint w, h;\n  shadelab_dfg.GetDimensions(w, h);\n  return int(w);\n}\n"
         "float split_sum_lobe_texel(int x, int y, int channel) { return shadelab_split_sum_lobes.Load(int3(x, y, 0))[channel]; }\n"
         "int shadelab_split_sum_lobe_size() {\n  uint w, h;\n  shadelab_split_sum_lobes.GetDimensions(w, h);\n  return int(w);\n}\n"
         "#endif  // SHADELAB_IBL_FETCHES\n\n";
    return s;
  }
  s += "// Define SHADELAB_IBL_CHAIN_LAYOUT, SHADELAB_IBL_DFG_LAYOUT, SHADELAB_IBL_LOBES_LAYOUT (e.g. layout(binding = 4))\n"
       "// to bind them.\n"
       "#ifndef SHADELAB_IBL_FETCHES\n#define SHADELAB_IBL_FETCHES\n"
       "#ifndef SHADELAB_IBL_CHAIN_LAYOUT\n#define SHADELAB_IBL_CHAIN_LAYOUT\n#endif\n"
       "#ifndef SHADELAB_IBL_DFG_LAYOUT\n#define SHADELAB_IBL_DFG_LAYOUT\n#endif\n"
       "#ifndef SHADELAB_IBL_LOBES_LAYOUT\n#define SHADELAB_IBL_LOBES_LAYOUT\n#endif\n"
       "SHADELAB_IBL_CHAIN_LAYOUT uniform highp sampler2DArray shadelab_ggx_chain;\n"
       "SHADELAB_IBL_DFG_LAYOUT uniform highp sampler2D shadelab_dfg;\n"
       "SHADELAB_IBL_LOBES_LAYOUT uniform highp sampler2D shadelab_split_sum_lobes;\n"
       "vec3 cube_texel(int cube, int face, int x, int y) { return texelFetch(shadelab_ggx_chain, ivec3(x, y, face), cube).rgb; }\n"
       "int cube_size(int cube) { return textureSize(shadelab_ggx_chain, cube).x; }\n"
       "float dfg_texel(int x, int y, int channel) { return texelFetch(shadelab_dfg, ivec2(x, y), 0)[channel]; }\n"
       "int shadelab_dfg_size() { return textureSize(shadelab_dfg, 0).x; }\n"
       "float split_sum_lobe_texel(int x, int y, int channel) { return texelFetch(shadelab_split_sum_lobes, ivec2(x, y), 0)[channel]; }\n"
       "int shadelab_split_sum_lobe_size() { return textureSize(shadelab_split_sum_lobes, 0).x; }\n"
       "#endif  // SHADELAB_IBL_FETCHES\n\n";
  return s;
}

Result<std::string> kernel_section(const std::vector<std::string>& names, Lang lang) {
  const KernelLibrary& lib = KernelLibrary::embedded();
  std::string out;
  for (std::size_t f : lib.closure(names)) {
    const KernelFile& file = lib.files()[f];
    auto text = translate(file.text, lang, file.name);
    if (!text) return text.error();
    if (file.name == "cube.sl") out += ibl_fetch_declarations(lang);  // cube.sl and game_ibl.sl call the fetches
    const std::string guard = "SHADELAB_KERNEL_" + upper_identifier(file.name);
    out += "#ifndef " + guard + "\n#define " + guard + "\n// ---- kernels/" + file.name + "\n";
    if (file.name == kGgxEnergyTableFile) out += ggx_energy_block_declaration(lang);
    if (file.name == kSheenEnergyTableFile) out += sheen_energy_block_declaration(lang);
    out += *text;
    if (!out.empty() && out.back() != '\n') out += "\n";
    out += "#endif  // " + guard + "\n\n";
  }
  return out;
}

Result<ShaderExport> export_model(std::string_view model, const ParamAssignments& params, const ExportOptions& options) {
  const ModelInfo* info = find_brdf_model(model);
  if (info == nullptr) {
    auto r = make_brdf(model, params);  // the registry's message lists the models
    return r ? make_error("unknown model '" + std::string(model) + "'") : r.error();
  }
  auto values = parse_params(info->name, info->params, params);
  if (!values) return values.error();
  // Before the model is built: measured refuses to be built without its file, and has no shader with one.
  if (!info->no_shader.empty()) return make_error("model '" + info->name + "' has no shader: " + info->no_shader);
  auto brdf = info->create(*values);
  if (!brdf) return brdf.error();
  const std::optional<KernelBinding> binding = (*brdf)->kernel_binding();
  if (!binding && (*brdf)->is_stochastic()) {
    return make_error("model '" + info->name + "' has no shader: its eval is a Monte Carlo estimate (a random walk), " +
                      "the ground truth that shaders are measured against");
  }
  if (!binding && !info->no_shader.empty()) return make_error("model '" + info->name + "' has no shader: " + info->no_shader);
  if (!binding) throw std::logic_error("model " + info->name + " has no kernel binding (Brdf::kernel_binding)");

  const Lang lang = options.lang;
  const bool hlsl = lang == Lang::hlsl;
  const std::string v3 = hlsl ? "float3" : "vec3";
  ShaderExport ex;
  ex.entry = options.entry.empty() ? default_entry(info->name) : options.entry;
  if (!valid_entry_name(ex.entry)) return make_error("--entry: '" + ex.entry + "' is not a valid function name");

  const KernelLibrary& lib = KernelLibrary::embedded();
  const std::string& k = binding->kernel;
  const auto ptype = lib.prepare_parameter_type(k);
  if (!ptype) throw std::logic_error("model " + info->name + ": no kernel defines " + k + "_prepare");
  const StructDecl* decl = lib.find_struct(*ptype);
  if (decl == nullptr) throw std::logic_error("model " + info->name + ": no kernel defines struct " + *ptype);
  auto packed = pack_std140(*decl, *binding, &ex.uniform_layout);
  if (!packed) throw std::logic_error("model " + info->name + ": " + packed.error().message);
  ex.uniform_data = std::move(packed).value();
  ex.params_type = *ptype;
  ex.block_name = ex.entry + "_block";

  std::vector<std::string> names = {k + "_prepare",          k + "_eval",         "punctual_game",
                                     "punctual_radiometric",   "sh9_irradiance",    "sh9_irradiance_game",
                                     "sh9_irradiance_game_wrapped"};
  if (options.ibl) {
    if (!lib.defining_file(k + "_split_sum")) {
      return make_error("--ibl: the model '" + info->name + "' has no split-sum description (its kernel defines no " + k +
                        "_split_sum); the split sum is for " + split_sum_model_names());
    }
    names.push_back(k + "_split_sum");
    names.push_back("game_ibl_ambient");
    ex.ibl_entry = ex.entry + "_ambient_game";
  }
  auto kernels = kernel_section(names, lang);
  if (!kernels) return kernels.error();
  for (std::size_t f : lib.closure(names)) {
    const std::string& name = lib.files()[f].name;
    if (name != kGgxEnergyTableFile && name != kSheenEnergyTableFile) continue;
    if (!ex.tables_block.empty()) throw std::logic_error("model " + info->name + " reads two tables blocks");
    ex.tables_block = name == kGgxEnergyTableFile ? kGgxEnergyBlock : kSheenEnergyBlock;
    ex.tables_data = name == kGgxEnergyTableFile ? ggx_energy_block_data() : sheen_energy_block_data();
  }

  std::string& s = ex.text;
  s += "// shadelab: the BRDF model '" + info->name + "' for " + lang_display_name(lang) + ", " + info->summary + " (" +
       info->source + ").\n";
  if (!options.command.empty()) s += "// Made by: " + options.command + "\n";
  s += comment_block("Parameters: " + describe_params(*info, *values) +
                     (options.uniforms ? " (the values of this export; the shader reads them from the uniform block "
                                         "below)."
                                       : " (baked in as constants)."));
  s += comment_block(
      "Self-contained: no engine dependency. Local shading frame: normal = +Z, tangent = +X, bitangent = +Y; wi "
      "points toward the light, wo toward the viewer, both unit length. " +
      ex.entry + "(wi, wo) returns f_r in 1/sr without the cosine, 0 when either direction is on or below the "
      "horizon. Single precision: `shadelab shader verify` measures its difference from the C++ reference (double) "
      "on a real driver. The kernels below are shadelab's src/shadelab/kernels/*.sl, the text the C++ evaluates, "
      "translated token by token (docs/shaders.md).");
  if (lang == Lang::essl) s += "// GLSL ES: use with `precision highp float;` (mediump is too coarse for f_r).\n";
  if (!ex.tables_block.empty()) {
    s += comment_block(std::string("Tables: this model reads ") +
                       (ex.tables_block == kGgxEnergyBlock ? "the GGX energy tables" : "the sheen albedo table") +
                       " from the uniform block " + ex.tables_block +
                       " (declared with the kernels below); fill it once with the " +
                       std::to_string(ex.tables_data.size()) + " bytes `shadelab shader " + info->name +
                       " --lang " + lang_name(lang) + " --tables-out FILE` writes (the same for every model that reads it).");
  }
  s += "//\n// Entry points:\n";
  s += "//   " + v3 + " " + ex.entry + "(" + v3 + " wi, " + v3 + " wo)  f_r\n";
  s += "//   " + v3 + " " + ex.entry + "_punctual_game(" + v3 + " wi, " + v3 + " wo, " + v3 +
       " colour)  pi f c N.L, a light of game colour c (game units)\n";
  s += "//   " + v3 + " " + ex.entry + "_punctual_radiometric(" + v3 + " wi, " + v3 + " wo, " + v3 +
       " e_perp)  f E N.L, E the irradiance facing the light in W/m^2\n";
  s += "//   " + v3 + " sh9_irradiance_game(Sh9Coefficients sh, " + v3 +
       " n), sh9_irradiance(...), sh9_irradiance_game_wrapped(sh, n, w): SH9 irradiance\n";
  if (options.ibl) {
    s += "//   " + v3 + " " + ex.ibl_entry + "(" + v3 + " n, " + v3 +
         " v, Sh9Coefficients sh, int levels, int mapping)  environment lighting (game units) from the files of\n"
         "//     `shadelab bake ibl`: n the unit normal, v the unit direction to the viewer (world space), sh the\n"
         "//     radiance_coefficients of sh9.json, levels the specular chain's level count, mapping its\n"
         "//     shadelab.mip_mapping (GGX_MIP_MAPPING_LINEAR or GGX_MIP_MAPPING_FILAMENT); the textures below\n";
  }
  s += "\n";
  s += *kernels;

  s += "// ---- the model '" + info->name + "' and its parameters\n";
  if (options.uniforms) {
    if (hlsl) {
      s += "// A constant buffer the application fills (add `: register(bN)` as your engine binds it).\n";
      s += "cbuffer " + ex.block_name + " {\n  " + *ptype + " " + ex.entry + "_params;\n};\n";
    } else {
      s += "// A uniform block the application fills, std140 layout (docs/shaders.md lists the offsets); define\n"
           "// SHADELAB_PARAMS_LAYOUT before this file to add a binding, e.g. layout(std140, binding = 3).\n";
      s += "#ifndef SHADELAB_PARAMS_LAYOUT\n#define SHADELAB_PARAMS_LAYOUT layout(std140)\n#endif\n";
      s += "SHADELAB_PARAMS_LAYOUT uniform " + ex.block_name + " {\n  " + *ptype + " " + ex.entry + "_params;\n};\n";
    }
    s += "// Offsets (bytes) of the fields in the block:";
    for (const auto& f : ex.uniform_layout) {
      s += " " + f.name + " " + std::to_string(f.offset) + (f.array_stride ? " (stride 16)" : "") + ";";
    }
    s += "\n\n";
    s += v3 + " " + ex.entry + "(" + v3 + " wi, " + v3 + " wo) {\n  return " + k + "_eval(" + k + "_prepare(" + ex.entry +
         "_params), wi, wo);\n}\n\n";
  } else {
    s += *ptype + " " + ex.entry + "_params() {\n  " + *ptype + " p;\n";
    for (std::size_t i = 0; i < decl->fields.size(); ++i) {
      const StructField& f = decl->fields[i];
      const std::vector<double>& v = binding->fields[i].values;
      const std::size_t per = (f.type == FieldType::rgb || f.type == FieldType::vec3) ? 3 : 1;
      if (f.array_size > 0) {
        for (int e = 0; e < f.array_size; ++e) {
          s += "  p." + f.name + "[" + std::to_string(e) + "] = " + value_text(f, v, static_cast<std::size_t>(e) * per, lang) + ";\n";
        }
      } else {
        s += "  p." + f.name + " = " + value_text(f, v, 0, lang) + ";\n";
      }
    }
    s += "  return p;\n}\n\n";
    s += v3 + " " + ex.entry + "(" + v3 + " wi, " + v3 + " wo) {\n  return " + k + "_eval(" + k + "_prepare(" + ex.entry +
         "_params()), wi, wo);\n}\n\n";
  }
  if (options.ibl) {
    const std::string params_expr = ex.entry + (options.uniforms ? "_params" : "_params()");
    s += "// The split sum's lookup: SPLIT_SUM_LOOKUP_LOBES (shadelab's default and `render --mode game`'s), or define\n"
         "// SHADELAB_SPLIT_SUM_LOOKUP before this file as SPLIT_SUM_LOOKUP_MIRROR (Karis 2013 as published) or\n"
         "// SPLIT_SUM_LOOKUP_DOMINANT (neither reads shadelab_split_sum_lobes).\n"
         "#ifndef SHADELAB_SPLIT_SUM_LOOKUP\n#define SHADELAB_SPLIT_SUM_LOOKUP SPLIT_SUM_LOOKUP_LOBES\n#endif\n";
    s += "// Environment lighting in game units: SH9 diffuse plus the split-sum specular (kernels/game_ibl.sl).\n";
    s += v3 + " " + ex.ibl_entry + "(" + v3 + " n, " + v3 + " v, Sh9Coefficients sh, int levels, int mapping) {\n  return game_ibl_ambient(n, v, " +
         k + "_split_sum(" + k + "_prepare(" + params_expr + ")), sh9_irradiance_game(sh, n), SHADELAB_SPLIT_SUM_LOOKUP, levels,\n"
         "                          mapping, shadelab_dfg_size(), shadelab_split_sum_lobe_size());\n}\n\n";
  }
  s += "// Punctual light in game units: exit radiance pi f c N.L for a light of colour c from wi.\n";
  s += v3 + " " + ex.entry + "_punctual_game(" + v3 + " wi, " + v3 + " wo, " + v3 + " colour) {\n  return punctual_game(" +
       ex.entry + "(wi, wo), colour, wi.z);\n}\n\n";
  s += "// Punctual light in radiometric units: exit radiance f E N.L, E the irradiance facing the light (W/m^2).\n";
  s += v3 + " " + ex.entry + "_punctual_radiometric(" + v3 + " wi, " + v3 + " wo, " + v3 +
       " e_perp) {\n  return punctual_radiometric(" + ex.entry + "(wi, wo), e_perp, wi.z);\n}\n";
  return ex;
}

}  // namespace shadelab::shaders
