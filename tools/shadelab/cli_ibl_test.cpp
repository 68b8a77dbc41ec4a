// End-to-end tests of split-sum IBL from the command line (issue 11, sections 2 and 3): `bake specular
// --lobe ggx` (level 0 = the input, a constant stays constant, the roughness-to-mip mapping in the KTX 2
// key/value data), `bake dfg` as KTX 2, `bake ibl` and its manifest, and bad input. Every file is read back
// by the independent readers in tools/containers (Node's ktx-parse, a Python DDS reader).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <string>

#include "cli_run.h"
#define SHADELAB_SOURCE_DIR SHADELAB_SCENES_DIR "/.."
#include "shadelab/envmap/base/container_test_util.h"
#include "shadelab/envmap/specular/split_sum_lobes.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/image/image_io.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::json_of;
using shadelab::testing::run;
using shadelab::testing::temp_dir;
using shadelab::testing::ktx2_dump;
using shadelab::testing::dds_dump;
using shadelab::testing::constant_hdr;

// Face f, texel (x, y) of the 8 x 8 test cube: distinct values on a 1/64 grid (exact in float).
shadelab::Rgb cross_texel(int f, int x, int y) { return {0.25 + f / 8.0, 0.5 + (x + 8 * y) / 64.0, 2.0 - (x * y) / 64.0}; }

// That cube as a float32 EXR horizontal cross.
fs::path cross_exr() {
  const fs::path p = temp_dir() / "cross.exr";
  if (fs::exists(p)) return p;
  shadelab::CubeMap cube(8);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) cube.set(f, x, y, cross_texel(f, x, y));
  EXPECT_TRUE(shadelab::write_image(shadelab::cube_to_cross(cube, shadelab::CrossLayout::horizontal), p).has_value());
  return p;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f, nullptr, false);
}

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) names.insert(fs::relative(e.path(), dir).string());
  return names;
}

TEST(CliIbl, GgxLevelZeroIsTheInputBitForBit) {
  const fs::path out = temp_dir() / "ggx_cross.ktx2";
  const auto j = json_of(run("bake specular " + cross_exr().string() + " --lobe ggx --size 8 --samples 64 --format rgba32f "
                             "--no-exr-faces --out " + out.string() + " --json"));
  EXPECT_EQ(j["levels"], 4);
  std::string queries;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) queries += " 0:" + std::to_string(f) + ":" + std::to_string(x) + ":" + std::to_string(y);
  const auto k = ktx2_dump(out, queries);
  EXPECT_TRUE(k["problems"].empty()) << k["problems"].dump();
  ASSERT_EQ(k["texels"].size(), 384u);
  for (const auto& t : k["texels"]) {
    const shadelab::Rgb want = cross_texel(t["face"], t["x"], t["y"]);
    EXPECT_EQ(t["value"][0].get<double>(), want.r) << t.dump();
    EXPECT_EQ(t["value"][1].get<double>(), want.g) << t.dump();
    EXPECT_EQ(t["value"][2].get<double>(), want.b) << t.dump();
  }
}

TEST(CliIbl, GgxConstantStaysConstantAndTheMappingReadsBack) {
  for (const std::string mapping : {"linear", "filament"}) {
    SCOPED_TRACE(mapping);
    const fs::path out = temp_dir() / ("ggx_" + mapping + ".ktx2");
    // linear is the default mapping, sum the default method; --samples alone means --method sampled.
    const std::string args = mapping == "linear" ? "" : " --mapping filament --samples 128";
    const auto j = json_of(run("bake specular " + constant_hdr().string() + " --lobe ggx --size 16" + args +
                               " --format rgba32f --no-exr-faces --out " + out.string() + " --json"));
    const int levels = 5;
    EXPECT_EQ(j["levels"], levels);
    EXPECT_EQ(j["mapping"], mapping);
    std::string queries;
    for (int m = 0; m < levels; ++m) {
      const int n = 16 >> m;
      for (int f = 0; f < 6; ++f) queries += " " + std::to_string(m) + ":" + std::to_string(f) + ":0:0 " + std::to_string(m) +
                                             ":" + std::to_string(f) + ":" + std::to_string(n - 1) + ":" + std::to_string(n / 2);
    }
    const auto k = ktx2_dump(out, queries);
    EXPECT_TRUE(k["problems"].empty()) << k["problems"].dump();
    EXPECT_EQ(k["levelCount"], levels);
    for (const auto& t : k["texels"]) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(t["value"][c].get<double>(), 0.5, 0.5e-3) << t.dump();  // 0.1%
    }
    // The mapping as ktx-parse reads it, against the published formulas written here: linear r_i = i / (L - 1)
    // (glTF-Sample-Viewer), filament lod = r (2 - r) (L - 1), so r_i = 1 - sqrt(1 - i / (L - 1)).
    const auto kv = nlohmann::json::parse(k["keyValue"]["shadelab.mip_mapping"].get<std::string>());
    EXPECT_EQ(kv["lobe"], "ggx");
    EXPECT_EQ(kv["mapping"], mapping);
    EXPECT_EQ(kv["levels"], levels);
    EXPECT_EQ(kv["formula"], mapping == "linear" ? "lod = r * 4" : "lod = r * (2 - r) * 4");
    ASSERT_EQ(kv["roughness"].size(), static_cast<std::size_t>(levels));
    for (int i = 0; i < levels; ++i) {
      const double t = i / (levels - 1.0);
      EXPECT_NEAR(kv["roughness"][i].get<double>(), mapping == "linear" ? t : 1.0 - std::sqrt(1.0 - t), 1e-12) << i;
    }
    EXPECT_EQ(kv, j["mip_mapping"]);
    // How each level was made: sum sums the faces of 16 and below exactly; sampled with 128 samples exactly
    // where 3 n^2 <= 128 (faces 4, 2, 1) and samples face 8.
    const bool sum = mapping == "linear";
    EXPECT_EQ(kv["filter"], sum ? "sum" : "sampled");
    EXPECT_EQ(j["method"], sum ? "sum" : "sampled");
    EXPECT_EQ(kv["samples"], sum ? 0 : 128);
    EXPECT_EQ(j["samples"], sum ? 0 : 128);
    const nlohmann::json methods = sum ? nlohmann::json{"input", "exact", "exact", "exact", "exact"}
                                       : nlohmann::json{"input", "sampled", "exact", "exact", "exact"};
    EXPECT_EQ(kv["level_methods"], methods);
    EXPECT_NE(k["keyValue"]["shadelab.cube_convention"].get<std::string>().find("+X, -X, +Y, -Y, +Z, -Z"), std::string::npos);
  }
  // DDS holds no metadata: --json says the mapping is recorded there only.
  const auto d = json_of(run("bake specular " + constant_hdr().string() + " --lobe ggx --size 4 --samples 16 --no-exr-faces --out " +
                             (temp_dir() / "ggx.dds").string() + " --json"));
  EXPECT_NE(d["mip_mapping_recorded_in"].get<std::string>().find("only here"), std::string::npos);
  EXPECT_EQ(d["mip_mapping"]["mapping"], "linear");
}

TEST(CliIbl, GgxNearFarLevelKeepsAConstant) {
  // At --size 128 the default method sums face 64 (r = 0.5) near and far (n^2 N^2 > 2^24): mid cells of 4 x 4
  // texels, coarse of 16 x 16, the near field 86 degrees (3 lobe widths); a constant stays constant through
  // it (its cells' centroids are their centres, and the fields partition the sphere).
  const fs::path out = temp_dir() / "ggx_near_far.ktx2";
  const auto j = json_of(run("bake specular " + constant_hdr().string() + " --lobe ggx --size 128 --levels 3 --format rgba32f "
                             "--no-exr-faces --out " + out.string() + " --json"));
  EXPECT_EQ(j["mip_mapping"]["level_methods"], (nlohmann::json{"input", "near-far", "exact"}));
  EXPECT_EQ(j["mip_mapping"]["far_block"], 4);
  EXPECT_EQ(j["mip_mapping"]["coarse_block"], 16);
  ASSERT_EQ(j["mip_mapping"]["near_angle_degrees"].size(), 3u);
  // near_angle = max(near_cells 2 B / N, 3 lobe widths 2 alpha) = max(12 x 8 / 128, 3 x 2 x 0.25) rad.
  EXPECT_NEAR(j["mip_mapping"]["near_angle_degrees"][1].get<double>(), 1.5 * 180.0 / std::numbers::pi, 1e-9);
  EXPECT_EQ(j["mip_mapping"]["near_angle_degrees"][2].get<double>(), 0.0);
  std::string queries;
  for (int f = 0; f < 6; ++f)
    for (const int x : {0, 17, 40, 63}) queries += " 1:" + std::to_string(f) + ":" + std::to_string(x) + ":" + std::to_string(63 - x);
  const auto k = ktx2_dump(out, queries);
  EXPECT_TRUE(k["problems"].empty()) << k["problems"].dump();
  ASSERT_EQ(k["texels"].size(), 24u);
  for (const auto& t : k["texels"]) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t["value"][c].get<double>(), 0.5, 0.5e-3) << t.dump();  // 0.1%
  }
}

TEST(CliIbl, GgxBadOptionsNameTheOptionAndWriteNothing) {
  const std::string in = constant_hdr().string();
  const fs::path out = temp_dir() / "never_ggx.ktx2";
  auto refused = [&](const std::string& args, const std::string& needle) {
    expect_usage_error("bake specular " + in + " " + args + " --out " + out.string(), needle);
    EXPECT_FALSE(fs::exists(out)) << args;
  };
  refused("--lobe ggx --size 8 --levels 5", "--levels: 5 is out of range [1, 4] for --size 8");
  refused("--lobe ggx --size 12", "--size: 12 is not a power of two");
  refused("--lobe blinn", "--lobe: 'blinn' is not one of phong | ggx");
  refused("--lobe ggx --mapping cubic", "--mapping: 'cubic' is not one of linear | filament");
  refused("--lobe ggx --samples 0", "--samples");
  refused("--lobe ggx --gloss-scale 5", "--gloss-scale does not apply to bake specular --lobe ggx");
  refused("--mapping filament", "--mapping does not apply to bake specular --lobe phong");
  refused("--samples 64", "--samples does not apply to bake specular --lobe phong");
  refused("--method sum", "--method does not apply to bake specular --lobe phong");
  refused("--lobe ggx --method exact", "--method: 'exact' is not one of sum | sampled");
  refused("--lobe ggx --method sum --samples 64", "--samples does not apply to --method sum");
}

TEST(CliIbl, DfgKtx2ReadsBackWithKtxParseAndEqualsTheExr) {
  for (const bool multiscatter : {false, true}) {
    SCOPED_TRACE(multiscatter);
    const std::string ms = multiscatter ? " --multiscatter" : "";
    const std::string stem = multiscatter ? "dfg_ms" : "dfg";
    const fs::path exr = temp_dir() / (stem + ".exr"), ktx2 = temp_dir() / (stem + ".ktx2");
    ASSERT_EQ(run("bake dfg --size 8" + ms + " --out " + exr.string()).code, 0);
    const auto j = json_of(run("bake dfg --size 8" + ms + " --out " + ktx2.string() + " --json"));
    EXPECT_EQ(j["container"], "ktx2");
    EXPECT_EQ(j["format"], multiscatter ? "rgba16f" : "rg16f");
    const auto k = ktx2_dump(ktx2, " 0:0:5:2 0:0:0:7 0:0:7:0");
    EXPECT_TRUE(k["problems"].empty()) << k["problems"].dump();
    EXPECT_EQ(k["vkFormat"], multiscatter ? 97 : 83);  // VK_FORMAT_R16G16B16A16_SFLOAT / VK_FORMAT_R16G16_SFLOAT
    EXPECT_EQ(k["vkFormatName"], j["vk_format"]);
    EXPECT_EQ(k["pixelWidth"], 8);
    EXPECT_EQ(k["pixelHeight"], 8);
    EXPECT_EQ(k["faceCount"], 1);
    EXPECT_EQ(k["levelCount"], 1);
    EXPECT_EQ(k["dfd"]["samples"].size(), multiscatter ? 4u : 2u);
    EXPECT_NE(k["keyValue"]["shadelab.dfg_axes"].get<std::string>().find("N.V"), std::string::npos);
    const auto img = shadelab::read_image(exr).value();
    for (const auto& t : k["texels"]) {
      const shadelab::Rgb e = img.at(t["x"], t["y"]);
      const double want[4] = {e.r, e.g, e.b, 1.0};
      const std::size_t channels = multiscatter ? 4 : 2;
      ASSERT_EQ(t["value"].size(), channels);
      for (std::size_t c = 0; c < channels; ++c) {  // half: 11 significant bits
        EXPECT_NEAR(t["value"][c].get<double>(), want[c], std::abs(want[c]) * 0x1p-11 + 0x1p-25) << t.dump() << " " << c;
      }
    }
  }
}

TEST(CliIbl, ManifestNamesEveryFileAsWritten) {
  for (const std::string container : {"ktx2", "dds"}) {
    SCOPED_TRACE(container);
    const fs::path dir = temp_dir() / ("ibl_" + container) / "nested";  // created, parents too
    const auto j = json_of(run("bake ibl " + constant_hdr().string() + " --out-dir " + dir.string() + " --container " +
                               container + " --size 8 --levels 3 --samples 64 --irradiance-size 4 --dfg-size 4 --json"));
    const auto m = read_json(dir / "manifest.json");
    ASSERT_TRUE(m.is_object());
    auto printed = j;
    printed.erase("out_dir");
    printed.erase("seconds");
    EXPECT_EQ(printed, m);
    EXPECT_EQ(listing(dir), (std::set<std::string>{"specular." + container, "irradiance." + container, "sh9.json", "dfg.ktx2",
                                                    "split_sum_lobes.json", "manifest.json"}));
    ASSERT_EQ(m["files"].size(), 5u);
    for (const auto& [role, e] : m["files"].items()) {
      SCOPED_TRACE(role);
      const fs::path file = dir / e["file"].get<std::string>();
      ASSERT_TRUE(fs::is_regular_file(file));
      if (e["container"] == "ktx2") {
        const int n = e["size"];
        const auto k = ktx2_dump(file, " 0:0:0:0 " + std::to_string(e["levels"].get<int>() - 1) + ":0:0:0");
        EXPECT_TRUE(k["problems"].empty()) << k["problems"].dump();
        EXPECT_EQ(k["vkFormatName"], e["vk_format"]);
        EXPECT_EQ(k["pixelWidth"], n);
        EXPECT_EQ(k["pixelHeight"], n);
        EXPECT_EQ(k["levelCount"], e["levels"]);
        EXPECT_EQ(k["faceCount"], e["faces"]);
        if (role == "specular") {
          EXPECT_EQ(nlohmann::json::parse(k["keyValue"]["shadelab.mip_mapping"].get<std::string>()), e["mip_mapping"]);
        }
        if (role != "dfg") {
          for (const auto& t : k["texels"]) EXPECT_NEAR(t["value"][0].get<double>(), 0.5, 1e-3) << t.dump();  // game units
        } else {
          EXPECT_EQ(k["vkFormat"], 83);
          EXPECT_GT(k["texels"][0]["value"][0].get<double>(), 0.0);
        }
      } else if (e["container"] == "dds") {
        const auto d = dds_dump(file, " 0:0:0:0");
        EXPECT_TRUE(d["problems"].empty()) << d["problems"].dump();
        EXPECT_EQ(d["dxgiFormatName"], e["dxgi_format"]);
        EXPECT_EQ(d["width"], e["size"]);
        EXPECT_EQ(d["mipMapCount"], e["levels"]);
        EXPECT_NEAR(d["texels"][0]["value"][0].get<double>(), 0.5, 1e-3);
      } else if (role == "split_sum_lobes") {
        EXPECT_EQ(e["container"], "json");
        const auto t = read_json(file);
        const int n = t["size"];
        ASSERT_EQ(n, shadelab::split_sum_lobe_size);
        ASSERT_EQ(t["texels"].size(), static_cast<std::size_t>(n * n));
        // Texel (i = 5, j = 20) at its centre, as the library computes it there.
        const auto want = shadelab::split_sum_lobes_at(5.5 / n, 20.5 / n);
        const auto& got = t["texels"][static_cast<std::size_t>(20 * n + 5)];
        EXPECT_NEAR(got[0].get<double>(), want.a.angle, 1e-12);
        EXPECT_NEAR(got[1].get<double>(), want.a.roughness, 1e-12);
        EXPECT_NEAR(got[2].get<double>(), want.b.angle, 1e-12);
        EXPECT_NEAR(got[3].get<double>(), want.b.roughness, 1e-12);
        EXPECT_EQ(t["use"], e["use"]);
      } else {
        EXPECT_EQ(e["container"], "json");
        const auto sh = read_json(file);
        ASSERT_EQ(sh["irradiance_coefficients"].size(), 9u);
        EXPECT_NEAR(sh["irradiance_coefficients"][0][0].get<double>() * 0.28209479177387814, 0.5, 1e-6);  // E/pi of 0.5
      }
    }
    EXPECT_EQ(m["files"]["specular"]["levels"], 3);
    EXPECT_EQ(m["files"]["irradiance"]["size"], 4);
    EXPECT_EQ(m["files"]["dfg"]["size"], 4);
    EXPECT_NE(m["conventions"]["sh"]["d3dx"].get<std::string>().find("D3DXSHEvalDirection"), std::string::npos);
    EXPECT_EQ(m["conventions"]["dfg"]["x"], "N.V = (i + 0.5) / size, column i, left to right");
  }
}

// An input whose name is not UTF-8 (any byte but '/' and NUL is a Linux file name): the manifest, which names
// the input, is written with U+FFFD in its place (found 2026-12-06: the JSON library threw, "internal error",
// exit 3).
TEST(CliIbl, AnInputNameThatIsNotUtf8IsWrittenToTheManifest) {
  const fs::path in = temp_dir() / "const\xff" "ant.hdr";
  fs::copy_file(constant_hdr(), in, fs::copy_options::overwrite_existing);
  const fs::path dir = temp_dir() / "ibl_not_utf8";
  const auto r = run("bake ibl '" + in.string() + "' --out-dir " + dir.string() +
                     " --size 8 --levels 3 --samples 16 --irradiance-size 2 --dfg-size 2");
  EXPECT_EQ(r.code, 0) << r.err;
  const auto m = read_json(dir / "manifest.json");
  ASSERT_TRUE(m.is_object());
  EXPECT_NE(m["input"].get<std::string>().find("const\xef\xbf\xbd" "ant.hdr"), std::string::npos) << m["input"];
}

TEST(CliIbl, RefusalsAndFailuresLeaveNoPartialDirectory) {
  const std::string in = constant_hdr().string();
  const std::string small = " --size 8 --samples 16 --irradiance-size 2 --dfg-size 2";
  // Bad options: nothing is created, not even the directory.
  const fs::path fresh = temp_dir() / "fresh" / "ibl";
  expect_usage_error("bake ibl " + in + " --out-dir " + fresh.string() + " --size 8 --levels 5", "--levels: 5 is out of range [1, 4]");
  expect_usage_error("bake ibl " + in + " --out-dir " + fresh.string() + " --size 12", "--size: 12 is not a power of two");
  expect_usage_error("bake ibl " + in + " --out-dir " + fresh.string() + " --mapping cubic", "--mapping: 'cubic'");
  expect_usage_error("bake ibl " + in + " --out-dir " + fresh.string() + " --container ktx", "--container: 'ktx'");
  expect_usage_error("bake ibl " + in + " --out-dir " + fresh.string() + " --dfg-size 0", "--dfg-size");
  expect_usage_error("bake ibl " + (temp_dir() / "missing.exr").string() + " --out-dir " + fresh.string() + small, "missing.exr");
  EXPECT_FALSE(fs::exists(temp_dir() / "fresh"));
  // A file where the directory should be.
  const fs::path file = temp_dir() / "a_file";
  std::ofstream(file) << "x";
  expect_usage_error("bake ibl " + in + " --out-dir " + file.string() + small, "is not a directory");
  // A directory where an output should be: refused, and what was there stays as it was.
  const fs::path dir = temp_dir() / "occupied";
  fs::create_directories(dir / "dfg.ktx2");
  std::ofstream(dir / "specular.ktx2") << "old";
  const auto before = listing(dir);
  expect_usage_error("bake ibl " + in + " --out-dir " + dir.string() + small, "dfg.ktx2' exists and is not a regular file");
  EXPECT_EQ(listing(dir), before);
  std::ifstream old(dir / "specular.ktx2");
  std::string content;
  old >> content;
  EXPECT_EQ(content, "old");
  // The output over the input.
  const fs::path self = temp_dir() / "self";
  fs::create_directories(self);
  fs::copy_file(constant_hdr(), self / "manifest.json");
  expect_usage_error("bake ibl " + (self / "manifest.json").string() + " --out-dir " + self.string() + small, "manifest.json");
  EXPECT_EQ(listing(self), (std::set<std::string>{"manifest.json"}));
}

}  // namespace
