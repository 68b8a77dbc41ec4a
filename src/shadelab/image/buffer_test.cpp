// Pixel buffers (image.h, buffer.cpp): every block 64-byte aligned, a block of buffer_huge_bytes or more on a
// 2 MiB boundary (where the huge-page advice applies), values kept through growth and copies.
#include "shadelab/image/image.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace shadelab {
namespace {

std::uintptr_t address(const FloatBuffer& b) { return reinterpret_cast<std::uintptr_t>(b.data()); }

TEST(ImageBuffer, BlocksAreAlignedForTheirSize) {
  for (std::size_t n : {std::size_t{1}, std::size_t{3}, std::size_t{1000}, std::size_t{12345}}) {
    const FloatBuffer small(n, 1.0f);
    EXPECT_EQ(address(small) % 64, 0u) << n;
  }
  const std::size_t big = buffer_huge_bytes / sizeof(float) + 7;
  const FloatBuffer large(big, 2.0f);
  EXPECT_EQ(address(large) % (std::size_t{2} << 20), 0u);
  EXPECT_EQ(large.front(), 2.0f);
  EXPECT_EQ(large.back(), 2.0f);
  // An image of 1024 x 512 (6 MiB, above the threshold) and one of 16 x 16: rows of 16k pixels on cache lines.
  const Image hdri(1024, 512);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(hdri.data.data()) % (std::size_t{2} << 20), 0u);
  const Image face(16, 16);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(face.data.data()) % 64, 0u);
}

TEST(ImageBuffer, GrowthAndCopiesKeepTheValues) {
  FloatBuffer b;
  for (int i = 0; i < 2'000'000; ++i) b.push_back(static_cast<float>(i));  // crosses the 2 MiB threshold
  ASSERT_EQ(b.size(), 2'000'000u);
  EXPECT_EQ(b[0], 0.0f);
  EXPECT_EQ(b[1'999'999], 1'999'999.0f);
  const FloatBuffer copy = b;
  EXPECT_EQ(copy, b);
  b.resize(10);
  b.shrink_to_fit();
  EXPECT_EQ(b[9], 9.0f);
  EXPECT_EQ(address(b) % 64, 0u);
}

}  // namespace
}  // namespace shadelab
