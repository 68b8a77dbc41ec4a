// shadelab convert shininess --from phong|blinn-phong|blinn-phong-modified --to ggx|beckmann --n N
//   [--metric cosine-l2|cube-root|log] [--json]
// The best-fit roughness for a Phong-family exponent and what the published mappings give beside it, each with its
// residual and its excess over the best fit (fit/shininess.h; docs/conversions.md).
//
// shadelab convert gltf IN.gltf|glb --out OUT.gltf|glb [--report] [--json] [--evaluations N]
// Every material with KHR_materials_pbrSpecularGlossiness becomes metallic-roughness with KHR_materials_specular
// and KHR_materials_ior, its factors fitted to the directional albedo (fit/gltf_convert.h); a textured spec-gloss
// material is converted texel by texel by the fast rule (convert_spec_gloss_fast) into four new PNG textures
// (beside OUT, or in a .glb's BIN chunk). IN is read by tinygltf (the whole file checked); the output is IN's JSON
// with the materials, extension lists and the new images/textures edited (everything else as it was), in IN's
// container (a .glb stays a .glb), written atomically with its PNGs as one set.
#include <fmt/core.h>
#include <tiny_gltf.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <tbb/parallel_for.h>
#include <algorithm>

#include "cli_common.h"
#include "shadelab/brdf/fresnel.h"
#include "shadelab/fit/gltf_convert.h"
#include "shadelab/fit/shininess.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/srgb.h"

namespace shadelab::cli {

namespace {

struct ShininessOptions {
  std::string from;
  std::string to = "ggx";
  double n = 0.0;
  std::string metric = "cosine-l2";
  bool json = false;
};

std::string shadowing_text(const ShininessConversion& c) {
  const std::string target = c.to == "ggx" ? "the target's Smith height-correlated G (GGX)" : "the target's Smith G (Beckmann)";
  return target + (c.from == "blinn-phong-microfacet" ? ", the source's Smith G (Blinn-Phong D)" : ", none in the source");
}

void run_shininess(const ShininessOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const FitMetric metric = unwrap(parse_fit_metric(o.metric));
  if (!std::isfinite(o.n)) throw UsageError("--n: not a finite number");
  work_begins();
  const ShininessConversion c = unwrap(convert_shininess(o.from, o.to, o.n, metric));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.json) {
    nlohmann::json maps = nlohmann::json::array();
    for (const auto& m : c.mappings) {
      nlohmann::json j = {{"name", m.name}, {"source", m.source}};
      if (m.alpha) {
        j["alpha"] = *m.alpha;
        j["roughness"] = std::sqrt(*m.alpha);
        j["residual"] = m.residual;
        j["relative_residual"] = m.relative_residual;
        j["excess"] = m.excess;
      } else {
        j["alpha"] = nullptr;
        j["roughness"] = nullptr;
        j["residual"] = nullptr;
        j["relative_residual"] = nullptr;
        j["excess"] = nullptr;
      }
      maps.push_back(j);
    }
    print_json({{"from", c.from},
                {"to", c.to},
                {"n", c.n},
                {"metric", fit_metric_name(c.metric)},
                {"alpha", c.alpha},
                {"roughness", std::sqrt(c.alpha)},
                {"residual", c.residual},
                {"relative_residual", c.relative_residual},
                {"at_bound", c.at_bound},
                {"fresnel", "none (F = 1) on both"},
                {"shadowing", shadowing_text(c)},
                {"mappings", maps},
                {"seconds", seconds}});
    return;
  }
  fmt::print("{} n = {:g} -> {}: best alpha {:.6g} (roughness {:.6g}), residual {:.6g} ({}; {:.1f}% of the lobe's own){}\n",
             c.from, c.n, c.to, c.alpha, std::sqrt(c.alpha), c.residual, fit_metric_name(c.metric), 100.0 * c.relative_residual,
             c.at_bound ? " [at the range's end]" : "");
  fmt::print("  Fresnel off (F = 1) on both; masking-shadowing: {}\n", shadowing_text(c));
  for (const auto& m : c.mappings) {
    if (!m.alpha) {
      fmt::print("  {:<8} undefined at n = {:g}   ({})\n", m.name, c.n, m.source);
      continue;
    }
    fmt::print("  {:<8} alpha {:<10.5g} residual {:<10.5g} ({:.1f}% of the lobe's own; excess {:+.1f}%)   ({})\n", m.name,
               *m.alpha, m.residual, 100.0 * m.relative_residual, 100.0 * m.excess, m.source);
  }
}


// ---- convert gltf ----

struct GltfOptions {
  std::string in;
  std::string out;
  bool report = false;
  bool json = false;
  int evaluations = 300;
  std::string peer;  // another converter's metallic-roughness result of IN, measured beside ours
};

constexpr const char* kSpecGloss = "KHR_materials_pbrSpecularGlossiness";
constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF" (glTF 2.0, "GLB File Format Specification")
constexpr std::uint32_t kChunkJson = 0x4E4F534A;
constexpr std::uint32_t kChunkBin = 0x004E4942;

std::uint32_t read_u32(const std::vector<char>& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);  // little-endian, as the GLB header is (x86 and ARM hosts)
  return v;
}
void append_u32(std::vector<char>& b, std::uint32_t v) {
  char c[4];
  std::memcpy(c, &v, 4);
  b.insert(b.end(), c, c + 4);
}

// A GLB's JSON chunk and the rest of the file after it (the BIN chunk, kept byte for byte).
struct Glb {
  std::string json;
  std::vector<char> rest;
};

Glb split_glb(const std::string& path, const std::vector<char>& b) {
  if (b.size() < 20 || read_u32(b, 0) != kGlbMagic) throw UsageError(path + ": not a GLB file (no glTF header)");
  const std::uint32_t length = read_u32(b, 8);
  const std::uint32_t json_length = read_u32(b, 12);
  if (length > b.size() || read_u32(b, 16) != kChunkJson || 20ull + json_length > length) {
    throw UsageError(path + ": GLB header: bad length or first chunk not JSON");
  }
  Glb g;
  g.json.assign(b.data() + 20, json_length);
  g.rest.assign(b.begin() + 20 + json_length, b.begin() + length);
  if (!g.rest.empty() && (g.rest.size() < 8 || read_u32(g.rest, 4) != kChunkBin)) {
    throw UsageError(path + ": GLB: the second chunk is not BIN");
  }
  return g;
}

std::vector<char> join_glb(std::string json, const std::vector<char>& rest) {
  while (json.size() % 4 != 0) json.push_back(' ');  // the JSON chunk is padded with spaces (GLB specification)
  std::vector<char> b;
  append_u32(b, kGlbMagic);
  append_u32(b, 2);
  append_u32(b, static_cast<std::uint32_t>(12 + 8 + json.size() + rest.size()));
  append_u32(b, static_cast<std::uint32_t>(json.size()));
  append_u32(b, kChunkJson);
  b.insert(b.end(), json.begin(), json.end());
  b.insert(b.end(), rest.begin(), rest.end());
  return b;
}

bool is_glb_path(const std::string& p) {
  std::string e = std::filesystem::path(p).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e == ".glb";
}

// The factor at `key` in `ext` (absent: the default), each number checked in [0, 1]; errors name the field.
std::vector<double> factor(const nlohmann::json& ext, const char* key, std::vector<double> fallback, const std::string& where) {
  if (!ext.contains(key)) return fallback;
  const nlohmann::json& v = ext[key];
  const std::string field = where + "." + key;
  std::vector<double> out;
  if (fallback.size() == 1 && v.is_number()) {
    out.push_back(v.get<double>());
  } else if (fallback.size() > 1 && v.is_array() && v.size() == fallback.size()) {
    for (const auto& x : v) {
      if (!x.is_number()) throw UsageError(field + ": expected " + std::to_string(fallback.size()) + " numbers in [0, 1]");
      out.push_back(x.get<double>());
    }
  } else {
    throw UsageError(field + (fallback.size() == 1 ? ": expected a number in [0, 1]"
                                                   : ": expected " + std::to_string(fallback.size()) + " numbers in [0, 1]"));
  }
  for (const double x : out) {
    if (!(x >= 0.0 && x <= 1.0)) throw UsageError(field + ": " + fmt::format("{:g}", x) + " is outside [0, 1]");
  }
  return out;
}

void remove_name(nlohmann::json& root, const char* list, const std::string& name) {
  if (!root.contains(list) || !root[list].is_array()) return;
  nlohmann::json kept = nlohmann::json::array();
  for (const auto& x : root[list]) {
    if (!(x.is_string() && x.get<std::string>() == name)) kept.push_back(x);
  }
  if (kept.empty()) {
    root.erase(list);
  } else {
    root[list] = kept;
  }
}

void add_name(nlohmann::json& root, const char* list, const std::string& name) {
  if (!root.contains(list) || !root[list].is_array()) root[list] = nlohmann::json::array();
  for (const auto& x : root[list]) {
    if (x.is_string() && x.get<std::string>() == name) return;
  }
  root[list].push_back(name);
}

// A number, or `fallback` when absent; errors name the field.
double number_or(const nlohmann::json& o, const char* key, double fallback, const std::string& where) {
  if (!o.is_object() || !o.contains(key)) return fallback;
  if (!o[key].is_number()) throw UsageError(where + "." + key + ": expected a number");
  return o[key].get<double>();
}
Rgb rgb_or(const nlohmann::json& o, const char* key, const Rgb& fallback, const std::string& where) {
  if (!o.is_object() || !o.contains(key)) return fallback;
  const nlohmann::json& v = o[key];
  if (!v.is_array() || v.size() < 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number()) {
    throw UsageError(where + "." + key + ": expected 3 numbers or more");
  }
  return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

// Material i of a metallic-roughness glTF as the gltf model's factors, glTF's defaults where absent.
MetalRoughFactors metal_rough_of(const nlohmann::json& root, std::size_t i, const std::string& file) {
  const std::string where = file + ": materials[" + std::to_string(i) + "]";
  if (!root.contains("materials") || !root["materials"].is_array() || i >= root["materials"].size()) {
    throw UsageError(where + ": no such material");
  }
  const nlohmann::json& m = root["materials"][i];
  const nlohmann::json none = nlohmann::json::object();
  const nlohmann::json& pbr = m.contains("pbrMetallicRoughness") ? m["pbrMetallicRoughness"] : none;
  const nlohmann::json& ext = m.contains("extensions") ? m["extensions"] : none;
  const nlohmann::json& spec = ext.contains("KHR_materials_specular") ? ext["KHR_materials_specular"] : none;
  const nlohmann::json& ior = ext.contains("KHR_materials_ior") ? ext["KHR_materials_ior"] : none;
  MetalRoughFactors f;
  f.base_color = rgb_or(pbr, "baseColorFactor", Rgb{1.0, 1.0, 1.0}, where + ".pbrMetallicRoughness");
  f.metallic = number_or(pbr, "metallicFactor", 1.0, where + ".pbrMetallicRoughness");
  f.roughness = number_or(pbr, "roughnessFactor", 1.0, where + ".pbrMetallicRoughness");
  f.specular = number_or(spec, "specularFactor", 1.0, where + ".extensions.KHR_materials_specular");
  f.specular_color = rgb_or(spec, "specularColorFactor", Rgb{1.0, 1.0, 1.0}, where + ".extensions.KHR_materials_specular");
  f.ior = number_or(ior, "ior", 1.5, where + ".extensions.KHR_materials_ior");
  return f;
}

nlohmann::json rgb_json(const Rgb& c) { return nlohmann::json::array({c.r, c.g, c.b}); }

// ---- textures ----

// A glTF file as read: its bytes, its container, its JSON, and the undecoded bytes of every image tinygltf could load
// (a file, a data URI or a buffer view); an image whose file is missing has no entry (tinygltf only warns).
struct GltfFile {
  bool glb = false;
  Glb container;
  nlohmann::json root;
  std::map<int, std::vector<unsigned char>> images;
};

bool capture_image(tinygltf::Image*, const int index, std::string*, std::string*, int, int, const unsigned char* bytes, int size,
                   void* user) {
  auto* images = static_cast<std::map<int, std::vector<unsigned char>>*>(user);
  if (bytes != nullptr && size > 0) (*images)[index] = std::vector<unsigned char>(bytes, bytes + size);
  return true;
}

GltfFile read_gltf_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw UsageError(path + ": cannot open");
  const std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  GltfFile g;
  g.glb = bytes.size() >= 4 && read_u32(bytes, 0) == kGlbMagic;
  if (g.glb != is_glb_path(path)) throw UsageError(path + ": the content is " + (g.glb ? "GLB" : "not GLB") + ", the name says otherwise");
  // tinygltf checks the whole file (accessors, buffers); images are captured, not decoded.
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(capture_image, &g.images);
  std::string err, warn;
  const std::string base = std::filesystem::path(path).parent_path().string();
  const bool ok = g.glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                      static_cast<unsigned int>(bytes.size()), base)
                        : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), base);
  if (!ok) {
    std::string e = err.empty() ? warn : err;
    for (char& c : e) if (c == '\n' || c == '\r') c = ' ';
    while (!e.empty() && e.back() == ' ') e.pop_back();
    throw UsageError(path + ": tinygltf: " + e);
  }
  if (g.glb) {
    g.container = split_glb(path, bytes);
  } else {
    g.container.json.assign(bytes.begin(), bytes.end());
  }
  g.root = nlohmann::json::parse(g.container.json, nullptr, false);
  if (g.root.is_discarded() || !g.root.is_object()) throw UsageError(path + ": the JSON is not an object");
  return g;
}

// A textureInfo of a material: the texture, its image (decoded), its texCoord, KHR_texture_transform and sampler.
struct TextureUse {
  std::string field;         // where it is, for messages
  int image = -1;
  int sampler = -1;          // -1: none
  int tex_coord = 0;
  nlohmann::json transform;  // KHR_texture_transform, null when absent
  Rgba8Image pixels;
};

std::string image_name(const nlohmann::json& root, int image) {
  const nlohmann::json& im = root["images"][static_cast<std::size_t>(image)];
  if (im.contains("uri") && im["uri"].is_string()) {
    const std::string uri = im["uri"].get<std::string>();
    return uri.rfind("data:", 0) == 0 ? std::string("a data URI") : "'" + uri + "'";
  }
  return "bufferView " + (im.contains("bufferView") ? im["bufferView"].dump() : std::string("?"));
}

std::optional<TextureUse> texture_use(const GltfFile& g, const nlohmann::json& owner, const char* key, const std::string& where,
                                      const std::string& file) {
  if (!owner.is_object() || !owner.contains(key)) return std::nullopt;
  TextureUse t;
  t.field = where + "." + key;
  const nlohmann::json& info = owner[key];
  if (!info.is_object() || !info.contains("index") || !info["index"].is_number_integer()) throw UsageError(t.field + ".index: expected an integer");
  const long long index = info["index"].get<long long>();
  if (!g.root.contains("textures") || index < 0 || index >= static_cast<long long>(g.root["textures"].size())) {
    throw UsageError(t.field + ".index: no texture " + std::to_string(index));
  }
  if (info.contains("texCoord")) {
    if (!info["texCoord"].is_number_integer() || info["texCoord"].get<long long>() < 0) throw UsageError(t.field + ".texCoord: expected an integer >= 0");
    t.tex_coord = info["texCoord"].get<int>();
  }
  if (info.contains("extensions") && info["extensions"].is_object() && info["extensions"].contains("KHR_texture_transform")) {
    t.transform = info["extensions"]["KHR_texture_transform"];
  }
  const nlohmann::json& tex = g.root["textures"][static_cast<std::size_t>(index)];
  if (!tex.contains("source") || !tex["source"].is_number_integer()) {
    throw UsageError(t.field + ": textures[" + std::to_string(index) + "] has no source (a PNG or JPEG image is needed)");
  }
  t.image = tex["source"].get<int>();
  if (t.image < 0 || !g.root.contains("images") || t.image >= static_cast<int>(g.root["images"].size())) {
    throw UsageError(t.field + ": textures[" + std::to_string(index) + "].source: no image " + std::to_string(t.image));
  }
  if (tex.contains("sampler") && tex["sampler"].is_number_integer()) t.sampler = tex["sampler"].get<int>();
  const std::string name = file + ": images[" + std::to_string(t.image) + "] (" + image_name(g.root, t.image) + ")";
  const auto it = g.images.find(t.image);
  if (it == g.images.end()) throw UsageError(name + ": cannot read the image (missing file?)");
  t.pixels = unwrap(decode_rgba8(it->second, name));
  return t;
}

// The converted textures of one material, in IN's texture coordinates.
struct TexturedMaterial {
  int width = 0, height = 0;
  TextureUse where;  // texCoord, transform and sampler the outputs take
  Rgba8Image base_color, metal_rough, specular, specular_color;
  std::vector<SpecGloss::Params> texel_sg;  // per texel (row-major)
  double max_difference = 0.0, mean_difference = 0.0, pr_max = 0.0, pr_mean = 0.0;
  std::size_t unique = 0;
  double seconds = 0.0;
};

// ((ior - 1)/(ior + 1))^2 at the written ior 1000 (brdf/fresnel.h): f0 = this x specularColor.
double out_f0_scale() { return f0_from_ior(1000.0); }

// The metallic-roughness factors a renderer reads at texel p of the outputs (codes decoded as glTF says: sRGB colour,
// linear data), with the factors run_gltf writes (metallic 0, roughness 1, specular 1, specularColor 1/out_f0_scale()).
MetalRoughFactors decoded_texel(const TexturedMaterial& t, std::size_t p) {
  const auto& lut = srgb8_to_linear_table();
  MetalRoughFactors m;
  for (int c = 0; c < 3; ++c) {
    m.base_color[c] = static_cast<double>(lut[t.base_color.rgba[4 * p + static_cast<std::size_t>(c)]]);
    m.specular_color[c] = static_cast<double>(lut[t.specular_color.rgba[4 * p + static_cast<std::size_t>(c)]]) / out_f0_scale();
  }
  m.metallic = 0.0;
  m.roughness = t.metal_rough.rgba[4 * p + 1] / 255.0;
  m.specular = t.specular.rgba[4 * p + 3] / 255.0;
  m.ior = 1000.0;
  return m;
}

TexturedMaterial convert_textured(const std::optional<TextureUse>& diffuse, const std::optional<TextureUse>& sg_tex,
                                  const std::vector<double>& df, const std::vector<double>& sf, double gf, const std::string& where) {
  const auto start = std::chrono::steady_clock::now();
  TexturedMaterial t;
  const TextureUse& first = diffuse ? *diffuse : *sg_tex;
  if (diffuse && sg_tex) {
    const TextureUse& a = *diffuse;
    const TextureUse& b = *sg_tex;
    const auto describe = [](const TextureUse& u) {
      return fmt::format("{}x{}, texCoord {}, sampler {}, transform {}", u.pixels.width, u.pixels.height, u.tex_coord, u.sampler,
                         u.transform.is_null() ? std::string("none") : u.transform.dump());
    };
    if (a.pixels.width != b.pixels.width || a.pixels.height != b.pixels.height || a.tex_coord != b.tex_coord ||
        a.sampler != b.sampler || a.transform != b.transform) {
      throw UsageError(where + ": diffuseTexture (" + describe(a) + ") and specularGlossinessTexture (" + describe(b) +
                       ") differ: converted only when they share size, texCoord, sampler and KHR_texture_transform");
    }
  }
  t.where = first;
  t.where.pixels = {};
  t.width = first.pixels.width;
  t.height = first.pixels.height;
  const std::size_t n = static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
  const auto& lut = srgb8_to_linear_table();
  // The key of a texel: the diffuse RGB codes and the specular-glossiness RGBA codes (diffuse alpha does not enter).
  std::vector<std::uint64_t> keys(n);
  for (std::size_t p = 0; p < n; ++p) {
    std::uint64_t k = 0;
    for (int c = 0; c < 3; ++c) k = (k << 8) | (diffuse ? diffuse->pixels.rgba[4 * p + static_cast<std::size_t>(c)] : 255u);
    for (int c = 0; c < 4; ++c) k = (k << 8) | (sg_tex ? sg_tex->pixels.rgba[4 * p + static_cast<std::size_t>(c)] : 255u);
    keys[p] = k;
  }
  std::vector<std::uint64_t> unique = keys;
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  t.unique = unique.size();
  // The material of a key: factor times texel (diffuse and specular sRGB-decoded, glossiness linear), as the
  // extension's README multiplies them.
  const auto material_of = [&](std::uint64_t k) {
    SpecGloss::Params sg;
    const int gloss = static_cast<int>(k & 0xFF);
    sg.glossiness = gf * (sg_tex ? gloss / 255.0 : 1.0);
    for (int c = 2; c >= 0; --c) {
      k >>= 8;
      sg.specular[c] = sf[static_cast<std::size_t>(c)] * (sg_tex ? static_cast<double>(lut[k & 0xFF]) : 1.0);
    }
    for (int c = 2; c >= 0; --c) {
      k >>= 8;
      sg.diffuse[c] = df[static_cast<std::size_t>(c)] * (diffuse ? static_cast<double>(lut[k & 0xFF]) : 1.0);
    }
    return sg;
  };
  struct Out {
    std::uint8_t base[3], rough, spec, f0[3];
    double ours, pr;
  };
  std::vector<Out> out(unique.size());
  (void)gltf_albedo_tables();
  tbb::parallel_for(std::size_t{0}, unique.size(), [&](std::size_t u) {
    const SpecGloss::Params sg = material_of(unique[u]);
    const MetalRoughFactors m = convert_spec_gloss_fast(sg).result;
    Out& o = out[u];
    for (int c = 0; c < 3; ++c) {
      o.base[c] = linear_to_srgb8(m.base_color[c]);
      o.f0[c] = linear_to_srgb8(std::min(out_f0_scale() * m.specular_color[c], 1.0));
    }
    o.rough = static_cast<std::uint8_t>(std::lround(std::clamp(m.roughness, 0.0, 1.0) * 255.0));
    o.spec = static_cast<std::uint8_t>(std::lround(std::clamp(m.specular, 0.0, 1.0) * 255.0));
    o.pr = table_albedo_difference(sg, pr1719_conversion(sg)).max;
  });
  for (Rgba8Image* im : {&t.base_color, &t.metal_rough, &t.specular, &t.specular_color}) {
    im->width = t.width;
    im->height = t.height;
    im->rgba.assign(4 * n, 255);
  }
  t.texel_sg.resize(n);
  std::vector<std::size_t> unique_of(n), first_texel(unique.size(), n);
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t u = static_cast<std::size_t>(std::lower_bound(unique.begin(), unique.end(), keys[p]) - unique.begin());
    unique_of[p] = u;
    if (first_texel[u] == n) first_texel[u] = p;
    const Out& o = out[u];
    for (std::size_t c = 0; c < 3; ++c) {
      t.base_color.rgba[4 * p + c] = o.base[c];
      t.specular_color.rgba[4 * p + c] = o.f0[c];
    }
    t.base_color.rgba[4 * p + 3] = diffuse ? diffuse->pixels.rgba[4 * p + 3] : 255;  // alpha: the diffuse texel's
    t.metal_rough.rgba[4 * p + 0] = 0;
    t.metal_rough.rgba[4 * p + 1] = o.rough;  // G: roughness
    t.metal_rough.rgba[4 * p + 2] = 0;        // B: metallic (0; metallicFactor 0 too)
    t.specular.rgba[4 * p + 3] = o.spec;      // A: specular
    t.texel_sg[p] = material_of(keys[p]);
  }
  // The report: what a renderer reads from the written codes, against each texel's spec-gloss material (tables).
  std::vector<double> ours(unique.size());
  tbb::parallel_for(std::size_t{0}, unique.size(), [&](std::size_t u) {
    ours[u] = table_albedo_difference(t.texel_sg[first_texel[u]], decoded_texel(t, first_texel[u])).max;
  });
  double sum = 0.0, sum_pr = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t u = unique_of[p];
    t.max_difference = std::max(t.max_difference, ours[u]);
    t.pr_max = std::max(t.pr_max, out[u].pr);
    sum += ours[u];
    sum_pr += out[u].pr;
  }
  t.mean_difference = n ? sum / static_cast<double>(n) : 0.0;
  t.pr_mean = n ? sum_pr / static_cast<double>(n) : 0.0;
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

// A file name as a glTF URI (RFC 3986: unreserved characters kept, the rest percent-encoded).
std::string uri_of(const std::string& name) {
  std::string out;
  for (const unsigned char c : name) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
      out.push_back(static_cast<char>(c));
    } else {
      out += fmt::format("%{:02X}", static_cast<unsigned>(c));
    }
  }
  return out;
}

nlohmann::json texture_info(int texture, const TextureUse& where) {
  nlohmann::json info = {{"index", texture}};
  if (where.tex_coord != 0) info["texCoord"] = where.tex_coord;
  if (!where.transform.is_null()) info["extensions"] = {{"KHR_texture_transform", where.transform}};
  return info;
}

// The peer's metallic-roughness material at texel p: factors times its textures' texels (which must have IN's size).
struct PeerMaterial {
  MetalRoughFactors factors;
  std::optional<TextureUse> base_color, metal_rough, specular, specular_color;
};

MetalRoughFactors peer_texel(const PeerMaterial& pm, std::size_t p) {
  const auto& lut = srgb8_to_linear_table();
  MetalRoughFactors m = pm.factors;
  if (pm.base_color) for (int c = 0; c < 3; ++c) m.base_color[c] *= static_cast<double>(lut[pm.base_color->pixels.rgba[4 * p + static_cast<std::size_t>(c)]]);
  if (pm.metal_rough) {
    m.roughness *= pm.metal_rough->pixels.rgba[4 * p + 1] / 255.0;
    m.metallic *= pm.metal_rough->pixels.rgba[4 * p + 2] / 255.0;
  }
  if (pm.specular) m.specular *= pm.specular->pixels.rgba[4 * p + 3] / 255.0;
  if (pm.specular_color) {
    for (int c = 0; c < 3; ++c) m.specular_color[c] *= static_cast<double>(lut[pm.specular_color->pixels.rgba[4 * p + static_cast<std::size_t>(c)]]);
  }
  return m;
}

PeerMaterial peer_material(const GltfFile& g, std::size_t i, const std::string& file, int width, int height) {
  PeerMaterial pm;
  pm.factors = metal_rough_of(g.root, i, file);
  const std::string where = file + ": materials[" + std::to_string(i) + "]";
  const nlohmann::json& m = g.root["materials"][i];
  const nlohmann::json none = nlohmann::json::object();
  const nlohmann::json& pbr = m.contains("pbrMetallicRoughness") ? m["pbrMetallicRoughness"] : none;
  const nlohmann::json& ext = m.contains("extensions") ? m["extensions"] : none;
  const nlohmann::json& spec = ext.contains("KHR_materials_specular") ? ext["KHR_materials_specular"] : none;
  pm.base_color = texture_use(g, pbr, "baseColorTexture", where + ".pbrMetallicRoughness", file);
  pm.metal_rough = texture_use(g, pbr, "metallicRoughnessTexture", where + ".pbrMetallicRoughness", file);
  pm.specular = texture_use(g, spec, "specularTexture", where + ".extensions.KHR_materials_specular", file);
  pm.specular_color = texture_use(g, spec, "specularColorTexture", where + ".extensions.KHR_materials_specular", file);
  for (const auto* t : {&pm.base_color, &pm.metal_rough, &pm.specular, &pm.specular_color}) {
    if (*t && ((*t)->pixels.width != width || (*t)->pixels.height != height)) {
      throw UsageError((*t)->field + ": " + std::to_string((*t)->pixels.width) + "x" + std::to_string((*t)->pixels.height) +
                       ", IN's textures are " + std::to_string(width) + "x" + std::to_string(height) + " (compared texel by texel)");
    }
  }
  return pm;
}

void run_gltf(const GltfOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (o.evaluations < 0) throw UsageError("--evaluations: must be 0 or more");
  check_outputs({{"IN", o.in}}, {{"--out", o.out}});
  if (is_glb_path(o.in) != is_glb_path(o.out)) {
    throw UsageError("--out " + o.out + ": must have IN's container (" + (is_glb_path(o.in) ? ".glb" : ".gltf") + ")");
  }
  GltfFile in = read_gltf_file(o.in);
  const bool glb = in.glb;
  nlohmann::json& root = in.root;

  // Check every spec-gloss material (and decode its textures) before any work.
  struct Job {
    std::size_t index;
    std::string name;
    std::string where;
    SpecGloss::Params sg;
    double alpha;
    std::vector<double> df, sf;
    std::optional<TextureUse> diffuse, sg_tex;
  };
  std::vector<Job> jobs;
  if (root.contains("materials") && root["materials"].is_array()) {
    for (std::size_t i = 0; i < root["materials"].size(); ++i) {
      const nlohmann::json& m = root["materials"][i];
      if (!m.is_object() || !m.contains("extensions") || !m["extensions"].is_object() || !m["extensions"].contains(kSpecGloss)) continue;
      const std::string where = o.in + ": materials[" + std::to_string(i) + "].extensions." + kSpecGloss;
      const nlohmann::json& e = m["extensions"][kSpecGloss];
      if (!e.is_object()) throw UsageError(where + ": expected an object");
      const std::vector<double> d = factor(e, "diffuseFactor", {1, 1, 1, 1}, where);
      const std::vector<double> s = factor(e, "specularFactor", {1, 1, 1}, where);
      const std::vector<double> g = factor(e, "glossinessFactor", {1}, where);
      Job j{i, m.contains("name") && m["name"].is_string() ? m["name"].get<std::string>() : "", where, {}, d[3], d, s, {}, {}};
      j.sg.diffuse = Rgb{d[0], d[1], d[2]};
      j.sg.specular = Rgb{s[0], s[1], s[2]};
      j.sg.glossiness = g[0];
      j.diffuse = texture_use(in, e, "diffuseTexture", where, o.in);
      j.sg_tex = texture_use(in, e, "specularGlossinessTexture", where, o.in);
      jobs.push_back(std::move(j));
    }
  }
  GltfFile peer;
  if (!o.peer.empty()) {
    peer = read_gltf_file(o.peer);
    for (const Job& j : jobs) (void)metal_rough_of(peer.root, j.index, o.peer);
  }
  work_begins();

  GltfConvertOptions copts;
  copts.max_evaluations = o.evaluations;
  nlohmann::json report = nlohmann::json::array();
  // The new PNGs: (file name, bytes); their images/textures entries are appended to the JSON.
  std::vector<std::pair<std::string, std::vector<char>>> pngs;
  const std::filesystem::path out_path(o.out);
  const std::string stem = out_path.stem().string();
  if (!root.contains("images") || !root["images"].is_array()) root["images"] = nlohmann::json::array();
  if (!root.contains("textures") || !root["textures"].is_array()) root["textures"] = nlohmann::json::array();
  bool any_transform = false;
  for (const Job& j : jobs) {
    nlohmann::json& m = root["materials"][j.index];
    if (j.diffuse || j.sg_tex) {
      const TexturedMaterial t = convert_textured(j.diffuse, j.sg_tex, j.df, j.sf, j.sg.glossiness, j.where);
      const auto add_texture = [&](const char* what, const Rgba8Image& image) {
        const std::string file = stem + "_m" + std::to_string(j.index) + "_" + what + ".png";
        pngs.emplace_back(file, unwrap(encode_png_rgba8(image, out_path.parent_path() / file)));
        nlohmann::json im = {{"name", file}};
        if (!glb) im["uri"] = uri_of(file);  // a .glb's images get their bufferView when the BIN chunk is written
        root["images"].push_back(im);
        nlohmann::json tex = {{"source", root["images"].size() - 1}};
        if (t.where.sampler >= 0) tex["sampler"] = t.where.sampler;
        root["textures"].push_back(tex);
        return texture_info(static_cast<int>(root["textures"].size() - 1), t.where);
      };
      any_transform = any_transform || !t.where.transform.is_null();
      m["pbrMetallicRoughness"] = {{"baseColorFactor", {1.0, 1.0, 1.0, j.alpha}},
                                   {"baseColorTexture", add_texture("base_color", t.base_color)},
                                   {"metallicFactor", 0.0},
                                   {"roughnessFactor", 1.0},
                                   {"metallicRoughnessTexture", add_texture("metallic_roughness", t.metal_rough)}};
      m["extensions"].erase(kSpecGloss);
      m["extensions"]["KHR_materials_specular"] = {{"specularFactor", 1.0},
                                                   {"specularTexture", add_texture("specular", t.specular)},
                                                   {"specularColorFactor", rgb_json(Rgb{1.0, 1.0, 1.0} * (1.0 / out_f0_scale()))},
                                                   {"specularColorTexture", add_texture("specular_color", t.specular_color)}};
      m["extensions"]["KHR_materials_ior"] = {{"ior", 1000.0}};
      nlohmann::json r = {{"index", j.index},
                          {"name", j.name},
                          {"textured", true},
                          {"width", t.width},
                          {"height", t.height},
                          {"unique_texels", t.unique},
                          {"max_albedo_difference", t.max_difference},
                          {"mean_albedo_difference", t.mean_difference},
                          {"pr1719_max_albedo_difference", t.pr_max},
                          {"pr1719_mean_albedo_difference", t.pr_mean},
                          {"seconds", t.seconds}};
      if (!o.peer.empty()) {
        const PeerMaterial pm = peer_material(peer, j.index, o.peer, t.width, t.height);
        std::vector<double> diff(t.texel_sg.size());
        tbb::parallel_for(std::size_t{0}, diff.size(),
                          [&](std::size_t p) { diff[p] = table_albedo_difference(t.texel_sg[p], peer_texel(pm, p)).max; });
        double mx = 0.0, sum = 0.0;
        for (const double x : diff) {
          mx = std::max(mx, x);
          sum += x;
        }
        r["peer_max_albedo_difference"] = mx;
        r["peer_mean_albedo_difference"] = diff.empty() ? 0.0 : sum / static_cast<double>(diff.size());
      }
      report.push_back(r);
      continue;
    }
    const GltfMaterialConversion c = convert_spec_gloss(j.sg, copts);
    const MetalRoughFactors& r = c.result;
    // The spec-gloss extension's fallback, if any, is replaced: its textures belonged to another conversion.
    m["pbrMetallicRoughness"] = {{"baseColorFactor", {r.base_color.r, r.base_color.g, r.base_color.b, j.alpha}},
                                 {"metallicFactor", r.metallic},
                                 {"roughnessFactor", r.roughness}};
    m["extensions"].erase(kSpecGloss);
    m["extensions"]["KHR_materials_specular"] = {{"specularFactor", r.specular}, {"specularColorFactor", rgb_json(r.specular_color)}};
    m["extensions"]["KHR_materials_ior"] = {{"ior", r.ior}};
    report.push_back({{"index", j.index},
                      {"name", j.name},
                      {"textured", false},
                      {"diffuse", rgb_json(j.sg.diffuse)},
                      {"specular", rgb_json(j.sg.specular)},
                      {"glossiness", j.sg.glossiness},
                      {"base_color", rgb_json(r.base_color)},
                      {"metallic", r.metallic},
                      {"roughness", r.roughness},
                      {"specular_factor", r.specular},
                      {"specular_color", rgb_json(r.specular_color)},
                      {"ior", r.ior},
                      {"max_albedo_difference", c.difference.max},
                      {"max_albedo_difference_rgb", rgb_json(c.difference.max_abs)},
                      {"rms_albedo_difference", c.difference.rms},
                      {"worst_theta_deg", c.difference.worst_theta_deg},
                      {"pr1719_max_albedo_difference", c.start_difference.max},
                      {"pr1719_rms_albedo_difference", c.start_difference.rms},
                      {"evaluations", c.evaluations}});
    if (!o.peer.empty()) {
      const AlbedoDifference p = albedo_difference(j.sg, metal_rough_of(peer.root, j.index, o.peer), copts);
      report.back()["peer_max_albedo_difference"] = p.max;
      report.back()["peer_rms_albedo_difference"] = p.rms;
    }
  }
  if (root["images"].empty()) root.erase("images");
  if (root["textures"].empty()) root.erase("textures");
  if (!jobs.empty()) {
    remove_name(root, "extensionsUsed", kSpecGloss);
    remove_name(root, "extensionsRequired", kSpecGloss);
    add_name(root, "extensionsUsed", "KHR_materials_specular");
    add_name(root, "extensionsUsed", "KHR_materials_ior");
    if (any_transform) add_name(root, "extensionsUsed", "KHR_texture_transform");
  }
  std::vector<std::pair<std::filesystem::path, std::vector<char>>> files;
  if (glb) {
    // The PNGs go into the BIN chunk (buffer 0, the GLB's own buffer), each at a 4-byte aligned offset.
    std::vector<char> bin;
    if (!in.container.rest.empty()) bin.assign(in.container.rest.begin() + 8, in.container.rest.begin() + 8 + read_u32(in.container.rest, 0));
    if (!pngs.empty()) {
      if (!root.contains("buffers") || !root["buffers"].is_array()) root["buffers"] = nlohmann::json::array();
      if (in.container.rest.empty()) {
        // No BIN chunk: a new buffer 0 for it, the others (all with a uri) shifted by one.
        root["buffers"].insert(root["buffers"].begin(), nlohmann::json{{"byteLength", 0}});
        if (root.contains("bufferViews")) {
          for (auto& v : root["bufferViews"]) v["buffer"] = v["buffer"].get<int>() + 1;
        }
      }
      if (!root.contains("bufferViews") || !root["bufferViews"].is_array()) root["bufferViews"] = nlohmann::json::array();
      std::size_t next = 0;
      for (auto& im : root["images"]) {
        if (!im.contains("name") || im.contains("uri") || im.contains("bufferView")) continue;
        while (next < pngs.size() && pngs[next].first != im["name"].get<std::string>()) ++next;
        if (next == pngs.size()) break;
        while (bin.size() % 4 != 0) bin.push_back(0);
        root["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", pngs[next].second.size()}});
        bin.insert(bin.end(), pngs[next].second.begin(), pngs[next].second.end());
        im["bufferView"] = root["bufferViews"].size() - 1;
        im["mimeType"] = "image/png";
      }
      while (bin.size() % 4 != 0) bin.push_back(0);
      root["buffers"][0]["byteLength"] = bin.size();
      in.container.rest.clear();
      append_u32(in.container.rest, static_cast<std::uint32_t>(bin.size()));
      append_u32(in.container.rest, kChunkBin);
      in.container.rest.insert(in.container.rest.end(), bin.begin(), bin.end());
    }
  } else {
    for (auto& [name, bytes] : pngs) files.emplace_back(out_path.parent_path() / name, std::move(bytes));
  }
  const std::string text = root.dump(2);
  files.emplace_back(o.out, glb ? join_glb(text, in.container.rest) : std::vector<char>(text.begin(), text.end()));
  unwrap(write_files_atomically(files));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.json) {
    print_json({{"in", o.in}, {"out", o.out}, {"converted", jobs.size()}, {"metric", "albedo over theta_o 0..80 step 10"},
                {"materials", report}, {"seconds", seconds}});
    return;
  }
  fmt::print("{}: {} spec-gloss material(s) -> metallic-roughness + KHR_materials_specular + KHR_materials_ior, {}\n", o.in,
             jobs.size(), o.out);
  if (!o.report) return;
  fmt::print("  max |directional albedo difference| over theta_o = 0..80 deg and RGB (fit: least RMS; textured: the\n"
             "  fast rule, max over texels as written, mean in brackets):\n");
  const bool with_peer = !o.peer.empty();
  fmt::print("  {:>3}  {:<20} {:>22} {:>22}{}  {}\n", "#", "name", "PR #1719", "fitted", with_peer ? fmt::format(" {:>22}", "peer") : "",
             "fitted factors");
  for (const auto& r : report) {
    const bool tex = r["textured"].get<bool>();
    const auto cell = [&](const char* max_key, const char* mean_key) {
      if (!r.contains(max_key)) return std::string();
      return tex ? fmt::format("{:.3e} ({:.2e})", r[max_key].get<double>(), r[mean_key].get<double>())
                 : fmt::format("{:.3e}", r[max_key].get<double>());
    };
    const std::string peer_cell = with_peer ? fmt::format(" {:>22}", cell("peer_max_albedo_difference", "peer_mean_albedo_difference")) : "";
    const std::string factors =
        tex ? fmt::format("textured {}x{} ({} unique texels)", r["width"].get<int>(), r["height"].get<int>(), r["unique_texels"].get<std::size_t>())
            : fmt::format("base ({:.4f}, {:.4f}, {:.4f}) metallic {:.4f} roughness {:.4f} specular {:.4f}", r["base_color"][0].get<double>(),
                          r["base_color"][1].get<double>(), r["base_color"][2].get<double>(), r["metallic"].get<double>(),
                          r["roughness"].get<double>(), r["specular_factor"].get<double>());
    fmt::print("  {:>3}  {:<20} {:>22} {:>22}{}  {}\n", r["index"].get<std::size_t>(), r["name"].get<std::string>(),
               cell("pr1719_max_albedo_difference", "pr1719_mean_albedo_difference"),
               cell("max_albedo_difference", "mean_albedo_difference"), peer_cell, factors);
  }
}

void add_convert_command(CLI::App& app, Command& command) {
  auto* sub = app.add_subcommand("convert", "convert legacy material parameters, with the conversion's error");
  sub->require_subcommand(1);
  auto o = std::make_shared<ShininessOptions>();
  auto* sh = sub->add_subcommand("shininess", "the best-fit roughness for a Phong-family exponent, beside the published mappings");
  sh->add_option("--from", o->from, "phong, blinn-phong, blinn-phong-modified or blinn-phong-microfacet")->required();
  sh->add_option("--to", o->to, "ggx or beckmann")->capture_default_str();
  sh->add_option("--n", o->n, "the exponent, in [1, 1e6]")->required();
  sh->add_option("--metric", o->metric, "cosine-l2, cube-root or log (fit/metric.h)")->capture_default_str();
  sh->add_flag("--json", o->json, "machine-readable output");
  sh->callback([o, &command] { command.run = [o] { run_shininess(*o); }; });
  auto g = std::make_shared<GltfOptions>();
  auto* gl = sub->add_subcommand("gltf", "KHR_materials_pbrSpecularGlossiness -> metallic-roughness + KHR_materials_specular + _ior");
  gl->add_option("IN", g->in, "the input .gltf or .glb")->required();
  gl->add_option("--out", g->out, "the output, in IN's container (.gltf or .glb)")->required();
  gl->add_flag("--report", g->report, "per material: the max directional-albedo difference, PR #1719's and the fit's (textured: over the texels, and the mean)");
  gl->add_flag("--json", g->json, "machine-readable output (with the report)");
  gl->add_option("--evaluations", g->evaluations, "BOBYQA's objective evaluations per material (0: the better of the two starts, no fit)")->capture_default_str();
  gl->add_option("--peer", g->peer, "another converter's result of IN (same material order): its difference beside ours");
  gl->callback([g, &command] { command.run = [g] { run_gltf(*g); }; });
}

}  // namespace

const CommandRegistration registration_convert(38, add_convert_command);

}  // namespace shadelab::cli
