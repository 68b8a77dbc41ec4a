// End-to-end tests of the engine containers (issue 11, 3) and bad input (issue 11, 6): `bake` chooses the
// container by extension (.ktx2, .ktx, .dds, .exr, .hdr), --format the texel format; every file is read back
// by an independent reader (Node's ktx-parse, a Python DDS reader); every refusal is one line, exit 2, and
// leaves no file.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "cli_run.h"
#define SHADELAB_SOURCE_DIR SHADELAB_SCENES_DIR "/.."
#include "shadelab/envmap/base/container_test_util.h"
#include "shadelab/envmap/base/ktx.h"
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

const char* formats[] = {"rgba16f", "rgba32f", "rg11b10f", "rgb9e5"};
const int vk[] = {97, 109, 122, 123};
const int dxgi[] = {10, 2, 26, 67};

TEST(CliContainer, SpecularChainAsKtx2InEveryFormat) {
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE(formats[i]);
    const fs::path out = temp_dir() / (std::string("spec_") + formats[i] + ".ktx2");
    const auto j = json_of(run("bake specular " + constant_hdr().string() + " --size 8 --no-exr-faces --format " +
                               formats[i] + " --out " + out.string() + " --json"));
    EXPECT_EQ(j["container"], "ktx2");
    EXPECT_EQ(j["format"], formats[i]);
    EXPECT_EQ(j["levels"], 4);
    const auto k = ktx2_dump(out, " 0:0:3:3 3:5:0:0 2:2:1:0");
    EXPECT_TRUE(k["problems"].empty()) << k["problems"].dump();
    EXPECT_EQ(k["vkFormat"], vk[i]);
    EXPECT_EQ(k["faceCount"], 6);
    EXPECT_EQ(k["levelCount"], 4);
    EXPECT_EQ(k["pixelWidth"], 8);
    EXPECT_EQ(k["keyValue"]["KTXorientation"], "rd");
    const auto mapping = nlohmann::json::parse(k["keyValue"]["shadelab.mip_mapping"].get<std::string>());
    EXPECT_EQ(mapping["lobe"], "phong");
    EXPECT_EQ(mapping["exponents"], j["exponents"]);
    EXPECT_EQ(mapping["gloss_scale"], 10.0);
    EXPECT_NE(k["keyValue"]["shadelab.cube_convention"].get<std::string>().find("+X, -X, +Y, -Y, +Z, -Z"), std::string::npos);
    for (const auto& t : k["texels"]) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(t["value"][c].get<double>(), 0.5, 1e-3) << t.dump();  // a constant stays constant
    }
  }
}

TEST(CliContainer, SpecularChainAsDdsInEveryFormat) {
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE(formats[i]);
    const fs::path out = temp_dir() / (std::string("spec_") + formats[i] + ".dds");
    const auto j = json_of(run("bake specular " + constant_hdr().string() + " --size 8 --levels 3 --no-exr-faces --format " +
                               formats[i] + " --out " + out.string() + " --json"));
    EXPECT_EQ(j["container"], "dds");
    EXPECT_EQ(j["levels"], 3);
    const auto d = dds_dump(out, " 0:0:3:3 2:5:1:1 1:3:0:2");
    EXPECT_TRUE(d["problems"].empty()) << d["problems"].dump();
    EXPECT_EQ(d["dxgiFormat"], dxgi[i]);
    EXPECT_EQ(d["mipMapCount"], 3);
    EXPECT_EQ(d["width"], 8);
    for (const auto& t : d["texels"]) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(t["value"][c].get<double>(), 0.5, 1e-3) << t.dump();
    }
  }
}

TEST(CliContainer, ConvertAndIrradianceChooseTheContainerByExtension) {
  const std::string in = constant_hdr().string();
  const fs::path k2 = temp_dir() / "env.ktx2", dds = temp_dir() / "env.dds", k1 = temp_dir() / "env.ktx",
                 exr = temp_dir() / "env.exr", hdr = temp_dir() / "env.hdr";
  EXPECT_EQ(json_of(run("bake convert " + in + " --out " + k2.string() + " --format rgb9e5 --json"))["container"], "ktx2");
  EXPECT_EQ(json_of(run("bake convert " + in + " --out " + dds.string() + " --json"))["dxgi_format"], "DXGI_FORMAT_R16G16B16A16_FLOAT");
  EXPECT_EQ(json_of(run("bake convert " + in + " --out " + k1.string() + " --format rgba32f --json"))["layout"], "ktx");
  EXPECT_EQ(json_of(run("bake convert " + in + " --out " + exr.string() + " --json"))["layout"], "hcross");
  EXPECT_EQ(json_of(run("bake convert " + in + " --out " + hdr.string() + " --json"))["container"], "hdr");
  const auto k = ktx2_dump(k2, " 0:4:2:2");
  EXPECT_EQ(k["vkFormat"], 123);
  EXPECT_EQ(k["levelCount"], 1);
  EXPECT_EQ(k["keyValue"]["shadelab.content"], "radiance");
  EXPECT_EQ(k["texels"][0]["value"][1].get<double>(), 0.5);
  EXPECT_EQ(dds_dump(dds, " 0:1:0:0")["texels"][0]["value"][0].get<double>(), 0.5);
  std::ifstream f(k1, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto levels = shadelab::decode_ktx_cubemap(bytes);  // KTX 1 stays, now also as RGBA32F
  ASSERT_TRUE(levels.has_value()) << levels.error().message;
  EXPECT_EQ((*levels)[0].texel(3, 1, 1).b, 0.5);
  EXPECT_EQ(shadelab::read_image(exr)->width * 3, shadelab::read_image(exr)->height * 4);
  EXPECT_EQ(shadelab::read_image(hdr)->at(20, 20).r, 0.5);
  // Irradiance in game units of a constant 0.5 is 0.5, here in 11/10-bit floats.
  const fs::path irr = temp_dir() / "irr.dds";
  EXPECT_EQ(json_of(run("bake irradiance " + in + " --size 4 --format rg11b10f --out " + irr.string() + " --json"))["format"], "rg11b10f");
  EXPECT_NEAR(dds_dump(irr, " 0:2:1:1")["texels"][0]["value"][0].get<double>(), 0.5, 2e-3);
}

// Issue 11, 6: one line naming the option or file, exit 2, no file written.
TEST(CliContainer, BadInputWritesNothing) {
  const std::string in = constant_hdr().string();
  const fs::path out = temp_dir() / "never.ktx2";
  auto refused = [&](const std::string& args, const std::string& needle, const fs::path& target) {
    expect_usage_error(args, needle);
    EXPECT_FALSE(fs::exists(target)) << args;
  };
  // Neither square faces in a cross nor 2:1.
  shadelab::Image odd(100, 60);
  const fs::path odd_path = temp_dir() / "odd.exr";
  ASSERT_TRUE(shadelab::write_image(odd, odd_path).has_value());
  refused("bake specular " + odd_path.string() + " --size 8 --out " + out.string(), "odd.exr", out);
  refused("bake convert " + odd_path.string() + " --out " + out.string(), "100 x 60", out);
  shadelab::Image tall(60, 100);
  const fs::path tall_path = temp_dir() / "tall.hdr";
  ASSERT_TRUE(shadelab::write_image(tall, tall_path).has_value());
  refused("bake irradiance " + tall_path.string() + " --out " + out.string(), "tall.hdr", out);
  // A face size that is not a power of two where mips need it.
  refused("bake specular " + in + " --size 12 --out " + out.string(), "--size: 12 is not a power of two", out);
  refused("bake specular " + in + " --size 48 --out " + (temp_dir() / "never.dds").string(), "--size", temp_dir() / "never.dds");
  // More levels than log2(size) + 1.
  refused("bake specular " + in + " --size 8 --levels 5 --out " + out.string(), "--levels: 5 is out of range [1, 4] for --size 8", out);
  refused("bake specular " + in + " --size 8 --mips 5 --out " + out.string(), "--mips: 5 is out of range [1, 4]", out);
  refused("bake specular " + in + " --size 8 --levels 0 --out " + out.string(), "--levels: 0", out);
  refused("bake specular " + in + " --levels 3 --mips 3 --out " + out.string(), "--levels and --mips", out);
  // Unknown extensions.
  const fs::path ktx3 = temp_dir() / "x.ktx3";
  refused("bake convert " + in + " --out " + ktx3.string(), "x.ktx3", ktx3);
  refused("bake specular " + in + " --out " + (temp_dir() / "s.exr").string(), "--out: the specular chain is written as .ktx, .ktx2 or .dds", temp_dir() / "s.exr");
  refused("bake irradiance " + in + " --out " + (temp_dir() / "i.bmp").string(), "--out", temp_dir() / "i.bmp");
  // --format: unknown, not held by KTX 1, not for images, not for sh.
  refused("bake convert " + in + " --format bc6h --out " + out.string(), "--format: 'bc6h' is not one of", out);
  refused("bake convert " + in + " --format rgb9e5 --out " + (temp_dir() / "c.ktx").string(), "--format: a .ktx (KTX 1) output", temp_dir() / "c.ktx");
  refused("bake convert " + in + " --format rgba32f --out " + (temp_dir() / "c.exr").string(), "--format applies to .ktx2, .ktx and .dds", temp_dir() / "c.exr");
  refused("bake sh " + in + " --format rgba16f", "--format does not apply to bake sh", temp_dir() / "none");
  refused("bake convert " + in + " --layout vcross --out " + (temp_dir() / "c.dds").string(), "--layout does not apply to a .dds output", temp_dir() / "c.dds");
  std::size_t left = 0;
  for (const auto& e : fs::directory_iterator(temp_dir())) left += e.path().filename().string().find(".tmp") != std::string::npos ? 1 : 0;
  EXPECT_EQ(left, 0u);  // no temporary left behind either
}

}  // namespace
