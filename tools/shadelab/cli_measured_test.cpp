// Issue 41's `measure`: the virtual gonioreflectometer writes a MERL file that the reader takes back, with the
// model's values at the bin centres; bad input is one line and exit 2, with no file left behind.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_run.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/core/constants.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;
using testing::json_of;
using testing::run;
using testing::temp_dir;

TEST(CliMeasured, MeasureWritesAMerlFileTheReaderTakesBack) {
  const fs::path out = temp_dir() / "lambert.binary";
  const auto j = json_of(run("measure lambert --param kd=0.5,0.25,0.125 --out " + out.string() + " --json"));
  EXPECT_EQ(j["format"], "merl");
  EXPECT_EQ(j["model"], "lambert");
  EXPECT_EQ(j["params"]["kd"], "0.5,0.25,0.125");
  EXPECT_EQ(j["bins"], 1458000);
  EXPECT_EQ(j["bytes"], 34992012);
  EXPECT_EQ(fs::file_size(out), 34992012u);
  const auto t = read_merl(out);
  ASSERT_TRUE(t.has_value()) << t.error().message;
  std::size_t measured = 0;
  for (std::size_t i = 0; i < MerlTable::count; ++i) {
    if (t->value(0, i) < 0.0) continue;
    ++measured;
    ASSERT_NEAR(t->value(0, i), 0.5 * inv_pi, 1e-15) << i;
    ASSERT_NEAR(t->value(2, i), 0.125 * inv_pi, 1e-15) << i;
  }
  EXPECT_EQ(j["measured_bins"], measured);
  EXPECT_EQ(measured, 1458000u - 361784u);
}

TEST(CliMeasured, BadInputIsOneLineAndExitTwo) {
  const fs::path out = temp_dir() / "bad.binary";
  for (const std::string& args : {"measure no-such-model --out " + out.string(), "measure ggx --param roughness=7 --out " + out.string(),
                                  "measure ggx --format utia --out " + out.string(),
                                  "measure ggx --out " + (temp_dir() / "x.exr").string()}) {
    const auto r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace shadelab
