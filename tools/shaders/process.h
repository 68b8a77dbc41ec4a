// shadelab shader tools: running the external programs verification needs (glslangValidator, chromium) with
// a time limit, and temporary folders that remove themselves.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shadelab/core/error.h"

namespace shadelab::shaders {

struct ProcessResult {
  int exit_code = -1;  // -1 when killed (timed out or by a signal)
  bool timed_out = false;
  std::string out;
  std::string err;
};

// Runs argv[0] (looked up on PATH) with the arguments, stdin from /dev/null, stdout and stderr captured, in
// its own process group; after timeout_s seconds the group is killed. Errors: the program cannot be started.
Result<ProcessResult> run_process(const std::vector<std::string>& argv, double timeout_s);

// The full path of a program on PATH, or empty.
std::string find_program(const std::string& name);

// A fresh folder under the system's temporary folder, removed with everything in it on destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "shadelab-shader");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return m_path; }
  std::filesystem::path operator/(const std::string& name) const { return m_path / name; }

 private:
  std::filesystem::path m_path;
};

// Writes a file (binary); errors name the file.
Result<bool> write_file(const std::filesystem::path& path, const std::string& content);
Result<std::string> read_file(const std::filesystem::path& path);

}  // namespace shadelab::shaders
