// Test helpers for the container tests: a mip chain whose texels are exact in every texel format, and a
// runner for the independent readers in tools/containers (Node's ktx-parse, a Python DDS reader).
#pragma once

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "shadelab/envmap/base/cubemap.h"

namespace shadelab::testing {

// Level m, face f, texel (x, y) holds (1 + f/8, 1 + y/16, 1 + (x + m)/32) for a face size up to 16: each
// channel lies in [1, 2) on a grid of 1/32 or coarser, exact in half, float, the 11/10-bit floats (6 and 5
// mantissa bits) and RGB9E5 (all three in [1, 2): a shared step of 2^-8).
inline Rgb exact_texel(int m, int f, int x, int y) { return {1.0 + f / 8.0, 1.0 + y / 16.0, 1.0 + (x + m) / 32.0}; }

inline std::vector<CubeMap> exact_chain(int size) {
  std::vector<CubeMap> levels;
  for (int m = 0, n = size; n >= 1; n /= 2, ++m) {
    CubeMap c(n);
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) c.set(f, x, y, exact_texel(m, f, x, y));
    levels.push_back(c);
  }
  return levels;
}

inline std::filesystem::path container_temp_dir() {
  static const std::filesystem::path d = [] {
    const auto p = std::filesystem::path(::testing::TempDir()) / ("shadelab_containers_" + std::to_string(::getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p;
  }();
  return d;
}

inline void write_bytes(const std::filesystem::path& p, const std::vector<char>& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Runs `command` and parses its stdout as JSON (a failure to run or parse fails the test).
inline nlohmann::json run_reader(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "cannot run " << command;
    return {};
  }
  std::string out;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int status = pclose(pipe);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command << "\n" << out;
  try {
    return nlohmann::json::parse(out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << command << ": not JSON (" << e.what() << ")\n" << out;
    return {};
  }
}

inline std::string containers_dir() { return std::string(SHADELAB_SOURCE_DIR) + "/tools/containers"; }

// The independent readers: ktx-parse in Node (ktx2_dump.mjs) and dds_dump.py in Debian's Python, on a file
// with optional texel queries (" L:F:X:Y ..."); their JSON report.
inline nlohmann::json ktx2_dump(const std::filesystem::path& file, const std::string& queries = "") {
  return run_reader("node " + containers_dir() + "/ktx2_dump.mjs " + file.string() + queries);
}
inline nlohmann::json dds_dump(const std::filesystem::path& file, const std::string& queries = "") {
  return run_reader("/usr/bin/python3 " + containers_dir() + "/dds_dump.py " + file.string() + queries);
}

// The texel queries "LEVEL:FACE:X:Y" the readers take: every level, every face, two texels each.
inline std::vector<std::array<int, 4>> texel_queries(int size) {
  std::vector<std::array<int, 4>> q;
  for (int m = 0, n = size; n >= 1; n /= 2, ++m)
    for (int f = 0; f < 6; ++f) {
      q.push_back({m, f, 0, 0});
      q.push_back({m, f, n - 1, n / 2});
    }
  return q;
}

inline std::string query_args(const std::vector<std::array<int, 4>>& q) {
  std::string s;
  for (const auto& t : q) s += " " + std::to_string(t[0]) + ":" + std::to_string(t[1]) + ":" + std::to_string(t[2]) + ":" + std::to_string(t[3]);
  return s;
}

}  // namespace shadelab::testing
