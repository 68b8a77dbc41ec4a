// Issue 37's commands: `layering-error` (glTF's clearcoat against the layered ground truth), `bake lut` (the tables
// layered materials read) and `audit-lut` (a shipped table against the exact integral), with their errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "cli_run.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/image/image_io.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {
namespace {

namespace fs = std::filesystem;
using testing::json_of;
using testing::run;
using testing::temp_dir;

TEST(CliLayered, LayeringErrorOfAClearcoatOverLambert) {
  const auto j = json_of(run("layering-error gltf --param metallic=0 --param specular=0 --param base_color=0.8 "
                             "--param clearcoat=1 --param clearcoat_roughness=0.3 --theta 0,60,85 --walks 8 --samples 20000 --json"));
  EXPECT_EQ(j["model"], "gltf");
  EXPECT_EQ(j["truth"]["model"], "layered");
  EXPECT_EQ(j["truth"]["params"]["base"], "lambert");
  EXPECT_EQ(j["truth"]["params"]["coat_ior"], "1.5");
  ASSERT_EQ(j["albedo"].size(), 3u);
  ASSERT_EQ(j["lobe"].size(), 3u);
  for (const auto& a : j["albedo"]) {
    // A clear coat over a white-ish Lambertian base: the truth's albedo is physical (< 1) and well measured.
    EXPECT_LT(a["truth"].get<double>(), 1.0);
    EXPECT_GT(a["truth"].get<double>(), 0.5);
    EXPECT_LT(a["truth_error"].get<double>(), 0.01);
  }
  // glTF's layering ignores the light the coat reflects back down: its albedo differs from the truth by more
  // than the truth's noise somewhere (the measurement this command exists for).
  double worst_z = 0.0;
  for (const auto& a : j["albedo"]) {
    worst_z = std::max(worst_z, std::abs(a["model"].get<double>() - a["truth"].get<double>()) / a["truth_error"].get<double>());
  }
  EXPECT_GT(worst_z, 5.0);
  EXPECT_GT(j["max_albedo_difference"].get<double>(), 0.0);
  for (const auto& l : j["lobe"]) EXPECT_GT(l["model_rmse"].get<double>(), 0.0);
}

TEST(CliLayered, LayeringErrorRefusesWhatTheTruthCannotHold) {
  const auto mixed = run("layering-error gltf --param metallic=0.5 --param clearcoat=1");
  EXPECT_EQ(mixed.code, 2);
  EXPECT_NE(mixed.err.find("parameter 'metallic' = 0.5"), std::string::npos) << mixed.err;
  const auto bare = run("layering-error gltf");
  EXPECT_EQ(bare.code, 2);
  EXPECT_NE(bare.err.find("parameter 'clearcoat' is 0"), std::string::npos) << bare.err;
  const auto other = run("layering-error lambert");
  EXPECT_EQ(other.code, 2);
  EXPECT_NE(other.err.find("model 'lambert'"), std::string::npos) << other.err;
  EXPECT_EQ(run("layering-error gltf --param clearcoat=1 --theta 95").code, 2);
}

// The baked sheen table, per texel by quadrature, against the kernel's interpolated table (a different computation:
// the table's nodes and Catmull-Rom), where the table claims 1e-4 (r >= 0.07, theta <= 89 degrees).
TEST(CliLayered, BakeLutSheenMatchesTheKernelTable) {
  const fs::path out = temp_dir() / "sheen_lut.exr";
  const auto j = json_of(run("bake lut sheen --size 8 --out " + out.string() + " --json"));
  EXPECT_EQ(j["kind"], "sheen");
  const Image img = read_image(out).value();
  ASSERT_EQ(img.width, 8);
  for (int row = 0; row < 8; ++row) {
    for (int i = 0; i < 8; ++i) {
      const double mu = (i + 0.5) / 8.0;
      const double r = std::max((row + 0.5) / 8.0, 0.07);
      EXPECT_NEAR(img.at(i, row).r, kernel::sheen_energy(kernel::SHEEN_VISIBILITY_CHARLIE, mu, r), 1e-4) << i << " " << row;
      EXPECT_NEAR(img.at(i, row).g, kernel::sheen_energy(kernel::SHEEN_VISIBILITY_ASHIKHMIN, mu, r), 1e-4) << i << " " << row;
    }
  }
}

// An exact float table audits to the float rounding; an 8-bit PNG of the same table (as viewers ship theirs) shows
// its quantization (<= half a code where the value is in [0, 1]) and its clipping of E > 1; a perturbed texel is found.
TEST(CliLayered, AuditLutFindsQuantizationClippingAndPerturbations) {
  const fs::path exr = temp_dir() / "audit_sheen.exr";
  const fs::path png = temp_dir() / "audit_sheen.png";
  ASSERT_EQ(run("bake lut sheen --size 16 --out " + exr.string()).code, 0);
  ASSERT_EQ(run("bake lut sheen --size 16 --out " + png.string()).code, 0);
  const auto exact = json_of(run("audit-lut " + exr.string() + " --kind sheen --json"));
  EXPECT_LT(exact["quantities"][0]["max_error"].get<double>(), 1e-6);
  const auto eight = json_of(run("audit-lut " + png.string() + " --kind sheen --json"));
  EXPECT_EQ(eight["sample_type"], "uint8");
  const auto& q = eight["quantities"][0];
  // Clipped: the largest error is where E > 1, and the bias is negative (the LUT reflects less than the lobe).
  EXPECT_GT(q["at"]["exact"].get<double>(), 1.0);
  EXPECT_GT(q["max_error"].get<double>(), 0.5 / 255.0);
  EXPECT_LT(q["bias"].get<double>(), 0.0);
  // The DFG table through the same path, and one texel moved by 0.01.
  const fs::path dfg = temp_dir() / "audit_dfg.exr";
  ASSERT_EQ(run("bake lut dfg --size 8 --out " + dfg.string()).code, 0);
  const auto good = json_of(run("audit-lut " + dfg.string() + " --kind dfg --json"));
  EXPECT_LT(good["quantities"][0]["max_error"].get<double>(), 1e-6);
  EXPECT_LT(good["quantities"][1]["max_error"].get<double>(), 1e-6);
  Image img = read_image(dfg).value();
  Rgb v = img.at(3, 5);
  v.g += 0.01;
  img.set(3, 5, v);
  const fs::path bad = temp_dir() / "audit_dfg_bad.exr";
  ASSERT_TRUE(write_image(img, bad).has_value());
  const auto found = json_of(run("audit-lut " + bad.string() + " --kind dfg --json"));
  EXPECT_NEAR(found["quantities"][1]["max_error"].get<double>(), 0.01, 1e-5);
  EXPECT_EQ(found["quantities"][1]["at"]["x"], 3);
  EXPECT_EQ(found["quantities"][1]["at"]["y"], 5);
  // Bad input: one line, exit 2.
  EXPECT_EQ(run("audit-lut " + (temp_dir() / "missing.png").string() + " --kind dfg").code, 2);
  EXPECT_EQ(run("audit-lut " + (temp_dir() / "missing.ktx2").string() + " --kind dfg").code, 2);
  EXPECT_EQ(run("audit-lut " + dfg.string() + " --kind brdf").code, 2);
  EXPECT_EQ(run("bake lut fuzz --out " + (temp_dir() / "x.exr").string()).code, 2);
}

// The KTX 2 table `bake lut` writes (RGBA16F) audits to half precision: its error is the half rounding (at most half
// an ulp, 2^-11 relative, of values up to 1), not zero; a truncated file is one line and exit 2.
TEST(CliLayered, AuditLutReadsTheKtx2TableItWrites) {
  const fs::path ktx = temp_dir() / "audit_dfg.ktx2";
  ASSERT_EQ(run("bake lut dfg --size 16 --out " + ktx.string()).code, 0);
  const auto a = json_of(run("audit-lut " + ktx.string() + " --kind dfg --json"));
  EXPECT_EQ(a["format"], "ktx2");
  EXPECT_EQ(a["sample_type"], "half");
  EXPECT_EQ(a["width"], 16);
  for (int c = 0; c < 2; ++c) {
    const double e = a["quantities"][c]["max_error"].get<double>();
    EXPECT_GT(e, 1e-6) << c;  // halves, not the float table
    EXPECT_LE(e, std::ldexp(1.0, -11) * 1.0000001) << c;
  }
  std::vector<char> bytes;
  {
    std::ifstream f(ktx, std::ios::binary | std::ios::ate);
    bytes.resize(static_cast<std::size_t>(f.tellg()));
    f.seekg(0);
    f.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  ASSERT_GT(bytes.size(), 200u);
  const fs::path cut = temp_dir() / "audit_dfg_cut.ktx2";
  {
    std::ofstream f(cut, std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size() - 100));
  }
  const auto r = run("audit-lut " + cut.string() + " --kind dfg");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("audit_dfg_cut.ktx2"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
}  // namespace shadelab
