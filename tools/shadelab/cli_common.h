// Shared pieces of the shadelab CLI: the usage-error type (exit code 2), argument parsers that name the
// offending option, and output helpers. Only the CLI prints; the library returns errors.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/color/rgb.h"
#include "shadelab/core/error.h"
#include "shadelab/core/vec.h"
#include "shadelab/render/film.h"
#include "shadelab/scene/scene.h"

namespace shadelab::cli {

// Bad input from the user: printed as one line "shadelab: <message>" and exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The display options of every command that writes an image for people (render, merge, sheet, report; docs/color.md):
// --view standard|filmic|pbr-neutral|agx|aces|OCIO:<config>:<display>:<view>, --look (OCIO looks), --ocio-config
// (the config of an OCIO view given as OCIO::<display>:<view>, instead of $OCIO). `filmic` is the older --filmic
// flag where a command has it (an alias of --view filmic).
struct ViewCliOptions {
  std::string view;
  std::string look;
  std::string ocio_config;
  bool filmic = false;
};
// Adds --view, --look and --ocio-config (and --filmic when `filmic_flag`) to `sub`.
void add_view_options(CLI::App* sub, ViewCliOptions& o, const std::string& default_view, bool filmic_flag);
// The one parse and check of those options (UsageError naming the option: exit 2): the view, the default when
// --view is not given; an OCIO view is tried once on one pixel, so a bad config, display, view or look is an
// error before any work.
DisplayView parse_view_options(const ViewCliOptions& o, ViewTransform default_view);

template <typename T>
T unwrap(Result<T> r) {
  if (!r) throw UsageError(r.error().message);
  return std::move(r).value();
}

// "X,Y,Z" -> a unit vector; zero, non-finite or malformed vectors are errors naming the option.
Vec3 parse_direction(const std::string& option, const std::string& text);

// --param NAME=VALUE list -> assignments.
ParamAssignments parse_assignments(const std::vector<std::string>& params);

// Builds a model, turning errors into UsageError.
BrdfPtr build_brdf(const std::string& model, const std::vector<std::string>& params);

nlohmann::json to_json(const Rgb& c);

// Writes JSON to stdout, indented, with a final newline. Strings that are not UTF-8 (file names) have
// their bad bytes replaced by U+FFFD rather than failing the dump.
void print_json(const nlohmann::json& j);
// A JSON file's text (indent 2, a final newline). Paths may hold bytes that are not UTF-8 (Linux allows them):
// those are written as U+FFFD, as print_json does, instead of the JSON library throwing.
std::vector<char> json_file_bytes(const nlohmann::json& j);

// A file a command reads or writes, and the option or argument that names it (for messages).
struct NamedPath {
  std::string option;
  std::filesystem::path path;
};

// Whether a command's output folders must exist (most) or are created by the command (bake ibl --out-dir,
// ibl-error --out, report --out).
enum class OutputFolders { must_exist, created };

// Refuses (UsageError, exit 2) an output that is one of the inputs or another output of the same command.
// Paths are compared as real paths: symbolic links and ".." resolved, hard links of existing files found.
// Every output is also checked writable before any work (issue 40, finding 8: a missing folder was reported
// after the whole render): not a folder itself, its folder (or, for `created`, the nearest that exists) a
// folder this process can write into. (When an input is missing, that is said first, by the command's reader.)
void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs,
                   OutputFolders folders = OutputFolders::must_exist);
// The writability check alone, for one output.
void check_output_writable(const NamedPath& output, OutputFolders folders = OutputFolders::must_exist);

// Refuses a path whose extension (case-insensitive) is not one of `allowed` (".png", ...).
void require_extension(const std::string& option, const std::filesystem::path& path,
                       const std::vector<std::string>& allowed, const std::string& what);

// The files a loaded scene read: the scene file, file textures, the environment map, mesh files.
std::vector<NamedPath> scene_inputs(const Scene& scene);

// A count option: when `given`, `value` must lie in [lo, hi]; the message names the option.
void check_range(const std::string& option, bool given, long long value, long long lo, long long hi);

// A seed: a decimal integer in [0, 2^64 - 1], nothing else (no sign, no wrap-around, no saturation).
std::uint64_t parse_seed(const std::string& option, const std::string& text);

// The built-in default scene (scene/default_scene.h), built once per process and copied by the commands
// that render it: its procedural textures take a while, and the CLI fuzz harness asks for it again and again.
const Scene& built_in_scene();

// A warning line on stderr ("shadelab: warning: ..."), printable and bounded like an error.
void warn(const std::string& message);

// The whole command line (main.cpp): parses argv, runs the command, maps errors to exit codes 0/1/2/3.
int run_cli(int argc, const char* const* argv);

// A command calls work_begins() where its options and inputs are checked and its work (rendering, baking,
// quadrature, writing files) starts. Normally it does nothing; in validation-only mode (set by the CLI fuzz
// harness, fuzz/fuzz_cli.cpp) it throws ValidationDone, which run_cli turns into exit code 0, so the parse
// and validation path runs without the work and without writing anything.
struct ValidationDone {};
void work_begins();
void set_validation_only(bool on);

// Commands register themselves on the app and store the action to run after parsing.
struct Command {
  std::function<void()> run;
};

// Each cmd_*.cpp registers its command with a static CommandRegistration; main adds them in `order`.
using AddCommand = void (*)(CLI::App& app, Command& command);
struct CommandEntry {
  int order;
  AddCommand add;
};
std::vector<CommandEntry>& command_registry();
struct CommandRegistration {
  CommandRegistration(int order, AddCommand add) { command_registry().push_back({order, add}); }
};

}  // namespace shadelab::cli
