// shadelab bake dfg [--size N] [--multiscatter] [--samples N] --out FILE [--json]: the split-sum DFG table
// of the height-correlated Smith GGX model (envmap/specular/dfg.h) as engines load it beside a prefiltered cube.
//
// Outputs by extension: .exr (float32 R G B: A, B, and A + B with --multiscatter, else 0), .h (a C header
// of float arrays), .ktx2 (a 2D texture: RG16F = A, B; with --multiscatter RGBA16F = A, B, A + B, 1).
// x = N.V at texel centres (i + 0.5)/N left to right; y = perceptual roughness (j + 0.5)/N, row 0 first.
#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "bake_shared.h"
#include "cli_common.h"
#include "shadelab/envmap/base/ktx2.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/image/image.h"
#include "shadelab/image/image_io.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab::cli {

Image dfg_image(const DfgTable& t) {
  Image img(t.size, t.size);
  for (int j = 0; j < t.size; ++j) {
    for (int i = 0; i < t.size; ++i) img.set(i, j, {t.at(i, j, 0), t.at(i, j, 1), t.at(i, j, 2)});
  }
  return img;
}

nlohmann::json dfg_conventions_json(bool multiscatter) {
  nlohmann::json channels = nlohmann::json::array({"A: scale of F0", "B: bias"});
  channels.push_back(multiscatter ? "E_ss = A + B: single-scattering albedo (F = 1)" : "0");
  return {{"model", "GGX, height-correlated Smith G2, Schlick F (Karis 2013 split sum)"},
          {"x", "N.V = (i + 0.5) / size, column i, left to right"},
          {"y", "perceptual roughness r = (j + 0.5) / size, row j; alpha = r^2"},
          {"orientation", "row 0 (first in memory; the top in an image viewer) is the smallest roughness"},
          {"channels", channels},
          {"specular", multiscatter ? "F0 A + B; multiple scattering: times 1 + F0 (1 / E_ss - 1)" : "F0 A + B"}};
}

KtxMetadata dfg_ktx2_metadata(bool multiscatter) {
  return {{"shadelab.content", "DFG table: split-sum environment BRDF of GGX with height-correlated Smith G2, "
                               "Schlick F (Karis 2013)"},
          {"shadelab.dfg_axes", "x (s, column i) = N.V = (i + 0.5) / width; y (t, row j, row 0 first) = perceptual "
                                "roughness r = (j + 0.5) / height, alpha = r^2; texel centres"},
          {"shadelab.dfg_channels", multiscatter ? "R = A (scale of F0), G = B (bias), B = A + B = E_ss "
                                                   "(single-scattering albedo, F = 1), A = 1"
                                                 : "R = A (scale of F0), G = B (bias)"}};
}

namespace {

namespace fs = std::filesystem;

struct DfgCliOptions {
  std::string out;
  int size = 128;
  int samples = 0;
  bool adaptive = false;
  bool multiscatter = false;
  bool json = false;
};

std::string lower_ext(const fs::path& p) {
  std::string e = p.extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// A C header: the table as `static const float NAME[size * size * channels]`, row-major, with its
// conventions in a comment. Floats printed with 9 significant digits (they round-trip).
std::vector<char> header_bytes(const DfgTable& t, const std::string& name) {
  const int channels = t.multiscatter ? 3 : 2;
  std::string s = fmt::format(
      "// DFG table written by shadelab bake dfg: the split-sum environment BRDF of the height-correlated\n"
      "// Smith GGX model (Karis 2013). {0} x {0} texels, {1} floats each, row-major.\n"
      "// Column i: N.V = (i + 0.5) / {0}. Row j: perceptual roughness r = (j + 0.5) / {0} (alpha = r^2), row 0 first.\n"
      "// Channels: A (scale of F0), B (bias){2}. Specular = F0 * A + B{3}.\n"
      "#pragma once\n\nstatic const int {4}_size = {0};\nstatic const int {4}_channels = {1};\n"
      "static const float {4}[{5}] = {{\n",
      t.size, channels, t.multiscatter ? ", E_ss = A + B (single-scattering albedo)" : "",
      t.multiscatter ? "; energy compensation 1 + F0 (1 / E_ss - 1)" : "", name, t.size * t.size * channels);
  for (int j = 0; j < t.size; ++j) {
    s += "  ";
    for (int i = 0; i < t.size; ++i) {
      for (int c = 0; c < channels; ++c) s += fmt::format("{:.9g}f, ", static_cast<float>(t.at(i, j, c)));
    }
    s += "\n";
  }
  s += "};\n";
  return {s.begin(), s.end()};
}

void run_dfg(const DfgCliOptions& o, const std::vector<std::string>& given) {
  const auto t0 = std::chrono::steady_clock::now();
  (void)given;
  check_range("--size", true, o.size, 1, 4096);
  check_range("--samples", true, o.samples, 0, 1 << 24);
  if (o.adaptive && o.samples > 0) throw UsageError("--adaptive: not with --samples (Hammersley sampling)");
  if (o.out.empty()) throw UsageError("--out is required (a .exr, .h or .ktx2 file)");
  const fs::path out(o.out);
  require_extension("--out", out, {".exr", ".h", ".ktx2"}, "the DFG table");
  check_outputs({}, {{"--out", out}});
  DfgOptions options;
  options.size = o.size;
  options.samples = o.samples;
  options.adaptive = o.adaptive;
  options.multiscatter = o.multiscatter;
  work_begins();
  const DfgTable t = bake_dfg(options);
  const std::string ext = lower_ext(out);
  const Ktx2ImageFormat ktx2_format = o.multiscatter ? Ktx2ImageFormat::rgba16f : Ktx2ImageFormat::rg16f;
  if (ext == ".exr") {
    unwrap(write_image(dfg_image(t), out));
  } else if (ext == ".ktx2") {
    unwrap(write_ktx2_image(dfg_image(t), out, ktx2_format, dfg_ktx2_metadata(o.multiscatter)));
  } else {
    unwrap(write_file_atomically(out, header_bytes(t, "shadelab_dfg")));
  }
  // Sampling's error, measured: the largest difference to the quadrature over a coarse subset of texels.
  double sampling_error = 0.0;
  if (o.samples > 0) {
    const int step = std::max(1, t.size / 16);
    for (int j = 0; j < t.size; j += step) {
      for (int i = 0; i < t.size; i += step) {
        const double mu = (i + 0.5) / t.size;
        const double r = (j + 0.5) / t.size;
        const DfgValue q = dfg_quadrature(mu, kernel::alpha_from_roughness(r));
        sampling_error = std::max({sampling_error, std::abs(q.a - t.at(i, j, 0)), std::abs(q.b - t.at(i, j, 1))});
      }
    }
  }
  if (o.json) {
    nlohmann::json j = {{"output", out.string()},
                {"size", t.size},
                {"method", o.samples > 0 ? "hammersley" : o.adaptive ? "adaptive quadrature" : "quadrature"},
                {"samples", o.samples},
                {"error", o.samples > 0 ? sampling_error : t.max_error_estimate},
                {"error_meaning", o.samples > 0 ? "max |difference| to the quadrature over a subset of texels"
                                  : o.adaptive  ? "largest per-texel absolute error estimate of the quadrature"
                                                : dfg_error_meaning},
                {"evaluations", t.evaluations},
                {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()}};
    j.update(dfg_conventions_json(o.multiscatter));
    if (ext == ".ktx2") {
      j["container"] = "ktx2";
      j["format"] = o.multiscatter ? "rgba16f" : "rg16f";
      j["vk_format"] = ktx2_image_vk_format_name(ktx2_format);
    }
    print_json(j);
  } else {
    fmt::print("wrote {} ({} x {} DFG table, {})\n", out.string(), t.size, t.size,
               o.samples > 0 ? fmt::format("{} Hammersley samples per texel", o.samples)
                             : std::string(o.adaptive ? "adaptive quadrature" : "quadrature"));
  }
}

void add_bake_dfg(CLI::App& app, Command& command) {
  CLI::App* bake = app.get_subcommand("bake");
  auto o = std::make_shared<DfgCliOptions>();
  auto* sub = bake->add_subcommand("dfg", "split-sum DFG table (scale, bias, albedo) of the GGX model");
  sub->add_option("--out", o->out, "output file: .exr (float), .ktx2 (RG16F; RGBA16F with --multiscatter) or .h (C header)")->required();
  sub->add_option("--size", o->size, "table size N (N x N texels)")->capture_default_str();
  sub->add_option("--samples", o->samples, "Hammersley samples per texel (0: quadrature)")->capture_default_str();
  sub->add_flag("--adaptive", o->adaptive, "adaptive quadrature to 1e-6 per texel (the reference; about 100x slower) instead of the fixed rule");
  sub->add_flag("--multiscatter", o->multiscatter, "add the single-scattering albedo A + B as a third channel");
  sub->add_flag("--json", o->json, "machine-readable output");
  sub->callback([o, sub, &command] {
    std::vector<std::string> given;
    for (const CLI::Option* opt : sub->get_options()) {
      if (opt->count() > 0) given.push_back(opt->get_name());
    }
    command.run = [o, given] { run_dfg(*o, given); };
  });
}

}  // namespace

const CommandRegistration registration_bake_dfg(61, add_bake_dfg);

}  // namespace shadelab::cli
