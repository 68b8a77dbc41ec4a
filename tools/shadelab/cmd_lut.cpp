// shadelab bake lut KIND --out FILE.exr|.ktx2|.json|.png [--size N] [--json]: the lookup tables layered materials
// read, computed per texel by the library's quadrature, for engines; and
// shadelab audit-lut FILE --kind dfg|sheen|coat [--flip-y] [--channel R|G|B] [--json]: a table an engine ships,
// read back and held against the exact integral at each texel.
//
// Kinds (x = N.V = (i + 0.5) / N, column i, left to right; y = the roughness (j + 0.5) / N, row j, row 0 first
// in the file, which is the top in an image viewer; texel centres, as a GPU's bilinear sampler reads them):
// - dfg: R = A, G = B of the split sum (envmap/specular/dfg.h: GGX, height-correlated Smith, Schlick F; y =
//   perceptual roughness, alpha = y^2), B = A + B = the single-scattering albedo E.
// - sheen: R = E of KHR_materials_sheen's lobe with the charlie visibility, G = with the ashikhmin one (sheen.sl;
//   y = sheenRoughness, clamped to >= 0.07 as the model clamps it), B = 0. E exceeds 1 near grazing at low
//   roughness: an 8-bit PNG clips it there (audit-lut measures what that costs).
// - coat: R = G = B = E of KHR_materials_clearcoat's lobe, D V F_schlick(0.04, V.H) (y = clearcoatRoughness):
//   0.04 A + B of the DFG quadrature, Schlick's F being linear in f0.
// Files: .exr (float32 RGB), .ktx2 (RGBA16F, the conventions in its key/value data), .json (the conventions and
// the values, rows of [R, G, B]), .png (8-bit codes round(255 v) without sRGB encoding, as glTF-IBL-Sampler and the
// sample viewer ship theirs: the way to make a viewer's LUT for audit-lut).
#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "cli_common.h"
#include "shadelab/envmap/base/ktx2.h"
#include "shadelab/envmap/base/ktx2_reader.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/image/image.h"
#include "shadelab/image/image_io.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/kernels/tables.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;

std::string lower_ext(const fs::path& p) {
  std::string e = p.extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

void check_kind(const std::string& kind) {
  if (kind != "dfg" && kind != "sheen" && kind != "coat") {
    throw UsageError("KIND: '" + kind + "' is not one of dfg | sheen | coat");
  }
}

// The exact texel at (mu, y) of a kind: three channels.
Rgb exact_texel(const std::string& kind, double mu, double y) {
  if (kind == "sheen") {
    const kernel::SheenAlbedo e = kernel::sheen_directional_albedo(mu, y);
    return {e.e[0], e.e[1], 0.0};
  }
  const DfgValue d = dfg_quadrature(mu, kernel::alpha_from_roughness(y), 1e-8);
  if (kind == "coat") {
    const double e = 0.04 * d.a + d.b;
    return {e, e, e};
  }
  return {d.a, d.b, d.a + d.b};
}

// The whole table, texel by texel (rows on the calling thread: deterministic).
Image exact_table(const std::string& kind, int width, int height, bool flip_y) {
  Image img(width, height);
  for (int j = 0; j < height; ++j) {
    const double y = ((flip_y ? height - 1 - j : j) + 0.5) / height;
    for (int i = 0; i < width; ++i) img.set(i, j, exact_texel(kind, (i + 0.5) / width, y));
  }
  return img;
}

std::string y_meaning(const std::string& kind) {
  if (kind == "sheen") return "sheenRoughness r = (j + 0.5) / size (alpha = r^2; r clamped to >= 0.07)";
  if (kind == "coat") return "clearcoatRoughness r = (j + 0.5) / size (alpha = r^2)";
  return "perceptual roughness r = (j + 0.5) / size (alpha = r^2)";
}

nlohmann::json channels_json(const std::string& kind) {
  if (kind == "sheen") return {"E, charlie visibility", "E, ashikhmin visibility", "0"};
  if (kind == "coat") return {"E of the clearcoat lobe (F0 0.04)", "the same", "the same"};
  return {"A: scale of F0", "B: bias", "A + B: single-scattering albedo (F = 1)"};
}

std::string content(const std::string& kind) {
  if (kind == "sheen") return "directional albedo E(N.V, r) of KHR_materials_sheen's lobe (Charlie D)";
  if (kind == "coat") return "directional albedo E(N.V, r) of KHR_materials_clearcoat's lobe (GGX, Schlick F0 0.04)";
  return "DFG table: split-sum environment BRDF of GGX, height-correlated Smith G2, Schlick F (Karis 2013)";
}

struct BakeLutOptions {
  std::string kind;
  std::string out;
  int size = 64;
  bool json = false;
};

void run_bake_lut(const BakeLutOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  check_kind(o.kind);
  check_range("--size", true, o.size, 2, 1024);
  const fs::path out(o.out);
  require_extension("--out", out, {".exr", ".ktx2", ".json", ".png"}, "the lookup table");
  check_outputs({}, {{"--out", out}});
  work_begins();
  const Image t = exact_table(o.kind, o.size, o.size, false);
  const std::string ext = lower_ext(out);
  nlohmann::json conventions = {{"kind", o.kind},
                                 {"content", content(o.kind)},
                                 {"size", o.size},
                                 {"x", "N.V = (i + 0.5) / size, column i, left to right"},
                                 {"y", y_meaning(o.kind)},
                                 {"orientation", "row 0 (first in the file; the top in an image viewer) is y's smallest value"},
                                 {"channels", channels_json(o.kind)}};
  if (ext == ".exr") {
    unwrap(write_image(t, out));
  } else if (ext == ".png") {
    WriteOptions w;
    w.png_samples = PngSamples::linear;
    unwrap(write_image(t, out, w));
  } else if (ext == ".ktx2") {
    unwrap(write_ktx2_image(t, out, Ktx2ImageFormat::rgba16f,
                            {{"shadelab.content", content(o.kind)},
                             {"shadelab.lut_axes", "x (s, column i) = N.V = (i + 0.5) / width; y (t, row j, row 0 first) = " +
                                                       y_meaning(o.kind)},
                             {"shadelab.lut_channels", channels_json(o.kind).dump()}}));
  } else {
    nlohmann::json rows = nlohmann::json::array();
    for (int j = 0; j < t.height; ++j) {
      nlohmann::json row = nlohmann::json::array();
      for (int i = 0; i < t.width; ++i) {
        const Rgb v = t.at(i, j);
        row.push_back({v.r, v.g, v.b});
      }
      rows.push_back(row);
    }
    nlohmann::json doc = conventions;
    doc["values"] = rows;
    const std::string text = doc.dump() + "\n";
    unwrap(write_file_atomically(out, std::vector<char>(text.begin(), text.end())));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (o.json) {
    conventions["output"] = out.string();
    conventions["seconds"] = seconds;
    if (ext == ".png") conventions["encoding"] = "8-bit codes round(255 v), no sRGB encoding; values above 1 clip";
    print_json(conventions);
  } else {
    fmt::print("wrote {} ({} x {} {} table, quadrature per texel, {:.1f} s)\n", out.string(), o.size, o.size, o.kind, seconds);
  }
}

struct AuditOptions {
  std::string file;
  std::string kind;
  bool flip_y = false;
  std::string channel = "R";
  bool json = false;
};

// A 2D KTX 2 table (level 0; RGBA16F as `bake lut` writes it, or any float format the reader takes) as an image of
// its first three channels. A cube map, a texture over 1024 x 1024 texels or a NaN / Inf texel is an error naming the
// file.
Image read_ktx2_table(const fs::path& in, ReadInfo& info) {
  const Ktx2Texture k = unwrap(read_ktx2(in));
  if (k.faces != 1) {
    throw UsageError(fmt::format("'{}': a cube map ({} faces); audit-lut reads a 2D table", in.string(), k.faces));
  }
  if (k.width > 1024 || k.height > 1024) {
    throw UsageError(fmt::format("'{}': {} x {} texels; audit-lut reads tables up to 1024 x 1024", in.string(), k.width,
                                 k.height));
  }
  Image img(k.width, k.height);
  for (int y = 0; y < k.height; ++y) {
    for (int x = 0; x < k.width; ++x) {
      const float* t = k.texel(0, 0, x, y);
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(t[c])) {
          throw UsageError(fmt::format("'{}': texel ({}, {}) channel {} of level 0 is not finite", in.string(), x, y, "RGB"[c]));
        }
      }
      img.set(x, y, Rgb{t[0], t[1], t[2]});
    }
  }
  info.format = "ktx2";
  switch (k.vk_format) {
    case 97: info.sample_type = "half"; break;    // VK_FORMAT_R16G16B16A16_SFLOAT
    case 83: info.sample_type = "half"; break;    // VK_FORMAT_R16G16_SFLOAT
    case 109: info.sample_type = "float"; break;  // VK_FORMAT_R32G32B32A32_SFLOAT
    default: info.sample_type = "vkFormat " + std::to_string(k.vk_format); break;
  }
  return img;
}

void run_audit(const AuditOptions& o) {
  check_kind(o.kind);
  if (o.channel != "R" && o.channel != "G" && o.channel != "B") {
    throw UsageError("--channel: '" + o.channel + "' is not one of R | G | B");
  }
  const fs::path in(o.file);
  require_extension("FILE", in, {".exr", ".ktx2", ".png"}, "the lookup table");
  ReadInfo info;
  const Image lut = lower_ext(in) == ".ktx2" ? read_ktx2_table(in, info)
                                             : unwrap(read_image(in, &info, image_read_budget_bytes, PngSamples::linear));
  if (lut.width > 1024 || lut.height > 1024) {
    throw UsageError(fmt::format("'{}': {} x {} texels; audit-lut reads tables up to 1024 x 1024", in.string(), lut.width,
                                 lut.height));
  }
  work_begins();
  // Which channels hold the table: dfg R = A and G = B; sheen the chosen channel against the visibility it names
  // (R charlie, G ashikhmin; B compared with charlie); coat the chosen channel.
  const int ch = o.channel == "R" ? 0 : (o.channel == "G" ? 1 : 2);
  const Image exact = exact_table(o.kind, lut.width, lut.height, o.flip_y);
  struct Stat {
    double max = 0.0, sum = 0.0, signed_sum = 0.0;
    int x = 0, y = 0;
    double at_value = 0.0, at_exact = 0.0;
  };
  const int comps = o.kind == "dfg" ? 2 : 1;
  std::vector<Stat> stats(static_cast<std::size_t>(comps));
  for (int j = 0; j < lut.height; ++j) {
    for (int i = 0; i < lut.width; ++i) {
      for (int c = 0; c < comps; ++c) {
        const int file_channel = o.kind == "dfg" ? c : ch;
        const int exact_channel = o.kind == "dfg" ? c : (o.kind == "sheen" ? (ch == 1 ? 1 : 0) : 0);
        const double v = lut.at(i, j)[file_channel];
        const double e = exact.at(i, j)[exact_channel];
        Stat& s = stats[static_cast<std::size_t>(c)];
        const double d = v - e;
        s.sum += std::abs(d);
        s.signed_sum += d;
        if (std::abs(d) > s.max) {
          s.max = std::abs(d);
          s.x = i;
          s.y = j;
          s.at_value = v;
          s.at_exact = e;
        }
      }
    }
  }
  const double n = static_cast<double>(lut.width) * lut.height;
  const char* names_dfg[] = {"A", "B"};
  nlohmann::json comps_json = nlohmann::json::array();
  for (int c = 0; c < comps; ++c) {
    const Stat& s = stats[static_cast<std::size_t>(c)];
    const double mu = (s.x + 0.5) / lut.width;
    const double y = ((o.flip_y ? lut.height - 1 - s.y : s.y) + 0.5) / lut.height;
    const std::string name = o.kind == "dfg" ? names_dfg[c] : (o.kind == "sheen" ? (ch == 1 ? "E ashikhmin" : "E charlie") : "E");
    comps_json.push_back({{"quantity", name},
                          {"max_error", s.max},
                          {"mean_error", s.sum / n},
                          {"bias", s.signed_sum / n},
                          {"at", {{"x", s.x}, {"y", s.y}, {"n_dot_v", mu}, {"roughness", y}, {"value", s.at_value}, {"exact", s.at_exact}}}});
  }
  if (o.json) {
    print_json({{"file", in.string()},
                {"kind", o.kind},
                {"width", lut.width},
                {"height", lut.height},
                {"format", info.format},
                {"sample_type", info.sample_type},
                {"flip_y", o.flip_y},
                {"quantities", comps_json}});
    return;
  }
  fmt::print("{}: {} x {} {} ({} {}), against the exact integral at each texel centre\n", in.string(), lut.width, lut.height,
             o.kind, info.format, info.sample_type);
  for (const auto& q : comps_json) {
    fmt::print("  {:<12} max |error| {:.3g} at N.V {:.4f}, roughness {:.4f} ({:.5f} vs {:.5f}); mean |error| {:.3g}; "
               "bias {:+.3g}\n",
               q["quantity"].get<std::string>(), q["max_error"].get<double>(), q["at"]["n_dot_v"].get<double>(),
               q["at"]["roughness"].get<double>(), q["at"]["value"].get<double>(), q["at"]["exact"].get<double>(),
               q["mean_error"].get<double>(), q["bias"].get<double>());
  }
}

void add_lut_commands(CLI::App& app, Command& command) {
  CLI::App* bake = app.get_subcommand("bake");
  auto b = std::make_shared<BakeLutOptions>();
  auto* sub = bake->add_subcommand("lut", "lookup tables of layered materials (dfg, sheen, coat) for engines");
  sub->add_option("kind", b->kind, "dfg | sheen | coat")->required();
  sub->add_option("--out", b->out, "output file: .exr (float), .ktx2 (RGBA16F), .json, or .png (8-bit, as viewers ship)")
      ->required();
  sub->add_option("--size", b->size, "table size N (N x N texels)")->capture_default_str();
  sub->add_flag("--json", b->json, "machine-readable output");
  sub->callback([b, &command] { command.run = [b] { run_bake_lut(*b); }; });

  auto a = std::make_shared<AuditOptions>();
  auto* audit = app.add_subcommand("audit-lut", "hold a lookup table an engine ships against the exact integral");
  audit->add_option("file", a->file, "the table: .png (8- or 16-bit, read as linear codes), .exr or .ktx2 (2D, float)")->required();
  audit->add_option("--kind", a->kind, "dfg | sheen | coat")->required();
  audit->add_flag("--flip-y", a->flip_y, "row 0 of the file is the largest roughness (OpenGL's bottom-up rows)");
  audit->add_option("--channel", a->channel, "sheen / coat: the channel holding E (sheen: R charlie, G ashikhmin)")
      ->capture_default_str();
  audit->add_flag("--json", a->json, "machine-readable output");
  audit->callback([a, &command] { command.run = [a] { run_audit(*a); }; });
}

}  // namespace

const CommandRegistration registration_lut(63, add_lut_commands);

}  // namespace shadelab::cli
