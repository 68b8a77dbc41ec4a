// The shadelab command line as a function (main.cpp calls it; the CLI fuzz harness, fuzz/fuzz_cli.cpp, calls
// it in validation-only mode). Exit codes: 0 success, 1 a check that ran and failed (or a render with
// non-finite samples), 2 bad input (one line on stderr naming the problem), 3 an internal error.
// Every message is one printable line of bounded length (core/text.h).
#include <fmt/core.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <iostream>
#include <new>

#include "cli_common.h"
#include "shadelab/core/text.h"

namespace shadelab::cli {

namespace {
std::atomic<bool> g_validation_only{false};
}  // namespace

void set_validation_only(bool on) { g_validation_only.store(on); }

void work_begins() {
  if (g_validation_only.load()) throw ValidationDone{};
}

int run_cli(int argc, const char* const* argv) {
  CLI::App app{"shadelab: physically based shading, correct and checkable"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "shadelab 0.1.0");
  Command command;
  auto entries = command_registry();
  std::sort(entries.begin(), entries.end(), [](const CommandEntry& a, const CommandEntry& b) { return a.order < b.order; });
  for (const auto& e : entries) e.add(app, command);
  if (argc > 1 && argv[1][0] != '-') {
    // An unknown command gets a message naming it, not CLI11's "a subcommand is required".
    std::string names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
      known = known || sub->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::cerr << "shadelab: unknown command '" << shadelab::printable(argv[1]) << "' (commands: " << names << ")\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::CallForVersion& v) {
    std::cout << v.what() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    // One line, exit code 2, whatever CLI11's own code would have been.
    std::cerr << "shadelab: " << shadelab::printable_message(e.what()) << " (see --help)\n";
    return 2;
  }
  try {
    if (command.run) command.run();
  } catch (const ValidationDone&) {
    return 0;  // validation-only mode: the command's options and inputs passed
  } catch (const UsageError& e) {
    std::cerr << "shadelab: " << shadelab::printable_message(e.what()) << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    // The inputs are within the documented limits (docs/testing.md) but the machine's memory is not.
    std::cerr << "shadelab: out of memory (the input is within shadelab's limits; this machine has too little memory for it)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "shadelab: internal error: " << shadelab::printable_message(e.what()) << "\n";
    return 3;
  }
  return 0;
}

}  // namespace shadelab::cli
