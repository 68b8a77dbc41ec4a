// shadelab bake irradiance|sh|specular|convert INPUT [--out FILE] [--size N] [--units game|radiometric]
// [--json]: environment lighting baked the way engines load it.
//
// An option that a subcommand does not use is refused (exit 2) rather than ignored; an output that is the
// input, or another output of the same command, is refused; a KTX output says how many values it clamped
// to the half-float range.
//
// Cube outputs choose their container by extension: .ktx2 (KTX 2.0), .ktx (KTX 1.1), .dds (DDS with the DX10
// header) hold the six faces (and the specular mip chain); .exr, .hdr, .pic, .png hold an image layout
// (--layout). --format chooses the texel format of the containers: rgba16f (default), rgba32f, rg11b10f,
// rgb9e5 (texel_format.h; .ktx holds the first two).
//
// bake specular --lobe phong (default) prefilters normalized Phong lobes (prefilter.h); --lobe ggx the GGX
// lobes of the split sum (prefilter_ggx.h), one perceptual roughness per level by --mapping linear|filament,
// level 0 = the input at --size, by --method sum (default: the lobe summed over the input texels, exactly near R
// and by cells far from it) or sampled (filtered importance sampling, --samples N; --samples alone implies it);
// the mapping goes into the KTX 2 key/value data (shadelab.mip_mapping) and
// --json (mip_mapping), the only record for .ktx, .dds and the EXR faces.
#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <iostream>

#include "bake_shared.h"
#include "cli_common.h"
#include "progress.h"
#include "shadelab/core/constants.h"
#include "shadelab/envmap/base/dds.h"
#include "shadelab/envmap/diffuse/irradiance.h"
#include "shadelab/envmap/base/ktx.h"
#include "shadelab/envmap/base/ktx2.h"
#include "shadelab/envmap/base/texel_format.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/envmap/specular/prefilter.h"
#include "shadelab/envmap/specular/prefilter_ggx.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/envmap/diffuse/sh_bands.h"
#include "shadelab/envmap/diffuse/sh_error.h"
#include "shadelab/envmap/diffuse/zh3.h"
#include "shadelab/image/image_io.h"

namespace shadelab::cli {

const char* const cube_convention_text =
    "faces +X, -X, +Y, -Y, +Z, -Z with the OpenGL / Vulkan cube map orientation (OpenGL 4.6 table 8.19), row 0 "
    "is t = 0; world +Y up";

KtxMetadata ktx2_metadata(const std::string& content, const nlohmann::json& mip_mapping) {
  KtxMetadata kv = {{"shadelab.content", content}, {"shadelab.cube_convention", cube_convention_text}};
  if (!mip_mapping.is_null()) kv.emplace_back("shadelab.mip_mapping", mip_mapping.dump());
  return kv;
}

namespace {

namespace fs = std::filesystem;

struct BakeOptions {
  std::string input;
  std::string out;
  int size = -1;  // -1: the command's default
  int input_size = -1;
  std::string units = "game";
  std::string layout = "hcross";
  std::string window = "none";
  int mips = 0;
  int levels = 0;                 // specular: --levels, the same as --mips
  std::string lobe = "phong";     // specular: phong | ggx
  std::string mapping = "linear";  // specular --lobe ggx: roughness-to-mip mapping
  int samples = 1024;              // specular --lobe ggx --method sampled: half vectors per texel
  std::string method = "sum";      // specular --lobe ggx: sum | sampled (GgxFilterMethod)
  std::string format = "rgba16f";  // texel format of .ktx2 / .ktx / .dds outputs
  double gloss_scale = 10.0;
  double gloss_bias = 1.0;
  bool exr_faces = false;  // bake specular: --exr-faces (issue 39: the one requested file by default)
  bool json = false;
  bool progress = false;
  std::vector<std::string> lights;         // sh: DIR[:COLOUR], game colour
  std::string light_normalization = "d3dx";  // sh: d3dx (16/17) or delta
  int bands = 3;                           // sh: --bands 2..5 (sh_bands.h)
  std::string zh3;                         // sh: --zh3 stored | hallucinated (zh3.h)
  bool error_report = false;               // sh: --error-report (sh_error.h)
  std::vector<std::string> given;          // the options given on the command line (set after parsing)
  bool has(const std::string& option) const { return std::find(given.begin(), given.end(), option) != given.end(); }
};

// Refuses each option of `options` that was given: it does not apply to `command`.
void refuse_options(const BakeOptions& o, const std::string& command, std::initializer_list<const char*> options,
                    const std::string& why) {
  for (const char* option : options) {
    if (o.has(option)) throw UsageError(std::string(option) + " does not apply to bake " + command + " (" + why + ")");
  }
}

// Refuses outputs that are the input or each other (real paths).
void check_bake_outputs(const BakeOptions& o, const std::vector<NamedPath>& outputs) {
  check_outputs({{"INPUT", o.input}}, outputs);
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool is_power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

// log2 of the largest (and of 1 / the smallest) prefiltered Phong exponent: 2^20, about the BRDF models' 1e6.
constexpr double max_gloss_log2 = 20.0;

void check_size(const std::string& option, int size, int max) {
  if (size < 1 || size > max) throw UsageError(fmt::format("{}: {} is out of range [1, {}]", option, size, max));
}


// Reads INPUT, radiance: a NaN, Inf or negative texel is bad input naming the file and the texel
// (read_radiance_image; it was a warning and a repair to 0 before issue 40).
Image read_environment_image(const BakeOptions& o) { return unwrap(read_radiance_image(o.input)); }

bool is_latlong(const Image& img) { return img.width == 2 * img.height; }

// Reads INPUT as a lat-long (2:1) or a cross (4:3 or 3:4) and returns a cube map.
CubeMap environment_to_cube(const BakeOptions& o, Image img) {
  if (is_latlong(img)) {
    int size = o.input_size;
    if (o.has("--input-size")) check_size("--input-size", size, 2048);
    if (!o.has("--input-size")) {  // about the lat-long's resolution: a face spans a quarter of its width
      size = 1;
      while (size * 2 <= std::min(512, img.width / 4)) size *= 2;
    }
    return latlong_to_cube(img, size);
  }
  auto cube = cube_from_cross(img);
  if (!cube) throw UsageError(o.input + ": " + cube.error().message + "; expected a 2:1 lat-long or a cube cross");
  return std::move(cube).value();
}

CubeMap load_environment(const BakeOptions& o) { return environment_to_cube(o, read_environment_image(o)); }

RadianceUnits parse_units(const std::string& u) {
  if (u == "game") return RadianceUnits::game;
  if (u == "radiometric") return RadianceUnits::radiometric;
  throw UsageError("--units: '" + u + "' is not one of game | radiometric");
}

fs::path default_out(const BakeOptions& o, const std::string& suffix) {
  const fs::path in(o.input);
  return in.parent_path() / (in.stem().string() + suffix);
}

// Says on stderr how many values a KTX (RGBA16F) output clamped to +-65504 (ktx.h).
void report_clamped(const fs::path& path, const KtxEncodeInfo& info) {
  if (info.clamped_values > 0) {
    warn(path.string() + ": " + std::to_string(info.clamped_values) +
         " values beyond the half-float range were clamped to +-65504 (RGBA16F)");
  }
}

bool is_ktx(const fs::path& path) { return lower(path.extension().string()) == ".ktx"; }
bool is_ktx2(const fs::path& path) { return lower(path.extension().string()) == ".ktx2"; }
bool is_dds(const fs::path& path) { return lower(path.extension().string()) == ".dds"; }
// A container that stores the six faces (and mip levels) rather than an image layout.
bool is_cube_container(const fs::path& path) { return is_ktx(path) || is_ktx2(path) || is_dds(path); }

// --format: the texel format of a container output (texel_format.h); refused for image outputs.
TexelFormat check_format(const BakeOptions& o, const fs::path& out) {
  const auto f = parse_texel_format(o.format);
  if (!f) throw UsageError("--format: '" + o.format + "' is not one of rgba16f | rgba32f | rg11b10f | rgb9e5");
  if (o.has("--format") && !is_cube_container(out)) {
    throw UsageError("--format applies to .ktx2, .ktx and .dds outputs, not '" + out.string() + "'");
  }
  if (is_ktx(out) && *f != TexelFormat::rgba16f && *f != TexelFormat::rgba32f) {
    throw UsageError("--format: a .ktx (KTX 1) output holds rgba16f or rgba32f; write .ktx2 or .dds for " + o.format);
  }
  return *f;
}

// The --layout applies to image outputs only; a .ktx, .ktx2 or .dds output stores the six faces.
void check_layout(const BakeOptions& o, const fs::path& out) {
  if (is_cube_container(out) && o.has("--layout")) {
    throw UsageError("--layout does not apply to a " + lower(out.extension().string()) + " output ('" + out.string() +
                     "' stores the six faces as a cube map)");
  }
  if (o.layout != "hcross" && o.layout != "vcross" && o.layout != "latlong") {
    throw UsageError("--layout: '" + o.layout + "' is not one of hcross | vcross | latlong");
  }
  if (!is_cube_container(out)) require_extension("--out", out, {".exr", ".hdr", ".pic", ".png", ".ktx", ".ktx2", ".dds"}, "the cube map");
  check_format(o, out);
}


// The bytes of a mip chain in a container chosen by extension (.ktx, .ktx2, .dds); warns about clamped values.
std::vector<char> encode_container(const std::vector<CubeMap>& levels, const fs::path& path, TexelFormat format,
                                   const KtxMetadata& metadata, std::uint64_t* clamped) {
  auto named = [&](Result<std::vector<char>> r) {
    if (!r) throw UsageError("'" + path.string() + "': " + r.error().message);
    return std::move(r).value();
  };
  TexelEncodeInfo info;
  if (is_ktx(path)) {
    KtxEncodeInfo k;
    std::vector<char> bytes =
        named(encode_ktx_cubemap(levels, format == TexelFormat::rgba32f ? KtxPixelType::float32 : KtxPixelType::half, &k));
    report_clamped(path, k);
    *clamped = k.clamped_values;
    return bytes;
  }
  std::vector<char> bytes = is_ktx2(path) ? named(encode_ktx2_cubemap(levels, format, metadata, &info))
                                          : named(encode_dds_cubemap(levels, format, &info));
  if (info.clamped_values > 0 && format == TexelFormat::rgba16f) {
    report_clamped(path, KtxEncodeInfo{info.clamped_values});
  } else if (info.clamped_values > 0) {
    warn(fmt::format("{}: {} values beyond the largest finite {} value were clamped to it", path.string(),
                     info.clamped_values, texel_format_name(format)));
  }
  if (info.negative_values > 0) {
    warn(fmt::format("{}: {} negative (or NaN) values were written as 0 ({} is unsigned)", path.string(),
                     info.negative_values, texel_format_name(format)));
  }
  *clamped = info.clamped_values;
  return bytes;
}

// Writes a mip chain to a container chosen by extension (.ktx, .ktx2, .dds); warns about clamped values.
std::uint64_t write_container(const std::vector<CubeMap>& levels, const fs::path& path, TexelFormat format,
                              const KtxMetadata& metadata) {
  std::uint64_t clamped = 0;
  const std::vector<char> bytes = encode_container(levels, path, format, metadata, &clamped);
  unwrap(write_file_atomically(path, bytes));
  return clamped;
}

// The EXR faces of `bake specular`'s chain OUT: "STEM_mLEVEL_FACE.exr" beside OUT.
const char* const specular_face_names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
fs::path specular_face_path(const fs::path& out, std::size_t level, int face) {
  return out.parent_path() / fmt::format("{}_m{}_{}.exr", out.stem().string(), level, specular_face_names[face]);
}
// Whether `name` is one of the EXR faces of a chain named `stem` (any level): a file of an older output of the
// same name, removed when a new chain is published (issue 40, finding 5).
bool is_specular_face_name(const std::string& name, const std::string& stem) {
  const std::string prefix = stem + "_m";
  if (name.size() < prefix.size() + 8 || name.compare(0, prefix.size(), prefix) != 0) return false;
  std::size_t i = prefix.size();
  const std::size_t digits = i;
  while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i])) != 0) ++i;
  if (i == digits || i - digits > 3) return false;
  const std::string rest = name.substr(i);
  for (const char* f : specular_face_names) {
    if (rest == std::string("_") + f + ".exr") return true;
  }
  return false;
}

nlohmann::json format_json(const fs::path& out, TexelFormat f) {
  if (is_ktx(out)) return {{"container", "ktx"}, {"format", texel_format_name(f)}};
  if (is_ktx2(out)) return {{"container", "ktx2"}, {"format", texel_format_name(f)}, {"vk_format", vk_format_name(f)}};
  if (is_dds(out)) return {{"container", "dds"}, {"format", texel_format_name(f)}, {"dxgi_format", dxgi_format_name(f)}};
  return {{"container", lower(out.extension().string()).substr(1)}};
}

std::uint64_t write_cube(const CubeMap& cube, const fs::path& path, const std::string& layout, TexelFormat format,
                         const std::string& content) {
  if (is_cube_container(path)) return write_container({cube}, path, format, ktx2_metadata(content));
  Image img;
  if (layout == "hcross") {
    img = cube_to_cross(cube, CrossLayout::horizontal);
  } else if (layout == "vcross") {
    img = cube_to_cross(cube, CrossLayout::vertical);
  } else if (layout == "latlong") {
    img = cube_to_latlong(cube, 4 * cube.size);
  } else {
    throw UsageError("--layout: '" + layout + "' is not one of hcross | vcross | latlong");
  }
  unwrap(write_image(img, path));
  return 0;
}


double elapsed_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Image read_environment(const std::string& input) {
  BakeOptions o;
  o.input = input;
  return read_environment_image(o);
}

bool is_latlong_image(const Image& img) { return is_latlong(img); }

CubeMap environment_cube(const Image& img, const std::string& input) {
  BakeOptions o;
  o.input = input;
  return environment_to_cube(o, img);
}

CubeMap environment_cube_at(const Image& img, const std::string& input, int size) {
  if (is_latlong(img)) return latlong_to_cube(img, size);
  CubeMap env = environment_cube(img, input);
  // Resampled through the lat-long form with area filtering when the size differs (as bake convert does).
  if (env.size != size) env = latlong_to_cube(cube_to_latlong(env, 4 * std::max(env.size, size)), size);
  return env;
}

GgxPrefilteredCube bake_ggx_chain(const CubeMap& env, int levels, GgxRoughnessMapping mapping, GgxFilterMethod method, int samples,
                                  bool progress) {
  GgxPrefilterOptions p;
  p.levels = levels;
  p.mapping = mapping;
  p.method = method;
  p.samples = samples;
  ProgressBar bar("specular", progress);
  p.progress = [&](double f) { bar.update(f); };
  try {
    GgxPrefilteredCube chain = prefilter_ggx(env, p);
    bar.finish();
    return chain;
  } catch (const std::invalid_argument& e) {  // the CLI checks first; this names the library's option
    throw UsageError(std::string("--") + e.what());
  }
}

GgxFilterMethod ggx_method_option(const std::string& name, bool method_given, bool samples_given) {
  if (!method_given) return samples_given ? GgxFilterMethod::sampled : GgxFilterMethod::sum;
  GgxFilterMethod method = GgxFilterMethod::sum;
  try {
    method = parse_ggx_filter_method(name);
  } catch (const std::invalid_argument&) {
    throw UsageError("--method: '" + name + "' is not one of sum | sampled");
  }
  if (method == GgxFilterMethod::sum && samples_given) {
    throw UsageError("--samples does not apply to --method sum (it sums the lobe over the input texels, drawing no samples)");
  }
  return method;
}

nlohmann::json ggx_mip_mapping_json(const GgxPrefilteredCube& chain) {
  nlohmann::json exact = nlohmann::json::array();  // the levels summed over every input texel
  nlohmann::json level_methods = nlohmann::json::array();
  for (std::size_t i = 0; i < chain.exact.size(); ++i) {
    if (chain.exact[i]) exact.push_back(i);
    level_methods.push_back(ggx_level_method_name(chain.method[i]));
  }
  const bool sampled = chain.filter == GgxFilterMethod::sampled;
  nlohmann::json j = {
      {"lobe", "ggx"},
      {"kernel", "GGX D(h) with alpha = r^2 (r the perceptual roughness), n = v = R (Karis 2013), normalized by "
                 "the integral of D(h) max(R.l, 0): a constant stays constant"},
      {"method", sampled ? "filtered importance sampling (Krivanek & Colbert 2008), Hammersley half vectors; exact sums on "
                           "the levels of face n with 3 n^2 <= samples"
                         : "the lobe summed over the input texels: exactly on the coarse levels; on the others exactly "
                           "within near_angle of R, over cells of far_block^2 texels within mid_angle and of "
                           "coarse_block^2 texels beyond (each cell's flux at its radiance centroid)"},
      {"filter", ggx_filter_method_name(chain.filter)},
      {"samples", chain.samples},
      {"exact_levels", exact},
      {"level_methods", level_methods},
      {"mapping", chain.mapping.name()},
      {"formula", chain.mapping.formula()},
      {"levels", chain.levels.size()},
      {"roughness", chain.roughness}};
  if (chain.far_block > 0) {
    nlohmann::json near = nlohmann::json::array(), mid = nlohmann::json::array();
    for (std::size_t i = 0; i < chain.near_angle.size(); ++i) {
      near.push_back(chain.near_angle[i] * 180.0 / pi);
      mid.push_back(chain.mid_angle[i] * 180.0 / pi);
    }
    j["far_block"] = chain.far_block;
    j["coarse_block"] = chain.coarse_block;
    j["near_angle_degrees"] = near;  // per level, 0 where not near-far
    j["mid_angle_degrees"] = mid;
  }
  return j;
}

namespace {

// The "units" and "convention" of every `bake sh` JSON (sh9_json, sh_bands_json).
const char* sh_units_name(RadianceUnits units) { return units == RadianceUnits::game ? "game" : "radiometric"; }

const char* sh_convention_text(RadianceUnits units) {
  return units == RadianceUnits::game
             ? "irradiance_coefficients give E/pi = sum_i c_i Y_i(n): multiply by kd for the diffuse exit radiance "
               "(game units, no pi)"
             : "irradiance_coefficients give E = sum_i c_i Y_i(n) in W/m^2 per unit of radiance";
}

}  // namespace

nlohmann::json sh9_json(const Sh9& sh, RadianceUnits units, ShWindow window, const std::string& window_name,
                        const nlohmann::json& lights, const std::string& light_normalization) {
  const BandFactors w = sh_window_factors(window);
  const BandFactors& base = units == RadianceUnits::game ? cosine_band_factors_over_pi : cosine_band_factors;
  const BandFactors factors = {w[0] * base[0], w[1] * base[1], w[2] * base[2]};
  const Sh9 irr = sh9_scale_bands(sh, factors);
  nlohmann::json radiance = nlohmann::json::array();
  nlohmann::json irradiance = nlohmann::json::array();
  for (std::size_t i = 0; i < 9; ++i) {
    radiance.push_back(to_json(sh.c[i]));
    irradiance.push_back(to_json(irr.c[i]));
  }
  return {
      {"order", 3},
      {"basis", "real SH, Condon-Shortley phase, z polar axis, Sloan 2008 order: Y00, Y1-1, Y10, Y11, Y2-2, "
                "Y2-1, Y20, Y21, Y22; world axes (+Y up)"},
      {"units", sh_units_name(units)},
      {"convention", sh_convention_text(units)},
      {"band_factors", factors},
      {"window", window_name},
      {"lights", lights},
      {"light_normalization", light_normalization},
      {"radiance_coefficients", radiance},
      {"irradiance_coefficients", irradiance}};
}

namespace {

void run_irradiance(const BakeOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const int size = o.has("--size") ? o.size : 32;
  check_size("--size", size, 1024);
  const RadianceUnits units = parse_units(o.units);
  const fs::path out = o.out.empty() ? default_out(o, "_irradiance.exr") : fs::path(o.out);
  check_layout(o, out);
  const TexelFormat format = check_format(o, out);
  check_bake_outputs(o, {{"--out", out}});
  work_begins();
  // A lat-long input is convolved over its own texels (exact for the map as given: no resampling to a cube,
  // whose texels would move a bright low sun across the horizon of the normals below it), unless
  // --input-size asks for a cube of that size first.
  Image img = read_environment_image(o);
  ProgressBar bar("irradiance", o.progress);
  ConvolveOptions opts;
  opts.progress = [&](double f) { bar.update(f); };
  const CubeMap e = is_latlong(img) && !o.has("--input-size") ? irradiance_cube(img, size, units, opts)
                                                              : irradiance_cube(environment_to_cube(o, std::move(img)), size, units, opts);
  bar.finish();
  const std::string convention = units == RadianceUnits::game ? "E/pi: exit radiance of a white Lambert surface"
                                                               : "E: irradiance, W/m^2 per unit of input radiance";
  const std::uint64_t clamped = write_cube(e, out, o.layout, format, "irradiance, " + convention);
  if (o.json) {
    nlohmann::json j = {{"output", out.string()}, {"size", size}, {"units", o.units}, {"clamped_values", clamped},
                        {"convention", convention}, {"seconds", elapsed_since(t0)}};
    j.update(format_json(out, format));
    print_json(j);
  } else {
    fmt::print("wrote {} ({} x {} faces, {} units)\n", out.string(), size, size, o.units);
  }
}

ShWindow parse_window(const std::string& w) {
  if (w == "none") return ShWindow::none;
  if (w == "hanning") return ShWindow::hanning;
  if (w == "lanczos") return ShWindow::lanczos;
  throw UsageError("--window: '" + w + "' is not one of none | hanning | lanczos");
}

// --light DIR[:COLOUR]: a directional light toward DIR (x,y,z, normalized) of game colour COLOUR (a number or
// r,g,b, default 1), so its irradiance facing it is pi x COLOUR per unit of the environment's radiance.
struct ShLight {
  Vec3 to_light;
  Rgb colour;
};

ShLight parse_sh_light(const std::string& text) {
  const auto colon = text.find(':');
  ShLight l;
  l.to_light = parse_direction("--light", text.substr(0, colon));
  l.colour = Rgb::gray(1.0);
  if (colon != std::string::npos) {
    auto nums = parse_numbers(text.substr(colon + 1));
    if (!nums || (nums->size() != 1 && nums->size() != 3)) {
      throw UsageError("--light: expected DIR[:COLOUR] with COLOUR a number or r,g,b, got '" + text + "'");
    }
    const std::vector<double>& v = *nums;
    l.colour = v.size() == 1 ? Rgb::gray(v[0]) : Rgb{v[0], v[1], v[2]};
    for (double c : v) {
      if (!std::isfinite(c) || c < 0.0 || c > 1e30) {
        throw UsageError("--light: colour values must be finite, >= 0 and <= 1e30, got '" + text + "'");
      }
    }
  }
  return l;
}

// The environment cube of --error-report and the face size of its exact irradiance (sh_error.h): small enough
// for the brute force to take about a second, fine enough that its own discretization (2e-4) is negligible.
constexpr int error_report_env_size = 128;
constexpr int error_report_eval_size = 32;

std::string sh_name(int l, int m) { return "L" + std::to_string(l) + std::to_string(m); }

// The JSON of `bake sh --bands N` for N != 3: the keys of sh9_json, generalised, plus "bands".
nlohmann::json sh_bands_json(const ShBands& sh, RadianceUnits units, ShWindow window, const std::string& window_name,
                             const nlohmann::json& lights, const std::string& light_normalization) {
  const std::vector<double> factors = sh_irradiance_factors(sh.bands, units == RadianceUnits::game, window);
  const ShBands irr = sh_bands_scale(sh, factors);
  nlohmann::json radiance = nlohmann::json::array(), irradiance = nlohmann::json::array();
  std::string names;
  for (int l = 0; l < sh.bands; ++l)
    for (int m = -l; m <= l; ++m) {
      const auto i = static_cast<std::size_t>(sh_index(l, m));
      radiance.push_back(to_json(sh.c[i]));
      irradiance.push_back(to_json(irr.c[i]));
      names += (names.empty() ? "" : ", ") + std::string("Y") + std::to_string(l) + std::to_string(m);
    }
  return {
      {"order", sh.bands},
      {"bands", sh.bands},
      {"basis", "real SH, Condon-Shortley phase, z polar axis, Sloan 2008 order (index l^2 + l + m): " + names +
                    "; world axes (+Y up)"},
      {"units", sh_units_name(units)},
      {"convention", sh_convention_text(units)},
      {"band_factors", factors},
      {"window", window_name},
      {"lights", lights},
      {"light_normalization", light_normalization},
      {"radiance_coefficients", radiance},
      {"irradiance_coefficients", irradiance}};
}

nlohmann::json zh3_json(const Zh3& z, RadianceUnits units, ShWindow window) {
  const std::vector<double> f = sh_irradiance_factors(3, units == RadianceUnits::game, window);
  nlohmann::json radiance = nlohmann::json::array(), irradiance = nlohmann::json::array();
  for (std::size_t i = 0; i < 4; ++i) {
    radiance.push_back(to_json(z.linear[i]));
    irradiance.push_back(to_json(z.linear[i] * f[i == 0 ? 0 : 1]));
  }
  radiance.push_back(to_json(z.zonal));
  irradiance.push_back(to_json(z.zonal * f[2]));
  return {{"mode", z.mode == Zh3Mode::stored ? "stored" : "hallucinated"},
          {"source", "Roughton et al., ZH3: Quadratic Zonal Harmonics, i3D 2024"},
          {"axis", {z.axis.x, z.axis.y, z.axis.z}},
          {"axis_definition", "normalize of the Rec. 709 luminance of (-c11, -c1-1, c10): the L1 direction"},
          {"zonal_definition", z.mode == Zh3Mode::stored
                                   ? "z = integral L(w) Y20(axis . w) dw = sqrt(4 pi/5) sum_m c2m Y2m(axis)"
                                   : "z = c00 (0.08 r + 0.6 r^2), r = |(-c11, -c1-1, c10) . axis| / c00 (per channel)"},
          {"evaluation", "sum_i c_i Y_i(n) over i = 0..3, plus c_4 Y20(axis . n), Y20(t) = sqrt(5/(16 pi)) (3 t^2 - 1)"},
          {"band_factors", f},
          {"radiance_coefficients", radiance},
          {"irradiance_coefficients", irradiance}};
}

nlohmann::json error_report_json(const Image& img, const std::string& input) {
  const CubeMap env = environment_cube_at(img, input, error_report_env_size);
  nlohmann::json rows = nlohmann::json::array();
  for (const ShEncodingError& e : sh_encoding_errors(env, error_report_eval_size)) {
    rows.push_back({{"encoding", e.encoding},
                    {"coefficients_per_channel", e.coefficients},
                    {"mean_relative_error", e.mean_relative},
                    {"max_relative_error", e.max_relative},
                    {"negative_solid_angle_sr", e.negative_solid_angle},
                    {"negative_fraction", e.negative_solid_angle / (4.0 * pi)}});
  }
  return {{"environment_face_size", env.size},
          {"evaluation_face_size", error_report_eval_size},
          {"reference", "exact irradiance: brute-force cosine convolution of the environment cube (irradiance_cube)"},
          {"error", "|Y(E_enc) - Y(E)| / Y(E) per evaluation texel, Y the Rec. 709 luminance; mean weighted by solid "
                    "angle; negative: solid angle of texels where any channel of E_enc < 0"},
          {"lights", "not included: the report measures the environment alone"},
          {"encodings", rows}};
}

// bake sh with --bands other than 3, --zh3 or --error-report: today's SH9 path is left exactly as it was.
void run_sh_extended(const BakeOptions& o, const Image& img, const std::vector<ShLight>& lights, RadianceUnits units,
                     ShWindow window) {
  // Bands 0..2 are project_sh9 of the same input, so --bands 3 --zh3 keeps today's coefficients bit for bit.
  const int bands = std::max(o.bands, o.has("--zh3") ? 3 : 2);
  ShBands sh = is_latlong(img) && !o.has("--input-size") ? project_sh_bands(img, bands)
                                                         : project_sh_bands(environment_to_cube(o, img), bands);
  nlohmann::json lights_json = nlohmann::json::array();
  for (const ShLight& l : lights) {
    sh += sh_bands_directional_light(l.to_light, l.colour, bands, o.light_normalization == "d3dx");
    lights_json.push_back({{"direction", {l.to_light.x, l.to_light.y, l.to_light.z}}, {"color", to_json(l.colour)}});
  }
  ShBands out(o.bands);
  for (std::size_t i = 0; i < out.c.size(); ++i) out.c[i] = sh.c[i];
  nlohmann::json j;
  if (o.bands == 3) {
    Sh9 s9;
    for (std::size_t i = 0; i < 9; ++i) s9.c[i] = out.c[i];
    j = sh9_json(s9, units, window, o.window, lights_json, o.light_normalization);
  } else {
    j = sh_bands_json(out, units, window, o.window, lights_json, o.light_normalization);
  }
  if (o.has("--zh3")) j["zh3"] = zh3_json(zh3_from_sh(sh, o.zh3 == "stored" ? Zh3Mode::stored : Zh3Mode::hallucinated), units, window);
  if (o.error_report) j["error_report"] = error_report_json(img, o.input);
  if (!o.out.empty()) {
    unwrap(write_file_atomically(o.out, json_file_bytes(j)));
  }
  if (o.json) {
    print_json(j);
    return;
  }
  fmt::print("SH irradiance coefficients, {} bands ({} units: {}):\n", o.bands, o.units,
             units == RadianceUnits::game ? "E/pi" : "E, W/m^2");
  for (int l = 0; l < o.bands; ++l)
    for (int m = -l; m <= l; ++m) {
      const auto& c = j["irradiance_coefficients"][static_cast<std::size_t>(sh_index(l, m))];
      fmt::print("  {:<5} {:>14.8f} {:>14.8f} {:>14.8f}\n", sh_name(l, m), c[0].get<double>(), c[1].get<double>(),
                 c[2].get<double>());
    }
  if (j.contains("zh3")) {
    const auto& z = j["zh3"];
    fmt::print("ZH3 ({}), axis ({:.6f}, {:.6f}, {:.6f}):\n", z["mode"].get<std::string>(), z["axis"][0].get<double>(),
               z["axis"][1].get<double>(), z["axis"][2].get<double>());
    const char* names[5] = {"L00", "L1-1", "L10", "L11", "Z20"};
    for (std::size_t i = 0; i < 5; ++i) {
      const auto& c = z["irradiance_coefficients"][i];
      fmt::print("  {:<5} {:>14.8f} {:>14.8f} {:>14.8f}\n", names[i], c[0].get<double>(), c[1].get<double>(),
                 c[2].get<double>());
    }
  }
  if (j.contains("error_report")) {
    fmt::print("irradiance error against the exact irradiance ({} x {} faces from a {} x {} cube):\n",
               error_report_eval_size, error_report_eval_size, error_report_env_size, error_report_env_size);
    fmt::print("  {:<18} {:>6} {:>10} {:>10} {:>12}\n", "encoding", "coeffs", "mean", "max", "negative sr");
    for (const auto& r : j["error_report"]["encodings"]) {
      fmt::print("  {:<18} {:>6} {:>9.2f}% {:>9.2f}% {:>12.4f}\n", r["encoding"].get<std::string>(),
                 r["coefficients_per_channel"].get<int>(), 100.0 * r["mean_relative_error"].get<double>(),
                 100.0 * r["max_relative_error"].get<double>(), r["negative_solid_angle_sr"].get<double>());
    }
  }
  if (!o.out.empty()) fmt::print("wrote {}\n", o.out);
}

void run_sh(const BakeOptions& o) {
  refuse_options(o, "sh", {"--size", "--layout", "--format"}, "it writes nine coefficients, not a cube map");
  const RadianceUnits units = parse_units(o.units);
  const ShWindow window = parse_window(o.window);
  if (o.bands < 2 || o.bands > sh_max_bands) {
    throw UsageError(fmt::format("--bands: {} is not one of 2 | 3 | 4 | 5 (L1 .. L4)", o.bands));
  }
  if (o.has("--zh3") && o.zh3 != "stored" && o.zh3 != "hallucinated") {
    throw UsageError("--zh3: '" + o.zh3 + "' is not one of stored | hallucinated");
  }
  const bool extended = o.bands != 3 || o.has("--zh3") || o.error_report;
  if (o.light_normalization != "d3dx" && o.light_normalization != "delta") {
    throw UsageError("--light-normalization: '" + o.light_normalization + "' is not one of d3dx | delta");
  }
  if (o.has("--light-normalization") && o.lights.empty()) {
    throw UsageError("--light-normalization applies to --light, and no --light was given");
  }
  std::vector<ShLight> lights;
  for (const auto& text : o.lights) lights.push_back(parse_sh_light(text));
  if (!o.out.empty()) {
    require_extension("--out", o.out, {".json"}, "the SH9 coefficients (JSON)");
    check_bake_outputs(o, {{"--out", o.out}});
  }
  work_begins();
  // A lat-long input is projected texel by texel (each with its exact solid angle), without resampling to a
  // cube first, unless --input-size asks for that cube: the command then costs about one read of the file.
  Image img = read_environment_image(o);
  if (extended) {
    run_sh_extended(o, img, lights, units, window);
    return;
  }
  Sh9 sh = is_latlong(img) && !o.has("--input-size") ? project_sh9(img) : project_sh9(environment_to_cube(o, std::move(img)));
  // D3DX-style punctual lights (sh.h): each adds the projection of pi c delta(w - d), scaled by 16/17 with
  // d3dx normalization so that the game irradiance facing a light of colour c is exactly c.
  nlohmann::json lights_json = nlohmann::json::array();
  for (const ShLight& l : lights) {
    sh += sh9_directional_light(l.to_light, l.colour, o.light_normalization == "d3dx");
    lights_json.push_back({{"direction", {l.to_light.x, l.to_light.y, l.to_light.z}}, {"color", to_json(l.colour)}});
  }
  const nlohmann::json j = sh9_json(sh, units, window, o.window, lights_json, o.light_normalization);
  if (!o.out.empty()) {
    unwrap(write_file_atomically(o.out, json_file_bytes(j)));
  }
  if (o.json) {
    print_json(j);
  } else {
    fmt::print("SH9 irradiance coefficients ({} units: {}):\n", o.units,
               units == RadianceUnits::game ? "E/pi" : "E, W/m^2");
    // The basis order and normalization, in the JSON's own words (issue 39: the text did not say them).
    fmt::print("  basis: {}\n  normalization: {}\n", j["basis"].get<std::string>(), j["convention"].get<std::string>());
    const char* names[9] = {"L00", "L1-1", "L10", "L11", "L2-2", "L2-1", "L20", "L21", "L22"};
    for (std::size_t i = 0; i < 9; ++i) {
      const auto& c = j["irradiance_coefficients"][i];
      fmt::print("  {:<5} {:>14.8f} {:>14.8f} {:>14.8f}\n", names[i], c[0].get<double>(), c[1].get<double>(),
                 c[2].get<double>());
    }
    if (!o.out.empty()) fmt::print("wrote {}\n", o.out);
  }
}

void run_specular(const BakeOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  refuse_options(o, "specular", {"--layout"}, "it writes a KTX mip chain and EXR faces");
  refuse_options(o, "specular", {"--units"}, "prefiltered radiance has no game or radiometric convention");
  if (o.lobe != "phong" && o.lobe != "ggx") throw UsageError("--lobe: '" + o.lobe + "' is not one of phong | ggx");
  const bool ggx = o.lobe == "ggx";
  GgxRoughnessMapping mapping = GgxRoughnessMapping::linear;
  GgxFilterMethod method = GgxFilterMethod::sum;
  if (ggx) {
    refuse_options(o, "specular --lobe ggx", {"--gloss-scale", "--gloss-bias"},
                   "they set Phong exponents; --mapping maps GGX roughness to levels");
    refuse_options(o, "specular --lobe ggx", {"--input-size"}, "level 0 is the input at --size");
    if (o.mapping != "linear" && o.mapping != "filament") {
      throw UsageError("--mapping: '" + o.mapping + "' is not one of linear | filament");
    }
    mapping = parse_ggx_roughness_mapping(o.mapping);
    method = ggx_method_option(o.method, o.has("--method"), o.has("--samples"));
    check_range("--samples", true, o.samples, 1, 1 << 20);
  } else {
    refuse_options(o, "specular --lobe phong", {"--mapping", "--samples", "--method"}, "they apply to --lobe ggx");
  }
  const int size = o.has("--size") ? o.size : 128;
  if (!is_power_of_two(size) || size > 2048) throw UsageError(fmt::format("--size: {} is not a power of two in [1, 2048]", size));
  const fs::path out = o.out.empty() ? default_out(o, "_specular.ktx") : fs::path(o.out);
  if (!is_cube_container(out)) {
    throw UsageError("--out: the specular chain is written as .ktx, .ktx2 or .dds, got '" + out.string() + "'");
  }
  const TexelFormat format = check_format(o, out);
  if (o.mips < 0 || o.mips > 32) throw UsageError(fmt::format("--mips: {} is out of range [0, 32]", o.mips));
  if (o.has("--levels") && o.has("--mips")) throw UsageError("--levels and --mips are the same option: give one");
  const int full_chain = static_cast<int>(std::log2(size)) + 1;  // down to 1 x 1
  const char* levels_option = o.has("--levels") ? "--levels" : "--mips";
  const int mip_count = o.has("--levels") ? o.levels : o.mips;
  if ((o.has("--levels") && mip_count < 1) || mip_count > full_chain) {
    throw UsageError(fmt::format("{}: {} is out of range [1, {}] for --size {} (log2(size) + 1 levels reach 1 x 1)",
                                 levels_option, mip_count, full_chain, size));
  }
  // Every level's exponent 2^(scale (1 - i/(M-1)) + bias) lies between 2^bias and 2^(scale + bias).
  if (!std::isfinite(o.gloss_scale) || o.gloss_scale < 0.0 || !std::isfinite(o.gloss_bias) ||
      o.gloss_bias < -max_gloss_log2 || o.gloss_scale + o.gloss_bias > max_gloss_log2) {
    throw UsageError(fmt::format("--gloss-scale {} / --gloss-bias {}: the level exponents 2^bias .. 2^(scale + bias) "
                                 "must lie in [2^-{}, 2^{}] with scale >= 0",
                                 o.gloss_scale, o.gloss_bias, max_gloss_log2, max_gloss_log2));
  }
  const std::vector<NamedPath> planned = [&] {
    std::vector<NamedPath> v{{"--out", out}};
    if (o.exr_faces) {
      const int levels = mip_count > 0 ? mip_count : full_chain;
      for (int m = 0; m < levels; ++m) {
        for (int f = 0; f < 6; ++f) v.push_back({"the EXR face", specular_face_path(out, static_cast<std::size_t>(m), f)});
      }
    }
    return v;
  }();
  check_bake_outputs(o, planned);
  work_begins();
  std::vector<CubeMap> levels;
  nlohmann::json mip_mapping;
  std::vector<double> exponents;
  std::vector<double> roughness;
  if (ggx) {
    GgxPrefilteredCube chain = bake_ggx_chain(environment_cube_at(read_environment(o.input), o.input, size), mip_count, mapping, method, o.samples,
                                              o.progress);
    mip_mapping = ggx_mip_mapping_json(chain);
    roughness = chain.roughness;
    levels = std::move(chain.levels);
  } else {
    const CubeMap env = load_environment(o);
    PrefilterOptions p;
    p.size = size;
    p.mip_count = mip_count;
    p.gloss_scale = o.gloss_scale;
    p.gloss_bias = o.gloss_bias;
    ProgressBar bar("specular", o.progress);
    p.progress = [&](double f) { bar.update(f); };
    auto chain = prefilter_specular(env, p);
    bar.finish();
    if (!chain) throw UsageError(chain.error().message);
    mip_mapping = {
        {"lobe", "phong"},
        {"kernel", "normalized Phong (n+1)/(2pi) (R.L)^n"},
        {"mapping", "level i of M holds the Phong exponent n_i = 2^(gloss_scale (1 - i/(M-1)) + gloss_bias); a shader "
                    "with gloss g in [0, 1] reads level (1 - g)(M - 1)"},
        {"gloss_scale", o.gloss_scale},
        {"gloss_bias", o.gloss_bias},
        {"exponents", chain->exponents}};
    exponents = chain->exponents;
    levels = std::move(chain->levels);
  }
  // The container and its faces are one output set (issue 40, finding 5): encoded first, then published as a
  // whole (write_files_atomically: temporaries, a journal, the renames), and the faces of an older chain of the
  // same name that this one does not have (deeper levels, or all of them with --no-exr-faces) go in the same step.
  std::uint64_t clamped = 0;
  std::vector<std::pair<fs::path, std::vector<char>>> files;
  files.emplace_back(out, encode_container(levels, out, format, ktx2_metadata("prefiltered specular radiance", mip_mapping),
                                           &clamped));
  std::vector<std::string> faces;
  if (o.exr_faces) {
    for (std::size_t m = 0; m < levels.size(); ++m) {
      for (int f = 0; f < 6; ++f) {
        const fs::path path = specular_face_path(out, m, f);
        files.emplace_back(path, unwrap(encode_image(levels[m].faces[static_cast<std::size_t>(f)], path)));
        faces.push_back(path.string());
      }
    }
  }
  PublishOptions publish;
  const std::string stem = out.stem().string();
  publish.remove_also = [stem](const fs::path& p) { return is_specular_face_name(p.filename().string(), stem); };
  unwrap(write_files_atomically(files, publish));
  const std::string recorded_in = is_ktx2(out) ? "the KTX 2 key/value data, key shadelab.mip_mapping (JSON)"
                                               : "only here: .ktx, .dds and the EXR faces hold no shadelab metadata";
  if (o.json) {
    nlohmann::json j = {{"output", out.string()}, {"exr_faces", faces}, {"size", size}, {"clamped_values", clamped},
                        {"levels", levels.size()}, {"mip_mapping", mip_mapping}, {"mip_mapping_recorded_in", recorded_in},
                        {"seconds", elapsed_since(t0)}};
    if (ggx) {
      j["lobe"] = "GGX D(h), alpha = r^2, n = v = R (Karis 2013 split sum)";
      j["mapping"] = o.mapping;
      j["roughness"] = roughness;
      j["samples"] = method == GgxFilterMethod::sampled ? o.samples : 0;
      j["method"] = ggx_filter_method_name(method);
    } else {
      j["lobe"] = "normalized Phong (n+1)/(2pi) (R.L)^n";
      j["exponents"] = exponents;
      j["gloss_scale"] = o.gloss_scale;
      j["gloss_bias"] = o.gloss_bias;
    }
    j.update(format_json(out, format));
    print_json(j);
  } else if (ggx) {
    fmt::print("wrote {} ({} levels, GGX perceptual roughness {:.4g} .. {:.4g}, {} mapping) and {} EXR faces\n",
               out.string(), levels.size(), roughness.front(), roughness.back(), o.mapping, faces.size());
  } else {
    fmt::print("wrote {} ({} levels, Phong exponents {:.4g} .. {:.4g}) and {} EXR faces\n", out.string(),
               levels.size(), exponents.front(), exponents.back(), faces.size());
  }
}

void run_convert(const BakeOptions& o) {
  if (o.out.empty()) throw UsageError("convert: --out FILE is required");
  refuse_options(o, "convert", {"--units"}, "conversion changes no values");
  check_layout(o, o.out);
  const TexelFormat format = check_format(o, o.out);
  check_bake_outputs(o, {{"--out", o.out}});
  if (o.has("--size")) check_size("--size", o.size, 4096);
  work_begins();
  CubeMap env = load_environment(o);
  if (o.has("--size")) {
    // Resample through the lat-long form with area filtering when the size changes.
    if (o.size != env.size) env = latlong_to_cube(cube_to_latlong(env, 4 * std::max(env.size, o.size)), o.size);
  }
  const std::uint64_t clamped = write_cube(env, o.out, o.layout, format, "radiance");
  const std::string layout = is_cube_container(o.out) ? lower(fs::path(o.out).extension().string()).substr(1) : o.layout;
  if (o.json) {
    nlohmann::json j = {{"output", o.out}, {"size", env.size}, {"layout", layout}, {"clamped_values", clamped}};
    j.update(format_json(o.out, format));
    print_json(j);
  } else {
    fmt::print("wrote {} ({} x {} faces as {})\n", o.out, env.size, env.size,
               is_ktx(o.out) ? std::string("a KTX cube map") : is_ktx2(o.out) ? std::string("a KTX 2 cube map")
               : is_dds(o.out) ? std::string("a DDS cube map") : o.layout);
  }
}

}  // namespace

namespace {
void add_bake_command(CLI::App& app, Command& command) {
  auto* bake = app.add_subcommand("bake", "bake environment lighting: irradiance, SH9, prefiltered specular, conversion");
  bake->require_subcommand(1);
  auto add = [&](const char* name, const char* help, void (*run)(const BakeOptions&)) {
    auto o = std::make_shared<BakeOptions>();
    auto* sub = bake->add_subcommand(name, help);
    sub->add_option("INPUT", o->input, "environment: lat-long (2:1) or cube cross (4:3, 3:4); EXR, HDR or PNG")
        ->required();
    sub->add_option("--out", o->out, "output file (.ktx2, .ktx, .dds, .exr, .hdr, .png; .json for sh)");
    sub->add_option("--size", o->size, "output face size");
    sub->add_option("--input-size", o->input_size, "face size a lat-long input is resampled to (default: width/4, <= 512)");
    sub->add_option("--units", o->units, "game (E/pi: a constant 0.5 bakes to 0.5) or radiometric (E)")->capture_default_str();
    sub->add_option("--layout", o->layout, "image layout of cube outputs: hcross, vcross or latlong")->capture_default_str();
    sub->add_flag("--json", o->json, "machine-readable output");
    sub->add_option("--format", o->format,
                    "texel format of a .ktx2 / .dds output: rgba16f, rgba32f, rg11b10f or rgb9e5 (.ktx: the first two)")
        ->capture_default_str();
    sub->add_flag("--progress", o->progress, "show the progress bar even when stderr is not a terminal");
    if (std::string(name) == "sh") {
      sub->add_option("--window", o->window, "ringing window: none, hanning or lanczos")->capture_default_str();
      sub->add_option("--bands", o->bands, "number of SH bands: 2 (L1, 4 coefficients), 3 (L2, 9), 4 (L3, 16), 5 (L4, 25)")
          ->capture_default_str();
      sub->add_option("--zh3", o->zh3,
                      "also write ZH3 (L1 + one zonal L2 coefficient along the luminance L1 axis, Roughton et al. 2024): "
                      "stored (projected) or hallucinated (from L1)");
      sub->add_flag("--error-report", o->error_report,
                    "add each encoding's irradiance error against the exact irradiance (L1..L4, windows, ZH3)");
      sub->add_option("--light", o->lights,
                      "add a directional light to the coefficients: DIR[:COLOUR], toward x,y,z, game colour (a number "
                      "or r,g,b; default 1); repeatable");
      sub->add_option("--light-normalization", o->light_normalization,
                      "d3dx: scaled by 16/17 so a light of colour c gives exactly c facing it (D3DXSHEvalDirectionalLight); "
                      "delta: the plain projection of the delta")
          ->capture_default_str();
    }
    if (std::string(name) == "specular") {
      sub->add_option("--mips", o->mips, "number of mip levels (default: down to 1 x 1)");
      sub->add_option("--levels", o->levels, "number of mip levels, at most log2(size) + 1 (the same as --mips)");
      sub->add_option("--gloss-scale", o->gloss_scale, "exponent of level i: 2^(scale (1 - i/(M-1)) + bias)")->capture_default_str();
      sub->add_option("--gloss-bias", o->gloss_bias, "see --gloss-scale")->capture_default_str();
      sub->add_flag("--exr-faces,!--no-exr-faces", o->exr_faces,
                    "also write each level's six faces as EXR files beside the container (STEM_mLEVEL_FACE.exr); "
                    "--no-exr-faces, the default, writes the container alone");
      sub->add_option("--lobe", o->lobe, "phong (normalized Phong lobes, cmft's) or ggx (the split sum's GGX lobes)")
          ->capture_default_str();
      sub->add_option("--mapping", o->mapping,
                      "--lobe ggx: roughness to level, linear (lod = r (L - 1), glTF-Sample-Viewer) or filament "
                      "(lod = r (2 - r) (L - 1))")
          ->capture_default_str();
      sub->add_option("--method", o->method,
                      "--lobe ggx: sum (the lobe summed over the input, exact near R and by cells far from it) or "
                      "sampled (filtered importance sampling)")
          ->capture_default_str();
      sub->add_option("--samples", o->samples, "--lobe ggx --method sampled: Hammersley half vectors per texel, in [1, 2^20] "
                                               "(given alone, it implies --method sampled)")
          ->capture_default_str();
    }
    sub->callback([o, run, sub, &command] {
      o->given.clear();
      for (const CLI::Option* opt : sub->get_options()) {
        if (opt->count() > 0) o->given.push_back(opt->get_name());
      }
      command.run = [o, run] { run(*o); };
    });
  };
  add("irradiance", "cosine-convolved irradiance cube map (brute force)", run_irradiance);
  add("sh", "nine RGB spherical-harmonic coefficients and their convention", run_sh);
  add("specular", "prefiltered specular mip chain (normalized Phong or GGX lobes) as KTX 2, KTX or DDS plus EXR faces",
      run_specular);
  add("convert", "lat-long <-> cube cross conversion and format change", run_convert);
}

}  // namespace

const CommandRegistration registration_bake(60, add_bake_command);

}  // namespace shadelab::cli
