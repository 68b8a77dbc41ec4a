// Test helpers: run the built shadelab binary and capture its exit code, stdout and stderr.
#pragma once

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <filesystem>
#include <unistd.h>

namespace shadelab::testing {

// A fresh folder for this test process: CTest runs every test in its own process, several at once, so the
// folder name carries the process id (a shared folder would be wiped by a neighbour).
inline std::filesystem::path process_temp_dir(const std::string& name) {
  const std::filesystem::path d = std::filesystem::path(::testing::TempDir()) / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// This process's folder for the running test suite ("shadelab_SUITE_PID"), made fresh the first time the
// suite asks for it in this process. Outside a test (static initialisation) the suite is "shadelab_cli".
inline std::filesystem::path temp_dir() {
  static std::map<std::string, std::filesystem::path> dirs;
  const ::testing::TestSuite* suite = ::testing::UnitTest::GetInstance()->current_test_suite();
  const std::string name = std::string("shadelab_") + (suite != nullptr ? suite->name() : "cli");
  auto it = dirs.find(name);
  if (it == dirs.end()) it = dirs.emplace(name, process_temp_dir(name)).first;
  return it->second;
}

// A 64 x 32 Radiance HDR lat-long of constant 0.5, written byte by byte (flat scan lines; RGBE
// (128,128,128,128) = 128/256 x 2^(128-128) = 0.5 exactly), so the input does not come from the code under test.
// Written again on every call: a test may have overwritten it.
inline std::filesystem::path constant_hdr() {
  const std::filesystem::path p = temp_dir() / "constant.hdr";
  std::ofstream f(p, std::ios::binary);
  f << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32 +X 64\n";
  for (int i = 0; i < 64 * 32 * 4; ++i) f << static_cast<char>(128);
  return p;
}

struct CliRun {
  int code = -1;
  std::string out;
  std::string err;
};

inline CliRun run(const std::string& args) {
  static int counter = 0;
  // Per process and call: CTest runs tests in parallel processes, which must not share the capture file.
  const std::string err_path = ::testing::TempDir() + "shadelab_cli_err_" + std::to_string(::getpid()) + "_" +
                               std::to_string(counter++) + ".txt";
  const std::string cmd = std::string(SHADELAB_EXE) + " " + args + " 2>" + err_path;
  CliRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream f(err_path);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  std::remove(err_path.c_str());
  return r;
}

inline nlohmann::json json_of(const CliRun& r) {
  EXPECT_EQ(r.code, 0) << r.err;
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON: " << e.what() << "\n" << r.out;
    return {};
  }
}

// A usage error: exit code 2, exactly one line on stderr, which mentions `needle`, and nothing on stdout.
inline void expect_usage_error(const std::string& args, const std::string& needle) {
  const CliRun r = run(args);
  EXPECT_EQ(r.code, 2) << args << "\nstderr: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\nstderr: " << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << args << "\nstderr: " << r.err;
  EXPECT_TRUE(r.out.empty()) << args << "\nstdout: " << r.out;
}

}  // namespace shadelab::testing
