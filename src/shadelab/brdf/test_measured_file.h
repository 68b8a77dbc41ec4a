// Test code only: one MERL file per test binary for the registry's `measured` model, and the parameters the loops
// over every registered model build each model with (a model with no usable default gets the file).
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "shadelab/brdf/merl.h"
#include "shadelab/brdf/registry.h"

namespace shadelab::testing {

// The model the file measures (the virtual gonioreflectometer, brdf/merl.h): coloured, glossy, with a diffuse base.
inline const char* measured_source_model() { return "ggx"; }
inline ParamAssignments measured_source_params() { return {{"roughness", "0.4"}, {"kd", "0.3"}, {"f0", "0.9,0.6,0.3"}}; }

// A fresh folder under the system's temporary folder, removed with what it holds when the test binary exits.
class MeasuredTestFolder {
 public:
  MeasuredTestFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "shadelab-measured-XXXXXX").string();
    if (::mkdtemp(pattern.data()) != nullptr) m_dir = pattern;
  }
  ~MeasuredTestFolder() {
    std::error_code ec;
    if (!m_dir.empty()) std::filesystem::remove_all(m_dir, ec);
  }
  MeasuredTestFolder(const MeasuredTestFolder&) = delete;
  MeasuredTestFolder& operator=(const MeasuredTestFolder&) = delete;
  const std::filesystem::path& dir() const { return m_dir; }

 private:
  std::filesystem::path m_dir;
};

inline const MeasuredTestFolder& measured_test_folder() {
  static const MeasuredTestFolder folder;
  return folder;
}

// Writes bytes to dir/name (the folder is this binary's own); empty path on failure (the caller's test fails).
inline std::filesystem::path write_test_file(const std::string& name, const std::vector<char>& bytes) {
  const auto& dir = measured_test_folder().dir();
  if (dir.empty()) return {};
  const auto path = dir / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return out ? path : std::filesystem::path{};
}

// The file, written on first use (about 0.5 s: measure_merl of ggx and 35 MB written).
inline const std::filesystem::path& measured_test_file() {
  static const std::filesystem::path path = [] {
    auto f = make_brdf(measured_source_model(), measured_source_params());
    if (!f) return std::filesystem::path{};
    return write_test_file("ggx.binary", encode_merl(measure_merl(**f)));
  }();
  EXPECT_FALSE(path.empty()) << "could not write the measured test file";
  return path;
}

// The parameters a loop over every model builds `m` with: none, or the test file for a model that needs one.
inline ParamAssignments registry_params(const ModelInfo& m) {
  if (!needs_input_file(m)) return {};
  return {{"file", measured_test_file().string()}};
}

}  // namespace shadelab::testing
