// DDS cube maps read back by an independent reader: tools/containers/dds_dump.py (Debian's /usr/bin/python3
// with numpy), written from Microsoft's header documentation and the D3D11 format definitions.
#include "shadelab/envmap/base/dds.h"

#include <gtest/gtest.h>

#include <cstring>

#include "shadelab/envmap/base/container_test_util.h"

namespace shadelab {
namespace {

using testing::container_temp_dir;
using testing::exact_chain;
using testing::exact_texel;

TEST(Dds, EveryFormatReadsBackWithAnIndependentReader) {
  const int size = 16;
  const auto chain = exact_chain(size);
  const auto queries = testing::texel_queries(size);
  for (TexelFormat f : all_texel_formats) {
    SCOPED_TRACE(texel_format_name(f));
    const auto path = container_temp_dir() / (std::string("exact_") + texel_format_name(f) + ".dds");
    ASSERT_TRUE(write_dds_cubemap(chain, path, f).has_value());
    const auto j = testing::dds_dump(path, testing::query_args(queries));
    ASSERT_TRUE(j.is_object());
    EXPECT_TRUE(j["problems"].empty()) << j["problems"].dump();
    EXPECT_EQ(j["dxgiFormat"], dxgi_format(f));
    EXPECT_EQ(j["dxgiFormatName"], dxgi_format_name(f));
    EXPECT_EQ(j["width"], size);
    EXPECT_EQ(j["height"], size);
    EXPECT_EQ(j["mipMapCount"], 5);       // 16 .. 1
    EXPECT_EQ(j["resourceDimension"], 3);  // TEXTURE2D
    EXPECT_EQ(j["miscFlag"], 4);           // TEXTURECUBE
    EXPECT_EQ(j["arraySize"], 1);
    ASSERT_EQ(j["texels"].size(), queries.size());
    for (const auto& t : j["texels"]) {
      const Rgb want = exact_texel(t["level"].get<int>(), t["face"].get<int>(), t["x"].get<int>(), t["y"].get<int>());
      EXPECT_EQ(t["value"][0].get<double>(), want.r) << t.dump();
      EXPECT_EQ(t["value"][1].get<double>(), want.g) << t.dump();
      EXPECT_EQ(t["value"][2].get<double>(), want.b) << t.dump();
      if (f == TexelFormat::rgba16f || f == TexelFormat::rgba32f) {
        EXPECT_EQ(t["value"][3].get<double>(), 1.0);
      }
    }
  }
}

TEST(Dds, HeaderBytes) {
  const auto bytes = encode_dds_cubemap(exact_chain(4), TexelFormat::rg11b10f).value();
  auto u32 = [&](std::size_t at) { std::uint32_t v; std::memcpy(&v, bytes.data() + at, 4); return v; };
  EXPECT_EQ(std::memcmp(bytes.data(), "DDS ", 4), 0);
  EXPECT_EQ(u32(4), 124u);
  EXPECT_EQ(u32(8), 0x1u | 0x2u | 0x4u | 0x8u | 0x1000u | 0x20000u);
  EXPECT_EQ(u32(20), 16u);        // pitch: 4 texels of 4 bytes
  EXPECT_EQ(u32(28), 3u);         // mips 4, 2, 1
  EXPECT_EQ(std::memcmp(bytes.data() + 84, "DX10", 4), 0);
  EXPECT_EQ(u32(108), 0x401008u);  // COMPLEX | TEXTURE | MIPMAP
  EXPECT_EQ(u32(112), 0xFE00u);    // CUBEMAP and the six faces
  EXPECT_EQ(u32(128), 26u);        // DXGI_FORMAT_R11G11B10_FLOAT
  EXPECT_EQ(bytes.size(), 148u + 6 * (16 + 4 + 1) * 4);
  EXPECT_FALSE(encode_dds_cubemap({}, TexelFormat::rgba16f).has_value());
}

}  // namespace
}  // namespace shadelab
