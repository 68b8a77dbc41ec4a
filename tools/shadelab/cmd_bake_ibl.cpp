// shadelab bake ibl INPUT --out-dir DIR [--size N] [--levels L] [--format F] [--container ktx2|dds]
// [--mapping linear|filament] [--method sum|sampled] [--samples N] [--irradiance-size N] [--dfg-size N]
// [--multiscatter] [--units game|radiometric] [--json]: everything an engine loads for split-sum image-based lighting, in one
// directory, baked by the same code as the single commands:
//   specular.ktx2|dds  the GGX prefiltered cube (bake specular --lobe ggx), level 0 = the input at --size
//   irradiance.ktx2|dds the cosine-convolved irradiance cube (bake irradiance)
//   sh9.json           the SH9 coefficients and their convention (bake sh)
//   dfg.ktx2           the DFG table, RG16F (RGBA16F with --multiscatter) (bake dfg)
//   split_sum_lobes.json the lobe-matched lookup's table (envmap/specular/split_sum_lobes.h): where and how rough to read
//                      the specular cube for each of the split sum's two parts, per (N.V, roughness)
//   manifest.json      each file's container, format, size, levels, faces and the conventions
// Every file is computed and encoded first, then all are written as one step (write_files_atomically): a
// refusal or a failure leaves DIR as it was (a DIR this run created is removed again).
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bake_shared.h"
#include "cli_common.h"
#include "shadelab/envmap/base/dds.h"
#include "shadelab/envmap/base/ktx2.h"
#include "shadelab/envmap/base/texel_format.h"
#include "shadelab/envmap/diffuse/irradiance.h"
#include "shadelab/envmap/specular/split_sum_lobes.h"
#include "shadelab/image/image_io.h"

namespace shadelab::cli {
namespace {

namespace fs = std::filesystem;

// The lobe table as JSON: its axes and channels as the DFG table states them, the texels row-major.
nlohmann::json split_sum_lobes_json(const SplitSumLobeTable& t) {
  nlohmann::json texels = nlohmann::json::array();
  for (const SplitSumLobes& l : t.all()) texels.push_back({l.a.angle, l.a.roughness, l.b.angle, l.b.roughness});
  return {{"content", "the split sum's lobe-matched lookup (shadelab, envmap/specular/split_sum_lobes.h): for each part, the "
                      "direction and perceptual roughness at which to read the specular cube so that the read matches "
                      "the first moments (mean direction, spread) of that part's true lobe"},
          {"size", t.size()},
          {"x", "N.V = (i + 0.5) / size, column i"},
          {"y", "perceptual roughness r = (j + 0.5) / size, row j; alpha = r^2"},
          {"texel_order", "row-major: texel (i, j) is texels[j * size + i]"},
          {"channels", {"angle_a: radians from n toward R (F0 A part)", "roughness_a: perceptual roughness of its read",
                        "angle_b: radians from n toward R (B part)", "roughness_b"}},
          {"use", "bilinear between texel centres, clamped at the edges, but below the first row linear to the mirror "
                  "(angle acos(N.V), roughness 0); d_k = n cos(angle_k) + t sin(angle_k), t the unit vector along R - "
                  "(R.n) n (n when R = n); specular = F0 A prefiltered(d_A, lod(roughness_a)) + B prefiltered(d_B, "
                  "lod(roughness_b)), A and B from the DFG table, lod the specular cube's mip_mapping"},
          {"model", "GGX, height-correlated Smith G2, Schlick F, as the DFG table"},
          {"texels", texels}};
}

struct IblOptions {
  std::string input;
  std::string out_dir;
  int size = 128;
  int levels = 0;  // 0: down to 1 x 1
  std::string format = "rgba16f";
  std::string container = "ktx2";
  std::string mapping = "linear";
  int samples = 1024;
  std::string method = "sum";
  int irradiance_size = 32;
  int dfg_size = 64;
  bool multiscatter = false;
  std::string units = "game";
  bool json = false;
  bool progress = false;
  std::vector<std::string> given;
  bool has(const std::string& option) const { return std::find(given.begin(), given.end(), option) != given.end(); }
};

// The manifest entry of a cube file: container, format, faces, size, levels.
nlohmann::json cube_entry(const std::string& file, const std::string& container, TexelFormat f, int size,
                          std::size_t levels) {
  nlohmann::json e = {{"file", file}, {"container", container}, {"format", texel_format_name(f)},
                      {"faces", 6},   {"size", size},           {"levels", levels}};
  if (container == "ktx2") {
    e["vk_format"] = vk_format_name(f);
  } else {
    e["dxgi_format"] = dxgi_format_name(f);
  }
  return e;
}

void warn_encoding(const std::string& file, TexelFormat f, const TexelEncodeInfo& info) {
  if (info.clamped_values > 0) {
    warn(fmt::format("{}: {} values beyond the largest finite {} value were clamped to it", file, info.clamped_values,
                     texel_format_name(f)));
  }
  if (info.negative_values > 0) {
    warn(fmt::format("{}: {} negative (or NaN) values were written as 0 ({} is unsigned)", file, info.negative_values,
                     texel_format_name(f)));
  }
}

void run_ibl(const IblOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  // Options first, all of them, before anything is read or written.
  if (o.size < 1 || o.size > 2048 || (o.size & (o.size - 1)) != 0) {
    throw UsageError(fmt::format("--size: {} is not a power of two in [1, 2048]", o.size));
  }
  const int full_chain = static_cast<int>(std::log2(o.size)) + 1;
  if (o.has("--levels") && (o.levels < 1 || o.levels > full_chain)) {
    throw UsageError(fmt::format("--levels: {} is out of range [1, {}] for --size {} (log2(size) + 1 levels reach 1 x 1)",
                                 o.levels, full_chain, o.size));
  }
  const auto format = parse_texel_format(o.format);
  if (!format) throw UsageError("--format: '" + o.format + "' is not one of rgba16f | rgba32f | rg11b10f | rgb9e5");
  if (o.container != "ktx2" && o.container != "dds") {
    throw UsageError("--container: '" + o.container + "' is not one of ktx2 | dds");
  }
  if (o.mapping != "linear" && o.mapping != "filament") {
    throw UsageError("--mapping: '" + o.mapping + "' is not one of linear | filament");
  }
  const GgxRoughnessMapping mapping = parse_ggx_roughness_mapping(o.mapping);
  const GgxFilterMethod method = ggx_method_option(o.method, o.has("--method"), o.has("--samples"));
  check_range("--samples", true, o.samples, 1, 1 << 20);
  check_range("--irradiance-size", true, o.irradiance_size, 1, 1024);
  check_range("--dfg-size", true, o.dfg_size, 1, 4096);
  if (o.units != "game" && o.units != "radiometric") {
    throw UsageError("--units: '" + o.units + "' is not one of game | radiometric");
  }
  const RadianceUnits units = o.units == "game" ? RadianceUnits::game : RadianceUnits::radiometric;

  const fs::path dir(o.out_dir);
  std::error_code ec;
  const fs::file_status dir_status = fs::status(dir, ec);
  if (fs::exists(dir_status) && !fs::is_directory(dir_status)) {
    throw UsageError("--out-dir: '" + dir.string() + "' exists and is not a directory");
  }
  const std::string ext = "." + o.container;
  const std::string specular_file = "specular" + ext, irradiance_file = "irradiance" + ext;
  const std::vector<std::string> names = {specular_file, irradiance_file, "sh9.json", "dfg.ktx2", "split_sum_lobes.json",
                                          "manifest.json"};
  std::vector<NamedPath> outputs;
  for (const std::string& name : names) {
    const fs::path p = dir / name;
    const fs::file_status st = fs::symlink_status(p, ec);
    if (fs::exists(st) && !fs::is_regular_file(st)) {
      throw UsageError("--out-dir: '" + p.string() + "' exists and is not a regular file");
    }
    outputs.push_back({"--out-dir", p});
  }
  check_outputs({{"INPUT", o.input}}, outputs, OutputFolders::created);

  // Compute and encode everything.
  work_begins();
  const Image img = read_environment(o.input);
  const GgxPrefilteredCube chain =
      bake_ggx_chain(environment_cube_at(img, o.input, o.size), o.levels, mapping, method, o.samples, o.progress);
  const bool latlong = is_latlong_image(img);
  // As bake irradiance and bake sh: a lat-long over its own texels, a cross as its cube.
  const CubeMap irradiance = latlong ? irradiance_cube(img, o.irradiance_size, units)
                                     : irradiance_cube(environment_cube(img, o.input), o.irradiance_size, units);
  const Sh9 sh = latlong ? project_sh9(img) : project_sh9(environment_cube(img, o.input));
  DfgOptions dfg_options;
  dfg_options.size = o.dfg_size;
  dfg_options.multiscatter = o.multiscatter;
  const DfgTable dfg = bake_dfg(dfg_options);

  const SplitSumLobeTable& lobes = split_sum_lobe_table();
  const nlohmann::json lobes_json = split_sum_lobes_json(lobes);

  const nlohmann::json mip_mapping = ggx_mip_mapping_json(chain);
  const std::string irradiance_convention = units == RadianceUnits::game
                                                ? "E/pi: exit radiance of a white Lambert surface"
                                                : "E: irradiance, W/m^2 per unit of input radiance";
  TexelEncodeInfo specular_info, irradiance_info, dfg_info;
  auto encode_cubes = [&](const std::vector<CubeMap>& levels, const KtxMetadata& kv, TexelEncodeInfo* info) {
    return unwrap(o.container == "ktx2" ? encode_ktx2_cubemap(levels, *format, kv, info)
                                        : encode_dds_cubemap(levels, *format, info));
  };
  std::vector<char> specular_bytes =
      encode_cubes(chain.levels, ktx2_metadata("prefiltered specular radiance (GGX)", mip_mapping), &specular_info);
  std::vector<char> irradiance_bytes =
      encode_cubes({irradiance}, ktx2_metadata("irradiance, " + irradiance_convention), &irradiance_info);
  const Ktx2ImageFormat dfg_format = o.multiscatter ? Ktx2ImageFormat::rgba16f : Ktx2ImageFormat::rg16f;
  std::vector<char> dfg_bytes = unwrap(encode_ktx2_image(dfg_image(dfg), dfg_format, dfg_ktx2_metadata(o.multiscatter), &dfg_info));
  const nlohmann::json sh_json = sh9_json(sh, units, ShWindow::none, "none", nlohmann::json::array(), "d3dx");
  warn_encoding((dir / specular_file).string(), *format, specular_info);
  warn_encoding((dir / irradiance_file).string(), *format, irradiance_info);

  nlohmann::json specular_entry = cube_entry(specular_file, o.container, *format, o.size, chain.levels.size());
  specular_entry["content"] = "prefiltered specular radiance: level i holds the GGX lobe at perceptual roughness "
                              "roughness[i] of mip_mapping";
  specular_entry["units"] = "the input's radiance, unchanged (a constant environment stays that constant)";
  specular_entry["mip_mapping"] = mip_mapping;
  specular_entry["mip_mapping_recorded_in"] =
      o.container == "ktx2" ? "this manifest and the KTX 2 key/value data, key shadelab.mip_mapping (JSON)"
                            : "this manifest only (DDS holds no metadata)";
  specular_entry["clamped_values"] = specular_info.clamped_values;
  nlohmann::json irradiance_entry = cube_entry(irradiance_file, o.container, *format, o.irradiance_size, 1);
  irradiance_entry["content"] = "irradiance of the input, cosine-convolved per texel (brute force)";
  irradiance_entry["units"] = irradiance_convention;
  irradiance_entry["clamped_values"] = irradiance_info.clamped_values;
  nlohmann::json dfg_entry = {{"file", "dfg.ktx2"},
                              {"container", "ktx2"},
                              {"format", o.multiscatter ? "rgba16f" : "rg16f"},
                              {"vk_format", ktx2_image_vk_format_name(dfg_format)},
                              {"faces", 1},
                              {"size", dfg.size},
                              {"width", dfg.size},
                              {"height", dfg.size},
                              {"levels", 1},
                              {"content", "DFG table of the split sum (scale A and bias B of F0)"},
                              {"error", dfg.max_error_estimate},
                              {"error_meaning", std::string(dfg_error_meaning) + " (before half-float rounding)"}};
  dfg_entry.update(dfg_conventions_json(o.multiscatter));
  const nlohmann::json lobes_entry = {{"file", "split_sum_lobes.json"}, {"container", "json"}, {"size", lobes.size()},
                                      {"content", lobes_json["content"]}, {"use", lobes_json["use"]}};
  const nlohmann::json sh_entry = {{"file", "sh9.json"}, {"container", "json"}, {"order", 3}, {"coefficients", 9},
                                   {"units", sh_json["units"]}, {"content", "SH9 radiance and irradiance coefficients"}};

  nlohmann::json manifest = {
      {"generator", ktx2_writer_name},
      {"input", o.input},
      {"files",
       {{"specular", specular_entry}, {"irradiance", irradiance_entry}, {"sh9", sh_entry}, {"dfg", dfg_entry},
        {"split_sum_lobes", lobes_entry}}},
      {"conventions",
       {{"cube_faces", {"+X", "-X", "+Y", "-Y", "+Z", "-Z"}},
        {"cube_orientation", cube_convention_text},
        {"ktx2_orientation", "KTXorientation rd: s to the right, t down (row 0, first in memory, is t = 0)"},
        {"world_up", "+Y"},
        {"units",
         {{"radiance", "the input's, unchanged (specular cube, level 0 = the input)"},
          {"irradiance", irradiance_convention},
          {"convention", o.units}}},
        {"split_sum", "specular = prefiltered(R, lod = mip_mapping(r)) * (F0 A + B) with A, B from dfg at (N.V, r); "
                      "or, corrected (shadelab's default), F0 A prefiltered(d_A, lod(r_A)) + B prefiltered(d_B, lod(r_B)) "
                      "with d_k, r_k from split_sum_lobes; diffuse = albedo * irradiance (game units: no pi)"},
        {"dfg", dfg_conventions_json(o.multiscatter)},
        {"sh",
         {{"basis", sh_json["basis"]},
          {"normalisation", "orthonormal real SH (the integral of Y_i^2 over the sphere is 1; Y00 = 0.282095) with the "
                            "Condon-Shortley phase: Y1-1 = -0.488603 y, Y10 = 0.488603 z, Y11 = -0.488603 x, "
                            "Y2-1 = -1.092548 yz, Y21 = -1.092548 xz"},
          {"d3dx", "the D3DX convention: the basis, signs and order of D3DXSHEvalDirection (Sloan 2008, 'Stupid SH "
                   "Tricks'); radiance_coefficients are the projection D3DXSHProjectCubeMap computes (texel solid "
                   "angles)"},
          {"cmft", "the same basis, signs and order as cmft's (its first 9 of 25 coefficients); cmft's irradiance "
                   "applies band factors 1, 2/3, 1/4, as our game-unit irradiance_coefficients do"},
          {"filament", "Filament's CubemapSH uses the same basis functions and order; its shader-ready coefficients "
                       "(cmgen --sh-shader) also fold in each basis function's constant and sign, which ours do not: "
                       "multiply irradiance_coefficients[i] (game units) by Y_i's constant and sign to get them"},
          {"radiance_coefficients", "c_i = sum over texels of L Y_i dOmega"},
          {"irradiance_coefficients", sh_json["convention"]}}}}}};

  std::vector<std::pair<fs::path, std::vector<char>>> files;
  files.emplace_back(dir / specular_file, std::move(specular_bytes));
  files.emplace_back(dir / irradiance_file, std::move(irradiance_bytes));
  files.emplace_back(dir / "sh9.json", json_file_bytes(sh_json));
  files.emplace_back(dir / "dfg.ktx2", std::move(dfg_bytes));
  files.emplace_back(dir / "split_sum_lobes.json", json_file_bytes(lobes_json));
  files.emplace_back(dir / "manifest.json", json_file_bytes(manifest));  // last: a manifest names complete files

  // The directories this run creates, outermost first, so that a failed write removes them again.
  std::vector<fs::path> created;
  for (fs::path p = fs::absolute(dir, ec); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    created.insert(created.begin(), p);
    if (p == p.parent_path()) break;
  }
  fs::create_directories(dir, ec);
  if (ec) throw UsageError("--out-dir: cannot create '" + dir.string() + "': " + ec.message());
  // One output set (issue 40, finding 7): a kill -9 between the renames is completed by the next writer into
  // DIR; the cubes of the other container (an older bake with --container dds, say) go in the same step, since
  // the manifest names only this set's.
  PublishOptions publish;
  const std::string other_ext = o.container == "ktx2" ? ".dds" : ".ktx2";
  publish.remove_also = [other_ext](const fs::path& p) {
    const std::string name = p.filename().string();
    return name == "specular" + other_ext || name == "irradiance" + other_ext;
  };
  auto written = write_files_atomically(files, publish);
  if (!written) {
    for (auto it = created.rbegin(); it != created.rend(); ++it) fs::remove(*it, ec);  // only if empty
    throw UsageError(written.error().message);
  }
  if (o.json) {
    nlohmann::json j = manifest;
    j["out_dir"] = dir.string();
    j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    print_json(j);
  } else {
    fmt::print("wrote {}: {} (GGX, {} x {} faces, {} levels, {} mapping), {} ({} x {}), sh9.json, dfg.ktx2 ({} x {} {}), "
               "split_sum_lobes.json, manifest.json\n",
               dir.string(), specular_file, o.size, o.size, chain.levels.size(), o.mapping, irradiance_file,
               o.irradiance_size, o.irradiance_size, dfg.size, dfg.size, ktx2_image_vk_format_name(dfg_format));
  }
}

void add_bake_ibl(CLI::App& app, Command& command) {
  CLI::App* bake = app.get_subcommand("bake");
  auto o = std::make_shared<IblOptions>();
  auto* sub = bake->add_subcommand("ibl", "split-sum IBL in one directory: GGX specular cube, irradiance cube, SH9, "
                                          "DFG table, split-sum lobe table and manifest.json");
  sub->add_option("INPUT", o->input, "environment: lat-long (2:1) or cube cross (4:3, 3:4); EXR, HDR or PNG")->required();
  sub->add_option("--out-dir", o->out_dir, "output directory (created if missing)")->required();
  sub->add_option("--size", o->size, "face size of the specular cube (a power of two)")->capture_default_str();
  sub->add_option("--levels", o->levels, "specular mip levels, at most log2(size) + 1 (default: down to 1 x 1)");
  sub->add_option("--format", o->format, "texel format of the cubes: rgba16f, rgba32f, rg11b10f or rgb9e5")
      ->capture_default_str();
  sub->add_option("--container", o->container, "container of the cubes: ktx2 or dds")->capture_default_str();
  sub->add_option("--mapping", o->mapping, "roughness to level: linear (lod = r (L - 1)) or filament (lod = r (2 - r) (L - 1))")
      ->capture_default_str();
  sub->add_option("--method", o->method, "GGX prefilter: sum (the lobe summed over the input) or sampled (filtered "
                                         "importance sampling)")->capture_default_str();
  sub->add_option("--samples", o->samples, "GGX prefilter --method sampled: Hammersley half vectors per texel (given "
                                           "alone, it implies --method sampled)")->capture_default_str();
  sub->add_option("--irradiance-size", o->irradiance_size, "face size of the irradiance cube")->capture_default_str();
  sub->add_option("--dfg-size", o->dfg_size, "DFG table size N (N x N; quadrature, ~2.7 s for 32 on 2 cores)")
      ->capture_default_str();
  sub->add_flag("--multiscatter", o->multiscatter, "DFG as RGBA16F with the single-scattering albedo A + B");
  sub->add_option("--units", o->units, "irradiance and SH: game (E/pi) or radiometric (E)")->capture_default_str();
  sub->add_flag("--json", o->json, "print the manifest (with out_dir and seconds)");
  sub->add_flag("--progress", o->progress, "show the progress bar even when stderr is not a terminal");
  sub->callback([o, sub, &command] {
    o->given.clear();
    for (const CLI::Option* opt : sub->get_options()) {
      if (opt->count() > 0) o->given.push_back(opt->get_name());
    }
    command.run = [o] { run_ibl(*o); };
  });
}

}  // namespace

const CommandRegistration registration_bake_ibl(62, add_bake_ibl);

}  // namespace shadelab::cli
