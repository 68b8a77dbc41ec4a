// shadelab shader MODEL [--param NAME=VALUE ...] --lang glsl|essl|hlsl [--out FILE] [--entry NAME] [--uniforms]
//                [--tables-out FILE] [--ibl]
// shadelab shader verify MODEL [--param ...] --lang glsl|essl|hlsl [--source FILE] [--cases N] [--json]
//                       [--entry NAME] [--uniforms] [--device all|vulkan|webgl2] [--tolerance X] [--seed N]
//                       [--ibl ENV|BAKE_DIR [--ibl-size N]]
// Exports a model as a shader function file, or verifies a shader (exported or the user's) on real drivers
// against the C++ reference (docs/shaders.md). verify exits 0 when the shader agrees, 1 when it does not.
#include <fmt/core.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "cli_common.h"
#include "export.h"
#include "process.h"
#include "shadelab/image/image_io.h"
#include "verify.h"
#include "verify_ibl.h"

namespace shadelab::cli {

namespace {

struct ShaderOptions {
  std::vector<std::string> args;  // MODEL, or verify MODEL
  std::vector<std::string> params;
  std::string lang;
  std::string out;
  std::string tables_out;
  std::string entry;
  bool uniforms = false;
  std::string source;
  std::size_t cases = 100000;
  bool json = false;
  std::string device = "all";
  double tolerance = shaders::kDefaultTolerance;
  std::uint64_t seed = shaders::kDefaultSeed;
  std::string ibl;      // export: present (a flag); verify: the environment or a bake directory
  int ibl_size = 128;
};

std::string command_line(const ShaderOptions& o, const std::string& model) {
  std::string s = "shadelab shader " + model;
  for (const auto& p : o.params) s += " --param " + p;
  s += " --lang " + o.lang;
  if (!o.entry.empty()) s += " --entry " + o.entry;
  if (o.uniforms) s += " --uniforms";
  if (!o.ibl.empty()) s += " --ibl";
  return s;
}

nlohmann::json array3(const auto& a) { return nlohmann::json::array({a[0], a[1], a[2]}); }

std::string vec_text(const auto& a) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", a[0], a[1], a[2]); }

void run_verify(const ShaderOptions& o, const std::string& model, bool ibl, bool tolerance_given) {
  shaders::VerifyOptions v;
  v.model = model;
  v.params = parse_assignments(o.params);
  v.lang = unwrap(shaders::parse_lang(o.lang));
  v.source = o.source;
  v.entry = o.entry;
  v.cases = o.cases;
  v.uniforms = o.uniforms;
  v.tolerance = o.tolerance;
  v.seed = o.seed;
  if (o.device == "all") v.device = shaders::VerifyDevice::all;
  else if (o.device == "vulkan") v.device = shaders::VerifyDevice::vulkan;
  else if (o.device == "webgl2") v.device = shaders::VerifyDevice::webgl2;
  else throw UsageError("--device: unknown device '" + o.device + "' (devices: all, vulkan, webgl2)");
  std::optional<shaders::TempDir> bake_dir;
  if (ibl) {
    if (o.ibl.empty()) throw UsageError("--ibl: verify needs the environment (or a `bake ibl` directory): --ibl ENV");
    if (o.ibl_size < 8 || o.ibl_size > 1024) throw UsageError("--ibl-size: " + std::to_string(o.ibl_size) + " is out of range [8, 1024]");
    std::error_code ec;
    if (!std::filesystem::exists(o.ibl, ec)) throw UsageError("--ibl: " + o.ibl + ": no such file or directory");
    v.ibl_size = o.ibl_size;
    if (!tolerance_given) v.tolerance = shaders::kIblTolerance;
    work_begins();
    if (std::filesystem::is_directory(o.ibl, ec)) {
      v.ibl_dir = o.ibl;
    } else {
      // The files `bake ibl ENV` writes, with its defaults: this program run as `bake ibl`.
      bake_dir.emplace("shadelab-verify-ibl");
      const std::string out = (bake_dir->path() / "bake").string();
      auto run = unwrap(shaders::run_process({"/proc/self/exe", "bake", "ibl", o.ibl, "--out-dir", out}, 600.0));
      if (run.exit_code != 0) {
        const std::string why = run.err.substr(0, run.err.find('\n'));
        // The bake's own line names the file and what is wrong with it: said as --ibl's (not as a `bake ibl`
        // command the user never typed).
        if (run.exit_code == 2) throw UsageError("--ibl: " + (why.rfind("shadelab: ", 0) == 0 ? why.substr(10) : why));
        throw std::runtime_error("--ibl: bake ibl " + o.ibl + " failed (exit code " + std::to_string(run.exit_code) + "): " + why);
      }
      v.ibl_dir = out;
    }
  } else {
    work_begins();
  }
  const shaders::VerifyReport r = unwrap(shaders::verify_shader(v));
  const shaders::DeviceReport& c = r.combined;
  if (o.json) {
    nlohmann::json worst = nullptr;
    if (c.worst) {
      worst = {{"wi", array3(c.worst->wi)}, {"wo", array3(c.worst->wo)}, {"shader", array3(c.worst->shader)},
               {"reference", array3(c.worst->reference)}};
    }
    nlohmann::json j = {{"device", c.device}, {"lang", o.lang}, {"cases", c.cases}, {"max_rel_error", c.max_rel_error},
                        {"mean_rel_error", c.mean_rel_error}, {"nonfinite", c.nonfinite}, {"worst", worst}};
    if (ibl) {
      j["pixels"] = r.pixels;
      j["tolerance"] = r.tolerance;
      j["worst"] = c.worst ? nlohmann::json{{"n", array3(c.worst->wi)}, {"v", array3(c.worst->wo)}, {"shader", array3(c.worst->shader)},
                                            {"reference", array3(c.worst->reference)}}
                           : nlohmann::json(nullptr);
    }
    print_json(j);
  } else {
    fmt::print("shader verify {} ({}, {}{})\n", model, shaders::lang_display_name(v.lang),
               o.source.empty() ? "the exported shader" : o.source, ibl ? ", environment lighting under " + o.ibl : "");
    for (const auto& d : r.devices) {
      if (ibl) {
        fmt::print("  device: {}\n", d.device);
        fmt::print("    pixels: {} (a {} x {} sphere, N.V >= {:g}; against render --mode game with the same files)\n",
                   d.cases, v.ibl_size, v.ibl_size, shaders::kIblMinCosine);
        fmt::print("    max relative error: {:.3g}   mean: {:.3g}   (|shader - reference| / max(|reference|, {:g}))\n",
                   d.max_rel_error, d.mean_rel_error, shaders::kRelativeErrorFloor);
        fmt::print("    non-finite outputs: {}\n", d.nonfinite);
        if (d.worst) {
          fmt::print("    worst pixel: n = {}, v = {}\n      shader    {}\n      reference {}\n", vec_text(d.worst->wi),
                     vec_text(d.worst->wo), vec_text(d.worst->shader), vec_text(d.worst->reference));
        }
        continue;
      }
      fmt::print("  device: {}\n", d.device);
      fmt::print("    cases: {} (seed {}; grazing, on- and below-horizon pairs included)\n", d.cases, v.seed);
      fmt::print("    max relative error: {:.3g}   mean: {:.3g}   (|shader - reference| / max(|reference|, {:g} /sr))\n",
                 d.max_rel_error, d.mean_rel_error, shaders::kRelativeErrorFloor);
      fmt::print("    non-finite outputs: {}\n", d.nonfinite);
      if (d.worst) {
        fmt::print("    worst case: wi = {}, wo = {}\n      shader    {}\n      reference {}\n", vec_text(d.worst->wi),
                   vec_text(d.worst->wo), vec_text(d.worst->shader), vec_text(d.worst->reference));
      }
    }
    fmt::print("{} (tolerance {:g}, no NaN or Inf)\n", r.passed ? "PASS" : "FAIL", r.tolerance);
  }
  std::cout.flush();
  if (!r.passed) std::exit(1);  // documented: the shader ran and differs from the reference
}

void run_export(const ShaderOptions& o, const std::string& model) {
  shaders::ExportOptions e;
  e.lang = unwrap(shaders::parse_lang(o.lang));
  e.entry = o.entry;
  e.uniforms = o.uniforms;
  e.command = command_line(o, model);
  e.ibl = !o.ibl.empty();
  const shaders::ShaderExport ex = unwrap(shaders::export_model(model, parse_assignments(o.params), e));
  if (!o.tables_out.empty() && ex.tables_data.empty()) {
    throw UsageError("--tables-out: the model '" + model + "' with these parameters reads no tables");
  }
  check_outputs({}, {{"--out", o.out}, {"--tables-out", o.tables_out}});  // writable, and not one file twice
  work_begins();
  // The shader and its tables are one output set (issue 40, finding 7): replaced together or not at all.
  std::vector<std::pair<std::filesystem::path, std::vector<char>>> files;
  if (!o.tables_out.empty()) files.emplace_back(o.tables_out, std::vector<char>(ex.tables_data.begin(), ex.tables_data.end()));
  if (!o.out.empty()) files.emplace_back(o.out, std::vector<char>(ex.text.begin(), ex.text.end()));
  unwrap(write_files_atomically(files));
  if (o.out.empty()) std::cout << ex.text;
}

void add_shader_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<ShaderOptions>();
  auto* sub = app.add_subcommand(
      "shader", "export a model as a GLSL / GLSL ES / HLSL function file (shader MODEL), or check a shader on real "
                "drivers against the C++ reference (shader verify MODEL; exit 1 when it differs)");
  sub->add_option("args", o->args, "MODEL, or verify MODEL")->required();
  sub->add_option("--param", o->params, "NAME=VALUE, repeatable (see brdf list)");
  sub->add_option("--lang", o->lang, "glsl (4.50), essl (GLSL ES 3.00) or hlsl (SM 5)")->required();
  sub->add_option("--out", o->out, "export: write the file here instead of stdout");
  sub->add_option("--tables-out", o->tables_out,
                  "export: write the bytes of the GGX energy tables' uniform block (std140 vec4, little-endian float) "
                  "here, for models that read them");
  sub->add_option("--entry", o->entry, "the f_r function's name (default brdf_MODEL, '-' as '_')");
  sub->add_flag("--uniforms", o->uniforms, "parameters in a uniform block (std140) instead of baked constants");
  sub->add_option("--source", o->source, "verify: the user's shader file, defining the entry");
  sub->add_option("--cases", o->cases, "verify: number of direction pairs")->capture_default_str();
  sub->add_flag("--json", o->json, "verify: machine-readable report");
  sub->add_option("--device", o->device, "verify: all, vulkan (lavapipe) or webgl2 (headless Chromium; essl only)")
      ->capture_default_str();
  sub->add_option("--tolerance", o->tolerance, "verify: the largest relative error that passes")->capture_default_str();
  sub->add_option("--seed", o->seed, "verify: seed of the direction pairs")->capture_default_str();
  sub->add_option("--ibl", o->ibl,
                  "export: also the environment lighting of `bake ibl`'s files (SH9 + split sum; ggx, filament); verify: "
                  "check it under ENV (an environment image, baked with bake ibl's defaults, or a bake ibl directory)")
      ->expected(0, 1);
  sub->add_option("--ibl-size", o->ibl_size, "verify --ibl: the sphere's image size in pixels")->capture_default_str();
  sub->callback([o, &command, sub] {
    command.run = [o, sub] {
      const bool verify = !o->args.empty() && o->args[0] == "verify";
      if (o->args.size() != (verify ? 2u : 1u)) {
        throw UsageError(verify ? "shader verify: expected one MODEL" : "shader: expected one MODEL (or verify MODEL)");
      }
      const std::string& model = o->args.back();
      if (verify) {
        if (sub->count("--out") > 0) throw UsageError("--out: only for shader export (shader MODEL)");
        if (sub->count("--tables-out") > 0) throw UsageError("--tables-out: only for shader export (shader MODEL)");
        if (sub->count("--ibl-size") > 0 && sub->count("--ibl") == 0) throw UsageError("--ibl-size: only with --ibl");
        run_verify(*o, model, sub->count("--ibl") > 0, sub->count("--tolerance") > 0);
      } else {
        if (sub->count("--ibl") > 0 && !o->ibl.empty()) {
          throw UsageError("--ibl: export takes no value (put --ibl after MODEL); verify takes the environment");
        }
        if (sub->count("--ibl") > 0) o->ibl = "yes";
        for (const char* flag : {"--source", "--cases", "--json", "--device", "--tolerance", "--seed", "--ibl-size"}) {
          if (sub->count(flag) > 0) throw UsageError(std::string(flag) + ": only for shader verify");
        }
        run_export(*o, model);
      }
    };
  });
}

}  // namespace

const CommandRegistration registration_shader(95, add_shader_command);

}  // namespace shadelab::cli
