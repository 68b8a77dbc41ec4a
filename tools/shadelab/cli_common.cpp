#include "cli_common.h"

#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iostream>
#include <system_error>

#include <unistd.h>

#include "shadelab/core/text.h"
#include "shadelab/scene/default_scene.h"

namespace shadelab::cli {

Vec3 parse_direction(const std::string& option, const std::string& text) {
  auto nums = parse_numbers(text);
  if (!nums) throw UsageError(option + ": " + nums.error().message);
  if (nums->size() != 3) throw UsageError(option + ": expected X,Y,Z, got '" + text + "'");
  const Vec3 v{(*nums)[0], (*nums)[1], (*nums)[2]};
  const double len = length(v);
  if (!(len > 0.0) || !std::isfinite(len)) throw UsageError(option + ": the vector '" + text + "' has zero length");
  return v / len;  // directions are normalized; docs/cli.md says so
}

ParamAssignments parse_assignments(const std::vector<std::string>& params) {
  ParamAssignments out;
  for (const auto& p : params) out.push_back(unwrap(split_assignment(p)));
  return out;
}

BrdfPtr build_brdf(const std::string& model, const std::vector<std::string>& params) {
  return unwrap(make_brdf(model, parse_assignments(params)));
}

nlohmann::json to_json(const Rgb& c) { return nlohmann::json::array({c.r, c.g, c.b}); }

namespace {

// Indented JSON with a final newline; bytes that are not UTF-8 become U+FFFD instead of the dump throwing.
std::string json_text(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace

void print_json(const nlohmann::json& j) { std::cout << json_text(j); }

std::vector<char> json_file_bytes(const nlohmann::json& j) {
  const std::string text = json_text(j);
  return {text.begin(), text.end()};
}

namespace {

namespace fs = std::filesystem;

fs::path real_path(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p, ec), ec);
  return ec ? fs::absolute(p).lexically_normal() : r;
}

bool same_file(const fs::path& a, const fs::path& b) {
  if (real_path(a) == real_path(b)) return true;
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec;
}

std::string lower_ext(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

}  // namespace

void check_output_writable(const NamedPath& out, OutputFolders folders) {
  const fs::path& p = out.path;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (fs::is_directory(st) || (fs::is_symlink(st) && fs::is_directory(p, ec))) {
    throw UsageError(out.option + ": '" + p.string() + "' is a folder; give a file name");
  }
  // The folder the file goes into; where the command creates it, the nearest folder that exists.
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (folders == OutputFolders::created) {
    while (!fs::exists(dir, ec) && dir.has_parent_path() && dir.parent_path() != dir) dir = dir.parent_path();
    if (!fs::exists(dir, ec)) dir = ".";
  }
  const fs::file_status ds = fs::status(dir, ec);
  if (!fs::exists(ds)) {
    throw UsageError(out.option + ": '" + p.string() + "': the folder '" + dir.string() + "' does not exist");
  }
  if (!fs::is_directory(ds)) {
    throw UsageError(out.option + ": '" + p.string() + "': '" + dir.string() + "' is not a folder");
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw UsageError(out.option + ": '" + p.string() + "': cannot write into the folder '" + dir.string() +
                     "': " + std::system_category().message(errno));
  }
}

void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs, OutputFolders folders) {
  // A missing input is the first thing to say (the command's reader says it, with its own words, right after
  // these checks and before any work), so the outputs' folders are checked only when every input is there.
  const bool inputs_present = std::all_of(inputs.begin(), inputs.end(), [](const NamedPath& in) {
    std::error_code ec;
    return in.path.empty() || fs::exists(fs::symlink_status(in.path, ec));
  });
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& out = outputs[i];
    if (out.path.empty()) continue;
    if (inputs_present) check_output_writable(out, folders);
    for (const NamedPath& in : inputs) {
      if (!in.path.empty() && same_file(out.path, in.path)) {
        throw UsageError(out.option + ": '" + out.path.string() + "' is the input " + in.option + " ('" +
                         in.path.string() + "'); refusing to overwrite it");
      }
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (!outputs[k].path.empty() && same_file(out.path, outputs[k].path)) {
        throw UsageError(out.option + ": '" + out.path.string() + "' is also the output of " + outputs[k].option +
                         "; give each output its own file");
      }
    }
  }
}

void require_extension(const std::string& option, const fs::path& path, const std::vector<std::string>& allowed,
                       const std::string& what) {
  const std::string ext = lower_ext(path);
  if (std::find(allowed.begin(), allowed.end(), ext) != allowed.end()) return;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : " or ") + a;
  throw UsageError(option + ": " + what + " must be written to a " + list + " file, got '" + path.string() + "'");
}

std::vector<NamedPath> scene_inputs(const Scene& scene) {
  std::vector<NamedPath> in;
  std::error_code ec;
  if (fs::exists(scene.source, ec)) in.push_back({"SCENE", scene.source});
  for (const Texture& t : scene.textures) {
    if (t.source.rfind("procedural ", 0) != 0) in.push_back({"the scene's texture '" + t.name + "'", t.source});
  }
  if (scene.environment.kind == Environment::Kind::image) {
    in.push_back({"the scene's environment", scene.environment.source});
  }
  for (const MeshShape& m : scene.meshes) in.push_back({"the scene's mesh", m.source});
  return in;
}

void check_range(const std::string& option, bool given, long long value, long long lo, long long hi) {
  if (given && (value < lo || value > hi)) {
    throw UsageError(option + ": " + std::to_string(value) + " is out of range [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
  }
}

std::uint64_t parse_seed(const std::string& option, const std::string& text) {
  std::uint64_t v = 0;
  const char* end = text.data() + text.size();
  const auto [p, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || p != end) {
    throw UsageError(option + ": '" + text + "' is not an integer in [0, 18446744073709551615]");
  }
  return v;
}

const Scene& built_in_scene() {
  static const Scene scene = default_scene();
  return scene;
}

void warn(const std::string& message) { std::cerr << "shadelab: warning: " << printable_message(message) << "\n"; }

std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> entries;
  return entries;
}

void add_view_options(CLI::App* sub, ViewCliOptions& o, const std::string& default_view, bool filmic_flag) {
  sub->add_option("--view", o.view,
                  "PNG view transform: standard (clamp), filmic, pbr-neutral (Khronos PBR Neutral), agx (AgX Base), aces "
                  "(Hill's ACES fit) or OCIO:<config>:<display>:<view> (docs/color.md; default: " + default_view + ")");
  sub->add_option("--look", o.look, "OpenColorIO look(s) applied before an OCIO view (OCIO's list syntax)");
  sub->add_option("--ocio-config", o.ocio_config, "OpenColorIO config for --view OCIO::<display>:<view> (default: $OCIO)");
  if (filmic_flag) sub->add_flag("--filmic", o.filmic, "PNG through the filmic curve (the same as --view filmic)");
}

DisplayView parse_view_options(const ViewCliOptions& o, ViewTransform default_view) {
  DisplayView v;
  v.transform = default_view;
  if (!o.view.empty()) {
    auto parsed = parse_view(o.view);
    if (!parsed) throw UsageError("--view: " + parsed.error().message);
    v = *parsed;
    if (o.filmic && v.transform != ViewTransform::filmic) throw UsageError("--filmic: conflicts with --view " + printable(o.view));
  } else if (o.filmic) {
    v.transform = ViewTransform::filmic;
  }
  if (v.transform != ViewTransform::ocio) {
    if (!o.look.empty()) throw UsageError("--look: looks are OpenColorIO's; give an OCIO view (--view OCIO:<config>:<display>:<view>)");
    if (!o.ocio_config.empty()) throw UsageError("--ocio-config: needs an OCIO view (--view OCIO::<display>:<view>)");
    return v;
  }
  if (!o.ocio_config.empty()) {
    if (!v.ocio_config.empty()) throw UsageError("--ocio-config: the --view already names a config (" + printable(v.ocio_config) + ")");
    v.ocio_config = o.ocio_config;
  }
  v.looks = o.look;
  Image probe(1, 1);
  probe.set(0, 0, Rgb::gray(0.18));
  if (auto ok = apply_view(probe, 0.0, v); !ok) throw UsageError("--view: " + ok.error().message);
  return v;
}

}  // namespace shadelab::cli
