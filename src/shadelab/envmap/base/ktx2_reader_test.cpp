// The KTX 2 reader against the writer (ktx2.h, itself checked against an independent reader, ktx-parse, in
// tools/containers): every texel of every level and face read back as written (exactly where the format holds
// the value), the key/value data, and malformed files refused with a message, never a crash.
#include "shadelab/envmap/base/ktx2_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "shadelab/envmap/base/ktx2.h"

namespace shadelab {
namespace {

// A chain whose texel values are exact in half floats: small integers over 8.
std::vector<CubeMap> test_chain(int size, int levels) {
  std::vector<CubeMap> chain;
  for (int l = 0; l < levels; ++l) {
    const int n = std::max(1, size >> l);
    CubeMap c(n);
    for (int f = 0; f < 6; ++f) {
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) c.set(f, x, y, Rgb{(x + 1) / 8.0, (y + 2) / 8.0, (f + 8 * l) / 8.0});
      }
    }
    chain.push_back(std::move(c));
  }
  return chain;
}

TEST(Ktx2Reader, ReadsEveryTexelOfEveryLevelAsWritten) {
  const auto chain = test_chain(8, 4);
  for (const TexelFormat f : {TexelFormat::rgba16f, TexelFormat::rgba32f, TexelFormat::rg11b10f, TexelFormat::rgb9e5}) {
    const auto bytes = encode_ktx2_cubemap(chain, f, {{"shadelab.test", "{\"a\": 1}"}}).value();
    const auto t = parse_ktx2(bytes, "mem.ktx2");
    ASSERT_TRUE(t.has_value()) << texel_format_name(f) << ": " << t.error().message;
    EXPECT_EQ(t->vk_format, vk_format(f));
    EXPECT_EQ(t->faces, 6);
    ASSERT_EQ(t->levels.size(), 4u);
    EXPECT_EQ(t->value("shadelab.test"), "{\"a\": 1}");
    EXPECT_EQ(t->value("KTXorientation"), "rd");
    for (int l = 0; l < 4; ++l) {
      const int n = chain[static_cast<std::size_t>(l)].size;
      ASSERT_EQ(t->level_width(l), n);
      for (int face = 0; face < 6; ++face) {
        for (int y = 0; y < n; ++y) {
          for (int x = 0; x < n; ++x) {
            const Rgb want = chain[static_cast<std::size_t>(l)].texel(face, x, y);
            const float* got = t->texel(l, face, x, y);
            // The packed formats round these values (6- and 5-bit mantissas, a shared exponent): 2^-5 relative.
            const double tol = (f == TexelFormat::rgba16f || f == TexelFormat::rgba32f) ? 0.0 : 0.04 * std::max(want.max_component(), 0.1);
            EXPECT_NEAR(got[0], want.r, tol) << texel_format_name(f) << " level " << l << " face " << face;
            EXPECT_NEAR(got[1], want.g, tol);
            EXPECT_NEAR(got[2], want.b, tol);
            EXPECT_EQ(got[3], 1.0f);
          }
        }
      }
    }
  }
}

TEST(Ktx2Reader, ReadsATwoChannelTable) {
  Image img(5, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) img.set(x, y, Rgb{x / 4.0, y / 2.0, 7.0});
  }
  const auto bytes = encode_ktx2_image(img, Ktx2ImageFormat::rg16f).value();
  const auto t = parse_ktx2(bytes, "dfg.ktx2").value();
  EXPECT_EQ(t.vk_format, 83u);
  EXPECT_EQ(t.faces, 1);
  ASSERT_EQ(t.width, 5);
  ASSERT_EQ(t.height, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      EXPECT_EQ(t.texel(0, 0, x, y)[0], static_cast<float>(x / 4.0));
      EXPECT_EQ(t.texel(0, 0, x, y)[1], static_cast<float>(y / 2.0));
      EXPECT_EQ(t.texel(0, 0, x, y)[2], 0.0f);  // R16G16 has no blue
    }
  }
}

TEST(Ktx2Reader, RefusesMalformedFilesWithAMessage) {
  const auto good = encode_ktx2_cubemap(test_chain(4, 3), TexelFormat::rgba16f).value();
  // Every truncation is an error (never a read past the end: the sanitizer build runs this).
  for (std::size_t n = 0; n < good.size(); n += 7) {
    const std::vector<char> cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
    const auto t = parse_ktx2(cut, "cut.ktx2");
    ASSERT_FALSE(t.has_value()) << n << " bytes";
    EXPECT_EQ(t.error().message.rfind("cut.ktx2: ", 0), 0u) << t.error().message;
  }
  auto bad = good;
  bad[0] = 'X';
  EXPECT_NE(parse_ktx2(bad, "f").error().message.find("identifier"), std::string::npos);
  bad = good;
  const std::uint32_t huge = 0x7fffffffu;
  std::memcpy(bad.data() + 20, &huge, 4);  // pixelWidth
  EXPECT_NE(parse_ktx2(bad, "f").error().message.find("pixelWidth"), std::string::npos);
  bad = good;
  const std::uint64_t far = 1ull << 40;
  std::memcpy(bad.data() + 80, &far, 8);  // level 0's byteOffset
  EXPECT_NE(parse_ktx2(bad, "f").error().message.find("beyond the file"), std::string::npos);
  bad = good;
  const std::uint32_t format = 131;  // a BC format
  std::memcpy(bad.data() + 12, &format, 4);
  EXPECT_NE(parse_ktx2(bad, "f").error().message.find("vkFormat 131"), std::string::npos);
  EXPECT_FALSE(read_ktx2("/nonexistent/x.ktx2").has_value());
}

}  // namespace
}  // namespace shadelab
