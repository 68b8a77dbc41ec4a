// Fuzz harness: the CLI's argument parsing and validation (run_cli in validation-only mode: every command
// checks its options and inputs, then stops where its work would start, cli_common.h work_begins; cheap
// commands such as brdf eval, fresnel and light run whole). The input is the argument list, NUL-separated
// (argv[0] is "shadelab"), run in a folder holding small files to name (fixture.h).
//
// Contract checked (docs/cli.md): exit code 0 or 2, never 3 (an internal error) or a crash; with 2, stderr is
// exactly one printable line "shadelab: ..."; every line on stderr is printable and bounded.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.h"
#include "fixture.h"
#include "harness.h"

using namespace shadelab;

namespace {

constexpr std::size_t max_arguments = 64;

// stdout goes to /dev/null (fmt::print writes to the C stream, std::cout to the C++ one).
void silence_stdout() {
  std::fflush(stdout);
  if (std::freopen("/dev/null", "w", stdout) == nullptr) fuzz::finding("setup", "cannot open /dev/null");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool ready = [] {
    const auto dir = fuzz::work_dir("cli");
    fuzz::write_fixture(dir);
    std::filesystem::current_path(dir);
    silence_stdout();
    cli::set_validation_only(true);
    return true;
  }();
  (void)ready;
  std::vector<std::string> args{"shadelab"};
  std::string current;
  for (std::size_t i = 0; i < size && args.size() <= max_arguments; ++i) {
    if (data[i] == 0) {
      args.push_back(current);
      current.clear();
    } else {
      current += static_cast<char>(data[i]);
    }
  }
  if (!current.empty() && args.size() <= max_arguments) args.push_back(current);
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);

  std::ostringstream err;
  std::streambuf* saved = std::cerr.rdbuf(err.rdbuf());
  const int code = cli::run_cli(static_cast<int>(args.size()), argv.data());
  std::cerr.rdbuf(saved);
  std::cout.clear();

  const std::string text = err.str();
  if (code != 0 && code != 2) fuzz::finding("exit code " + std::to_string(code), text);
  std::size_t start = 0;
  int lines = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) fuzz::finding("stderr does not end with a newline", text);
    const std::string line = text.substr(start, end - start);
    fuzz::require_one_line(line, "shadelab: ", 1100);
    ++lines;
    start = end + 1;
  }
  if (code == 2 && lines != 1) fuzz::finding("exit code 2 without exactly one line on stderr", text);
  return 0;
}
