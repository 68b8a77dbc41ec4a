// Shared pieces of the shadelab CLI: the usage-error type (exit code 2), argument parsers that name the
// offending option, and output helpers. Only the CLI prints; the library returns errors.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/color/rgb.h"
#include "shadelab/core/error.h"
#include "shadelab/core/vec.h"

namespace shadelab::cli {

// Bad input from the user: printed as one line "shadelab: <message>" and exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

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

// Writes JSON to stdout, indented, with a final newline.
void print_json(const nlohmann::json& j);

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
