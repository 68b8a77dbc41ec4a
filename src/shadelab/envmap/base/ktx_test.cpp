#include "shadelab/envmap/base/ktx.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace shadelab {
namespace {

std::vector<CubeMap> chain(int size) {
  std::vector<CubeMap> levels;
  for (int n = size; n >= 1; n /= 2) {
    CubeMap c(n);
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) c.set(f, x, y, {f + 0.25 * x, 0.5 * y, 1.0 / n});
    levels.push_back(c);
  }
  return levels;
}

std::uint32_t u32(const std::vector<char>& b, std::size_t off) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + off, 4);
  return v;
}

TEST(Ktx, HeaderFollowsTheSpecification) {
  const auto bytes = encode_ktx_cubemap(chain(8), KtxPixelType::half).value();
  const unsigned char id[12] = {0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB, '\r', '\n', 0x1A, '\n'};
  EXPECT_EQ(std::memcmp(bytes.data(), id, 12), 0);
  EXPECT_EQ(u32(bytes, 12), 0x04030201u);
  EXPECT_EQ(u32(bytes, 16), 0x140Bu);  // GL_HALF_FLOAT
  EXPECT_EQ(u32(bytes, 20), 2u);
  EXPECT_EQ(u32(bytes, 24), 0x1908u);  // GL_RGBA
  EXPECT_EQ(u32(bytes, 28), 0x881Au);  // GL_RGBA16F
  EXPECT_EQ(u32(bytes, 36), 8u);
  EXPECT_EQ(u32(bytes, 40), 8u);
  EXPECT_EQ(u32(bytes, 52), 6u);       // faces
  EXPECT_EQ(u32(bytes, 56), 4u);       // mips 8, 4, 2, 1
  EXPECT_EQ(u32(bytes, 64), 8u * 8u * 4u * 2u);  // imageSize of level 0: one face
  // Total: header + per level (4 + 6 faces).
  std::size_t expected = 64;
  for (int n = 8; n >= 1; n /= 2) expected += 4 + 6 * static_cast<std::size_t>(n * n * 8);
  EXPECT_EQ(bytes.size(), expected);
}

TEST(Ktx, RoundTrips) {
  const auto levels = chain(16);
  for (auto type : {KtxPixelType::half, KtxPixelType::float32}) {
    const auto back = decode_ktx_cubemap(encode_ktx_cubemap(levels, type).value());
    ASSERT_TRUE(back.has_value()) << back.error().message;
    ASSERT_EQ(back->size(), levels.size());
    for (std::size_t m = 0; m < levels.size(); ++m)
      for (int f = 0; f < 6; ++f) {
        const double tol = type == KtxPixelType::half ? 2e-3 * (f + 4.0) : 0.0;
        EXPECT_NEAR((*back)[m].texel(f, 0, levels[m].size - 1).r, levels[m].texel(f, 0, levels[m].size - 1).r, tol);
        EXPECT_NEAR((*back)[m].texel(f, levels[m].size - 1, 0).g, levels[m].texel(f, levels[m].size - 1, 0).g, tol);
      }
  }
}

TEST(Ktx, BadInputIsAnError) {
  EXPECT_FALSE(encode_ktx_cubemap({}).has_value());
  std::vector<CubeMap> wrong = {CubeMap(8), CubeMap(3)};
  EXPECT_FALSE(encode_ktx_cubemap(wrong).has_value());
  auto bytes = encode_ktx_cubemap(chain(4)).value();
  bytes.resize(bytes.size() / 2);
  EXPECT_FALSE(decode_ktx_cubemap(bytes).has_value());
  EXPECT_FALSE(decode_ktx_cubemap(std::vector<char>(100, 'x')).has_value());
}

// A header whose sizes the file cannot hold is an error that names the field, not an allocation: a face
// side of 2^31 + 1 once made the level-1 imageSize product wrap to 0 and the reader allocate 2^30-texel faces.
TEST(Ktx, HeaderSizesOutOfRangeAreErrorsNamingTheField) {
  const auto good = encode_ktx_cubemap(chain(4)).value();
  auto with = [&](std::size_t offset, std::uint32_t v) {
    auto bytes = good;
    std::memcpy(bytes.data() + offset, &v, 4);
    return decode_ktx_cubemap(bytes);
  };
  ASSERT_TRUE(decode_ktx_cubemap(good).has_value());
  for (std::uint32_t width : {0u, 0x80000001u, 65537u}) {
    auto r = with(36, width);
    ASSERT_FALSE(r.has_value()) << width;
    EXPECT_NE(r.error().message.find("pixelWidth"), std::string::npos) << r.error().message;
  }
  auto not_square = with(40, 8);
  ASSERT_FALSE(not_square.has_value());
  EXPECT_NE(not_square.error().message.find("pixelHeight 8"), std::string::npos) << not_square.error().message;
  auto too_many = with(56, 4);  // a 4-texel face has at most 3 levels (4, 2, 1)
  ASSERT_FALSE(too_many.has_value());
  EXPECT_NE(too_many.error().message.find("numberOfMipmapLevels 4"), std::string::npos) << too_many.error().message;
  EXPECT_TRUE(with(56, 3).has_value());
}

TEST(Ktx, WritesAtomically) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "shadelab_ktx_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "env.ktx";
  ASSERT_TRUE(write_ktx_cubemap(chain(4), path).has_value());
  std::ifstream f(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(decode_ktx_cubemap(bytes).has_value());
  EXPECT_FALSE(write_ktx_cubemap(chain(4), dir / "missing" / "env.ktx").has_value());
  std::filesystem::remove_all(dir);
}

// issue 16, 3: values above 65504 became +inf in RGBA16F with exit 0. They are clamped to the largest
// finite half (as the EXR half writer does) and counted; NaN is neither clamped nor counted. The half bits
// are read back from the file bytes, not through the encoder's own conversion.
TEST(Ktx, HalfValuesBeyondTheRangeAreClampedAndCounted) {
  CubeMap cube(1);
  cube.set(0, 0, 0, {2e5, -3e7, 1.0});
  cube.set(1, 0, 0, {std::nan(""), 65504.0, 7e4});  // 65504 is the largest half itself: kept, not counted
  KtxEncodeInfo info;
  const auto bytes = encode_ktx_cubemap({cube}, KtxPixelType::half, &info);
  ASSERT_TRUE(bytes.has_value()) << bytes.error().message;
  EXPECT_EQ(info.clamped_values, 3u);
  auto half_at = [&](std::size_t face, std::size_t channel) {
    std::uint16_t bits = 0;
    // 64-byte header, 4-byte imageSize, then per face one texel of 4 halves.
    std::memcpy(&bits, bytes->data() + 68 + face * 8 + channel * 2, 2);
    return bits;
  };
  EXPECT_EQ(half_at(0, 0), 0x7BFFu);  // +65504: exponent 30, mantissa all ones
  EXPECT_EQ(half_at(0, 1), 0xFBFFu);  // -65504
  EXPECT_EQ(half_at(0, 2), 0x3C00u);  // 1
  EXPECT_EQ(half_at(1, 0) & 0x7C00u, 0x7C00u);  // NaN stays NaN (exponent all ones, mantissa non-zero)
  EXPECT_NE(half_at(1, 0) & 0x03FFu, 0u);
  EXPECT_EQ(half_at(1, 1), 0x7BFFu);
  EXPECT_EQ(half_at(1, 2), 0x7BFFu);
  // Float KTX keeps everything and clamps nothing.
  KtxEncodeInfo full;
  ASSERT_TRUE(encode_ktx_cubemap({cube}, KtxPixelType::float32, &full).has_value());
  EXPECT_EQ(full.clamped_values, 0u);
}

}  // namespace
}  // namespace shadelab
