// shadelab convert shininess --from phong|blinn-phong|blinn-phong-modified --to ggx|beckmann --n N
//   [--metric cosine-l2|cube-root|log] [--json]
// The best-fit roughness for a Phong-family exponent and what the published mappings give beside it, each with its
// residual and its excess over the best fit (fit/shininess.h; docs/conversions.md).
//
// shadelab convert gltf IN.gltf|glb --out OUT.gltf|glb [--report] [--json] [--evaluations N]
// Every material with KHR_materials_pbrSpecularGlossiness becomes metallic-roughness with KHR_materials_specular
// and KHR_materials_ior, its factors fitted to the directional albedo (fit/gltf_convert.h); textured spec-gloss
// materials are refused. IN is read by tinygltf (the whole file checked); the output is IN's JSON with the
// materials and extension lists edited (everything else, buffers and images included, as it was), in IN's
// container (a .glb stays a .glb), written atomically.
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

#include "cli_common.h"
#include "shadelab/fit/gltf_convert.h"
#include "shadelab/fit/shininess.h"
#include "shadelab/image/image_io.h"

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

// The JSON of a .gltf or .glb file.
nlohmann::json read_gltf_json(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw UsageError(path + ": cannot open");
  const std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const bool glb = bytes.size() >= 4 && read_u32(bytes, 0) == kGlbMagic;
  const std::string text = glb ? split_glb(path, bytes).json : std::string(bytes.begin(), bytes.end());
  nlohmann::json root = nlohmann::json::parse(text, nullptr, false);
  if (root.is_discarded() || !root.is_object()) throw UsageError(path + ": the JSON is not an object");
  return root;
}

nlohmann::json rgb_json(const Rgb& c) { return nlohmann::json::array({c.r, c.g, c.b}); }

void run_gltf(const GltfOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (o.evaluations < 0) throw UsageError("--evaluations: must be 0 or more");
  check_outputs({{"IN", o.in}}, {{"--out", o.out}});
  if (is_glb_path(o.in) != is_glb_path(o.out)) {
    throw UsageError("--out " + o.out + ": must have IN's container (" + (is_glb_path(o.in) ? ".glb" : ".gltf") + ")");
  }
  std::ifstream f(o.in, std::ios::binary);
  if (!f) throw UsageError(o.in + ": cannot open");
  const std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const bool glb = bytes.size() >= 4 && read_u32(bytes, 0) == kGlbMagic;
  if (glb != is_glb_path(o.in)) throw UsageError(o.in + ": the content is " + (glb ? "GLB" : "not GLB") + ", the name says otherwise");

  // tinygltf checks the whole file (accessors, buffers); images are not decoded.
  {
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(
        [](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) { return true; },
        nullptr);
    std::string err, warn;
    const std::string base = std::filesystem::path(o.in).parent_path().string();
    const bool ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                      static_cast<unsigned int>(bytes.size()), base)
                        : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), base);
    if (!ok) {
      std::string e = err.empty() ? warn : err;
      for (char& c : e) if (c == '\n' || c == '\r') c = ' ';
      while (!e.empty() && e.back() == ' ') e.pop_back();
      throw UsageError(o.in + ": tinygltf: " + e);
    }
  }
  Glb container;
  if (glb) {
    container = split_glb(o.in, bytes);
  } else {
    container.json.assign(bytes.begin(), bytes.end());
  }
  nlohmann::json root = nlohmann::json::parse(container.json, nullptr, false);
  if (root.is_discarded() || !root.is_object()) throw UsageError(o.in + ": the JSON is not an object");

  // Check every spec-gloss material before any work.
  struct Job {
    std::size_t index;
    std::string name;
    SpecGloss::Params sg;
    double alpha;
  };
  std::vector<Job> jobs;
  if (root.contains("materials") && root["materials"].is_array()) {
    for (std::size_t i = 0; i < root["materials"].size(); ++i) {
      const nlohmann::json& m = root["materials"][i];
      if (!m.is_object() || !m.contains("extensions") || !m["extensions"].is_object() || !m["extensions"].contains(kSpecGloss)) continue;
      const std::string where = o.in + ": materials[" + std::to_string(i) + "].extensions." + kSpecGloss;
      const nlohmann::json& e = m["extensions"][kSpecGloss];
      if (!e.is_object()) throw UsageError(where + ": expected an object");
      for (const char* tex : {"diffuseTexture", "specularGlossinessTexture"}) {
        if (e.contains(tex)) {
          throw UsageError(where + "." + tex + ": textured spec-gloss materials are not converted (factors only)");
        }
      }
      const std::vector<double> d = factor(e, "diffuseFactor", {1, 1, 1, 1}, where);
      const std::vector<double> s = factor(e, "specularFactor", {1, 1, 1}, where);
      const std::vector<double> g = factor(e, "glossinessFactor", {1}, where);
      Job j{i, m.contains("name") && m["name"].is_string() ? m["name"].get<std::string>() : "", {}, d[3]};
      j.sg.diffuse = Rgb{d[0], d[1], d[2]};
      j.sg.specular = Rgb{s[0], s[1], s[2]};
      j.sg.glossiness = g[0];
      jobs.push_back(j);
    }
  }
  nlohmann::json peer;
  if (!o.peer.empty()) {
    peer = read_gltf_json(o.peer);
    for (const Job& j : jobs) (void)metal_rough_of(peer, j.index, o.peer);
  }
  work_begins();

  GltfConvertOptions copts;
  copts.max_evaluations = o.evaluations;
  nlohmann::json report = nlohmann::json::array();
  for (const Job& j : jobs) {
    const GltfMaterialConversion c = convert_spec_gloss(j.sg, copts);
    nlohmann::json& m = root["materials"][j.index];
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
      const AlbedoDifference p = albedo_difference(j.sg, metal_rough_of(peer, j.index, o.peer), copts);
      report.back()["peer_max_albedo_difference"] = p.max;
      report.back()["peer_rms_albedo_difference"] = p.rms;
    }
  }
  if (!jobs.empty()) {
    remove_name(root, "extensionsUsed", kSpecGloss);
    remove_name(root, "extensionsRequired", kSpecGloss);
    add_name(root, "extensionsUsed", "KHR_materials_specular");
    add_name(root, "extensionsUsed", "KHR_materials_ior");
  }
  const std::string text = root.dump(2);
  const std::vector<char> out = glb ? join_glb(text, container.rest) : std::vector<char>(text.begin(), text.end());
  unwrap(write_file_atomically(o.out, out));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.json) {
    print_json({{"in", o.in}, {"out", o.out}, {"converted", jobs.size()}, {"metric", "albedo over theta_o 0..80 step 10"},
                {"materials", report}, {"seconds", seconds}});
    return;
  }
  fmt::print("{}: {} spec-gloss material(s) -> metallic-roughness + KHR_materials_specular + KHR_materials_ior, {}\n", o.in,
             jobs.size(), o.out);
  if (!o.report) return;
  fmt::print("  max |directional albedo difference| over theta_o = 0..80 deg and RGB (fit: least RMS):\n");
  const bool with_peer = !o.peer.empty();
  fmt::print("  {:>3}  {:<20} {:>12} {:>12}{}  {}\n", "#", "name", "PR #1719", "fitted", with_peer ? fmt::format(" {:>12}", "peer") : "",
             "fitted factors");
  for (const auto& r : report) {
    const std::string peer_cell = with_peer ? fmt::format(" {:>12.3e}", r["peer_max_albedo_difference"].get<double>()) : "";
    fmt::print("  {:>3}  {:<20} {:>12.3e} {:>12.3e}{}  base ({:.4f}, {:.4f}, {:.4f}) metallic {:.4f} roughness {:.4f} specular {:.4f}\n",
               r["index"].get<std::size_t>(), r["name"].get<std::string>(), r["pr1719_max_albedo_difference"].get<double>(),
               r["max_albedo_difference"].get<double>(), peer_cell, r["base_color"][0].get<double>(), r["base_color"][1].get<double>(),
               r["base_color"][2].get<double>(), r["metallic"].get<double>(), r["roughness"].get<double>(),
               r["specular_factor"].get<double>());
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
  gl->add_flag("--report", g->report, "per material: the max directional-albedo difference, PR #1719's and the fit's");
  gl->add_flag("--json", g->json, "machine-readable output (with the report)");
  gl->add_option("--evaluations", g->evaluations, "BOBYQA's objective evaluations per material (0: the better of the two starts, no fit)")->capture_default_str();
  gl->add_option("--peer", g->peer, "another converter's result of IN (same material order): its difference beside ours");
  gl->callback([g, &command] { command.run = [g] { run_gltf(*g); }; });
}

}  // namespace

const CommandRegistration registration_convert(38, add_convert_command);

}  // namespace shadelab::cli
