// Issue 41's `fit`: a model fitted to another model's data and to a MERL file gives back the known parameters in
// the JSON shape the issue names; bad input is one line and exit 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/brdf/utia.h"
#include "shadelab/image/image_io.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;
using testing::json_of;
using testing::run;
using testing::temp_dir;

TEST(CliFit, FitsAModelToAnotherModelsDataAndPrintsTheIssuesJson) {
  const auto j = json_of(run("fit ggx model:ggx,alpha=0.3,f0=0.04,kd=0.6,0.4,0.2 --metric cube-root --starts 2 "
                             "--theta-d-stride 6 --phi-d-stride 12 --json"));
  EXPECT_EQ(j["model"], "ggx");
  EXPECT_EQ(j["metric"], "cube-root");
  EXPECT_EQ(j["fitted"], nlohmann::json({"kd", "alpha", "f0"}));
  EXPECT_NEAR(j["params"]["alpha"].get<double>(), 0.3, 3e-4);
  EXPECT_NEAR(j["params"]["kd"][0].get<double>(), 0.6, 6e-4);
  EXPECT_NEAR(j["params"]["kd"][2].get<double>(), 0.2, 2e-4);
  EXPECT_NEAR(j["params"]["f0"][1].get<double>(), 0.04, 4e-5);
  EXPECT_EQ(j["params"]["f"], "schlick");      // a choice: its default
  EXPECT_EQ(j["params"]["ks"], 1.0);           // not free: its default
  EXPECT_LT(j["residual"].get<double>(), 1e-6);
  ASSERT_EQ(j["albedo_difference"].size(), 9u);
  for (const auto& row : j["albedo_difference"]) EXPECT_LT(std::abs(row[1].get<double>()), 1e-4) << row;
  EXPECT_EQ(j["albedo_difference"][8][0], 80.0);
  EXPECT_GT(j["seconds"].get<double>(), 0.0);
}

TEST(CliFit, FitsAMerlFileAndReportsAResidualWhereTheModelFallsShort) {
  const fs::path file = temp_dir() / "ward.binary";
  ASSERT_EQ(run("measure ward --param kd=0.3 --param ks=0.1 --param alpha=0.2 --out " + file.string()).code, 0);
  // Lambert cannot hold the specular lobe: its residual is honest, its albedo falls short at every angle.
  const auto j = json_of(run("fit lambert " + file.string() + " --json --theta-d-stride 6 --phi-d-stride 12"));
  EXPECT_EQ(j["data_kind"], "merl");
  EXPECT_GT(j["residual"].get<double>(), 1e-3);
  EXPECT_GT(j["params"]["kd"].get<double>(), 0.3);  // the diffuse takes some of the specular energy
  for (const auto& row : j["albedo_difference"]) EXPECT_LT(row[1].get<double>(), 0.05) << row;
  // Ward itself fits it back.
  const auto w = json_of(run("fit ward " + file.string() + " --json --starts 1 --theta-d-stride 6 --phi-d-stride 12"));
  EXPECT_NEAR(w["params"]["alpha"].get<double>(), 0.2, 2e-4);
  EXPECT_NEAR(w["params"]["ks"].get<double>(), 0.1, 1e-4);
  // The text form names every parameter and the residual.
  const auto t = run("fit ward " + file.string() + " --starts 1 --theta-d-stride 6 --phi-d-stride 12");
  EXPECT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("alpha"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("residual"), std::string::npos) << t.out;
}

TEST(CliFit, BadInputIsOneLineAndExitTwo) {
  const fs::path truncated = temp_dir() / "short.binary";
  {
    std::ofstream f(truncated, std::ios::binary);
    f << "not a merl file";
  }
  for (const std::string& args : {std::string("fit ggx model:ggx --metric l1"), std::string("fit nope model:ggx"),
                                  std::string("fit ggx model:nope"), std::string("fit ggx model:ggx,alpha=7"),
                                  std::string("fit ggx model:ggx --fix nope=1"), std::string("fit ggx model:ggx --free f"),
                                  std::string("fit ggx model:ggx --starts 0"), std::string("fit ggx " + (temp_dir() / "missing.binary").string()),
                                  std::string("fit ggx " + truncated.string()), std::string("fit ggx data.exr")}) {
    const auto r = run(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

}  // namespace
}  // namespace shadelab

namespace shadelab {
namespace {

TEST(CliFit, FitsAUtiaFileByItsOwnInterpolation) {
  // UTIA's 15-degree sampling holds a broad lobe: ward with alpha 0.5 written at its 6 x 48 x 6 x 48 directions,
  // interpolated linearly between them, fitted back by ward within a few percent.
  auto ward = make_brdf("ward", {{"kd", "0.3"}, {"ks", "0.2"}, {"alpha", "0.5"}});
  ASSERT_TRUE(ward);
  const fs::path file = testing::temp_dir() / "ward.bin";
  ASSERT_TRUE(write_file_atomically(file, encode_utia(measure_utia(**ward))));
  const auto j = testing::json_of(testing::run("fit ward " + file.string() + " --json --starts 1 --theta-d-stride 6 --phi-d-stride 12"));
  EXPECT_EQ(j["data_kind"], "utia");
  EXPECT_NEAR(j["params"]["alpha"].get<double>(), 0.5, 0.05);
  EXPECT_NEAR(j["params"]["kd"].get<double>(), 0.3, 0.03);
}

}  // namespace
}  // namespace shadelab
