#include "harness.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>

#include "shadelab/core/text.h"

namespace shadelab::fuzz {

namespace {

struct WorkDir {
  std::filesystem::path path;
  ~WorkDir() {
    std::error_code ec;
    if (!path.empty()) std::filesystem::remove_all(path, ec);
  }
};

}  // namespace

const std::filesystem::path& work_dir(std::string_view name) {
  static WorkDir dir;
  if (dir.path.empty()) {
    std::error_code ec;
    std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    if (ec) base = "/tmp";
    dir.path = base / ("shadelab-fuzz-" + std::string(name) + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir.path, ec);
    std::filesystem::create_directories(dir.path, ec);
    if (ec) finding("setup", "cannot create " + dir.path.string() + ": " + ec.message());
  }
  return dir.path;
}

void write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!f) finding("setup", "cannot write " + path.string());
}

std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return size == 0 ? std::string_view() : std::string_view(reinterpret_cast<const char*>(data), size);
}

std::pair<std::string_view, std::string_view> split_files(std::string_view input) {
  const std::size_t at = input.find(file_separator);
  if (at == std::string_view::npos) return {input, {}};
  return {input.substr(0, at), input.substr(at + file_separator.size())};
}

void finding(std::string_view what, std::string_view detail) {
  const std::string shown = printable(detail, 4000);
  std::fprintf(stderr, "shadelab fuzz finding: %.*s: %s\n", static_cast<int>(what.size()), what.data(), shown.c_str());
  std::fflush(stderr);
  std::abort();
}

void require_one_line(std::string_view message, std::string_view must_contain, std::size_t max_bytes) {
  if (message.empty()) finding("empty message", "an error without a message");
  if (message.size() > max_bytes) finding("message too long", std::to_string(message.size()) + " bytes: " + std::string(message));
  if (printable(message, max_bytes) != message) finding("unprintable message", message);
  for (char c : message) {
    if (c == '\n' || c == '\r') finding("message of more than one line", message);
  }
  if (!must_contain.empty() && message.find(must_contain) == std::string_view::npos) {
    finding("message does not name the file", "expected '" + std::string(must_contain) + "' in: " + std::string(message));
  }
}

}  // namespace shadelab::fuzz
