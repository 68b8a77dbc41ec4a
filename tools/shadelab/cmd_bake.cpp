// shadelab bake irradiance|sh|specular|convert INPUT [--out FILE] [--size N] [--units game|radiometric]
// [--json]: environment lighting baked the way engines load it.
#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <iostream>

#include "cli_common.h"
#include "progress.h"
#include "shadelab/envmap/irradiance.h"
#include "shadelab/envmap/ktx.h"
#include "shadelab/envmap/latlong.h"
#include "shadelab/envmap/prefilter.h"
#include "shadelab/envmap/sh.h"
#include "shadelab/image/image_io.h"

namespace shadelab::cli {

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
  double gloss_scale = 10.0;
  double gloss_bias = 1.0;
  bool exr_faces = true;
  bool json = false;
  bool progress = false;
};

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool is_power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

void check_size(const std::string& option, int size, int max) {
  if (size < 1 || size > max) throw UsageError(fmt::format("{}: {} is out of range [1, {}]", option, size, max));
}


// Reads INPUT as a lat-long (2:1) or a cross (4:3 or 3:4) and returns a cube map.
CubeMap load_environment(const BakeOptions& o) {
  ReadInfo info;
  Image img = unwrap(read_image(o.input, &info));
  if (info.nonfinite_repaired > 0) {
    std::cerr << "shadelab: warning: " << o.input << ": " << info.nonfinite_repaired
              << " NaN/Inf values replaced by 0\n";
  }
  if (img.width == 2 * img.height) {
    int size = o.input_size;
    if (size != -1) check_size("--input-size", size, 2048);
    if (size == -1) {  // about the lat-long's resolution: a face spans a quarter of its width
      size = 1;
      while (size * 2 <= std::min(512, img.width / 4)) size *= 2;
    }
    return latlong_to_cube(img, size);
  }
  auto cube = cube_from_cross(img);
  if (!cube) throw UsageError(o.input + ": " + cube.error().message + "; expected a 2:1 lat-long or a cube cross");
  return std::move(cube).value();
}

RadianceUnits parse_units(const std::string& u) {
  if (u == "game") return RadianceUnits::game;
  if (u == "radiometric") return RadianceUnits::radiometric;
  throw UsageError("--units: '" + u + "' is not one of game | radiometric");
}

fs::path default_out(const BakeOptions& o, const std::string& suffix) {
  const fs::path in(o.input);
  return in.parent_path() / (in.stem().string() + suffix);
}

void write_cube(const CubeMap& cube, const fs::path& path, const std::string& layout) {
  const std::string ext = lower(path.extension().string());
  if (ext == ".ktx") {
    unwrap(write_ktx_cubemap({cube}, path));
    return;
  }
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
}


double elapsed_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void run_irradiance(const BakeOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const int size = o.size == -1 ? 32 : o.size;
  check_size("--size", size, 1024);
  const RadianceUnits units = parse_units(o.units);
  const fs::path out = o.out.empty() ? default_out(o, "_irradiance.exr") : fs::path(o.out);
  const CubeMap env = load_environment(o);
  ProgressBar bar("irradiance", o.progress);
  ConvolveOptions opts;
  opts.progress = [&](double f) { bar.update(f); };
  const CubeMap e = irradiance_cube(env, size, units, opts);
  bar.finish();
  write_cube(e, out, o.layout);
  if (o.json) {
    print_json({{"output", out.string()}, {"size", size}, {"units", o.units},
                {"convention", units == RadianceUnits::game ? "E/pi: exit radiance of a white Lambert surface"
                                                            : "E: irradiance, W/m^2 per unit of input radiance"},
                {"seconds", elapsed_since(t0)}});
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

void run_sh(const BakeOptions& o) {
  const RadianceUnits units = parse_units(o.units);
  const ShWindow window = parse_window(o.window);
  const CubeMap env = load_environment(o);
  const Sh9 sh = project_sh9(env);
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
  const nlohmann::json j = {
      {"order", 3},
      {"basis", "real SH, Condon-Shortley phase, z polar axis, Sloan 2008 order: Y00, Y1-1, Y10, Y11, Y2-2, "
                "Y2-1, Y20, Y21, Y22; world axes (+Y up)"},
      {"units", o.units},
      {"convention", units == RadianceUnits::game
                         ? "irradiance_coefficients give E/pi = sum_i c_i Y_i(n): multiply by kd for the diffuse "
                           "exit radiance (game units, no pi)"
                         : "irradiance_coefficients give E = sum_i c_i Y_i(n) in W/m^2 per unit of radiance"},
      {"band_factors", factors},
      {"window", o.window},
      {"radiance_coefficients", radiance},
      {"irradiance_coefficients", irradiance}};
  if (!o.out.empty()) {
    const std::string text = j.dump(2) + "\n";
    unwrap(write_file_atomically(o.out, std::vector<char>(text.begin(), text.end())));
  }
  if (o.json) {
    print_json(j);
  } else {
    fmt::print("SH9 irradiance coefficients ({} units: {}):\n", o.units,
               units == RadianceUnits::game ? "E/pi" : "E, W/m^2");
    const char* names[9] = {"L00", "L1-1", "L10", "L11", "L2-2", "L2-1", "L20", "L21", "L22"};
    for (std::size_t i = 0; i < 9; ++i) {
      fmt::print("  {:<5} {:>14.8f} {:>14.8f} {:>14.8f}\n", names[i], irr.c[i].r, irr.c[i].g, irr.c[i].b);
    }
    if (!o.out.empty()) fmt::print("wrote {}\n", o.out);
  }
}

void run_specular(const BakeOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const int size = o.size == -1 ? 128 : o.size;
  if (!is_power_of_two(size) || size > 2048) throw UsageError(fmt::format("--size: {} is not a power of two in [1, 2048]", size));
  const fs::path out = o.out.empty() ? default_out(o, "_specular.ktx") : fs::path(o.out);
  if (lower(out.extension().string()) != ".ktx") throw UsageError("--out: the specular chain is written as .ktx, got '" + out.string() + "'");
  const CubeMap env = load_environment(o);
  PrefilterOptions p;
  p.size = size;
  p.mip_count = o.mips;
  p.gloss_scale = o.gloss_scale;
  p.gloss_bias = o.gloss_bias;
  ProgressBar bar("specular", o.progress);
  p.progress = [&](double f) { bar.update(f); };
  auto chain = prefilter_specular(env, p);
  bar.finish();
  if (!chain) throw UsageError(chain.error().message);
  unwrap(write_ktx_cubemap(chain->levels, out));
  std::vector<std::string> faces;
  if (o.exr_faces) {
    static const char* face_names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    for (std::size_t m = 0; m < chain->levels.size(); ++m) {
      for (std::size_t f = 0; f < 6; ++f) {
        const fs::path path = out.parent_path() / fmt::format("{}_m{}_{}.exr", out.stem().string(), m, face_names[f]);
        unwrap(write_image(chain->levels[m].faces[f], path));
        faces.push_back(path.string());
      }
    }
  }
  if (o.json) {
    print_json({{"output", out.string()}, {"exr_faces", faces}, {"size", size},
                {"exponents", chain->exponents}, {"gloss_scale", o.gloss_scale}, {"gloss_bias", o.gloss_bias},
                {"lobe", "normalized Phong (n+1)/(2pi) (R.L)^n"}, {"seconds", elapsed_since(t0)}});
  } else {
    fmt::print("wrote {} ({} levels, Phong exponents {:.4g} .. {:.4g}) and {} EXR faces\n", out.string(),
               chain->levels.size(), chain->exponents.front(), chain->exponents.back(), faces.size());
  }
}

void run_convert(const BakeOptions& o) {
  if (o.out.empty()) throw UsageError("convert: --out FILE is required");
  CubeMap env = load_environment(o);
  if (o.size != -1) {
    check_size("--size", o.size, 4096);
    // Resample through the lat-long form with area filtering when the size changes.
    if (o.size != env.size) env = latlong_to_cube(cube_to_latlong(env, 4 * std::max(env.size, o.size)), o.size);
  }
  write_cube(env, o.out, o.layout);
  if (o.json) {
    print_json({{"output", o.out}, {"size", env.size}, {"layout", o.layout}});
  } else {
    fmt::print("wrote {} ({} x {} faces as {})\n", o.out, env.size, env.size, o.layout);
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
    sub->add_option("--out", o->out, "output file (.exr, .hdr, .png, .ktx; .json for sh)");
    sub->add_option("--size", o->size, "output face size");
    sub->add_option("--input-size", o->input_size, "face size a lat-long input is resampled to (default: width/4, <= 512)");
    sub->add_option("--units", o->units, "game (E/pi: a constant 0.5 bakes to 0.5) or radiometric (E)")->capture_default_str();
    sub->add_option("--layout", o->layout, "image layout of cube outputs: hcross, vcross or latlong")->capture_default_str();
    sub->add_flag("--json", o->json, "machine-readable output");
    sub->add_flag("--progress", o->progress, "show the progress bar even when stderr is not a terminal");
    if (std::string(name) == "sh") {
      sub->add_option("--window", o->window, "ringing window: none, hanning or lanczos")->capture_default_str();
    }
    if (std::string(name) == "specular") {
      sub->add_option("--mips", o->mips, "number of mip levels (default: down to 1 x 1)");
      sub->add_option("--gloss-scale", o->gloss_scale, "exponent of level i: 2^(scale (1 - i/(M-1)) + bias)")->capture_default_str();
      sub->add_option("--gloss-bias", o->gloss_bias, "see --gloss-scale")->capture_default_str();
      sub->add_flag("!--no-exr-faces", o->exr_faces, "do not write the per-level EXR faces");
    }
    sub->callback([o, run, &command] { command.run = [o, run] { run(*o); }; });
  };
  add("irradiance", "cosine-convolved irradiance cube map (brute force)", run_irradiance);
  add("sh", "nine RGB spherical-harmonic coefficients and their convention", run_sh);
  add("specular", "prefiltered specular mip chain (normalized Phong lobes) as KTX plus EXR faces", run_specular);
  add("convert", "lat-long <-> cube cross conversion and format change", run_convert);
}

}  // namespace

const CommandRegistration registration_bake(60, add_bake_command);

}  // namespace shadelab::cli
