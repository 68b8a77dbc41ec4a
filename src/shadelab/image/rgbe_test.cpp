// Tests of the Radiance RGBE decoder: agreement with stb_image on valid files, every orientation and
// encoding, and errors (never a hang) for every truncation and each kind of corrupt run.
#include "shadelab/image/rgbe.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace shadelab {
namespace {

constexpr long long limit = 1LL << 27;

std::vector<unsigned char> header(const std::string& resolution, const std::string& extra = "") {
  const std::string text = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n" + extra + "\n" + resolution + "\n";
  return {text.begin(), text.end()};
}

void append(std::vector<unsigned char>& out, std::initializer_list<int> bytes) {
  for (int b : bytes) {
    out.push_back(static_cast<unsigned char>(b));
  }
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
}

// An stb-written file of w x h random HDR values (run-length encoded when 8 <= w < 32768).
std::vector<unsigned char> stb_file(int w, int h, std::uint32_t seed) {
  std::mt19937 engine(seed);
  std::vector<float> values(static_cast<std::size_t>(w * h * 3));
  for (float& v : values) {
    // Mostly smooth values so that runs occur, with some noise and zeros.
    const auto r = engine();
    v = (r % 4 == 0) ? 0.0f : std::ldexp(static_cast<float>(r % 1000) / 1000.0f, static_cast<int>(r % 30) - 15);
  }
  std::vector<unsigned char> out;
  EXPECT_NE(stbi_write_hdr_to_func(append_bytes, &out, w, h, 3, values.data()), 0);
  return out;
}

TEST(Rgbe, AgreesWithStbOnValidFiles) {
  // Widths below 8 are flat; 8 and above are run-length encoded by stb_image_write.
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{1, 1}, {5, 3}, {8, 2}, {33, 17}, {300, 4}}) {
    const std::vector<unsigned char> file = stb_file(w, h, static_cast<std::uint32_t>(w * 1000 + h));
    const Result<Image> ours = decode_rgbe(file.data(), file.size(), limit);
    ASSERT_TRUE(ours) << ours.error().message;
    int sw = 0;
    int sh = 0;
    int sn = 0;
    float* theirs = stbi_loadf_from_memory(file.data(), static_cast<int>(file.size()), &sw, &sh, &sn, 3);
    ASSERT_NE(theirs, nullptr);
    EXPECT_EQ(ours->width, sw);
    EXPECT_EQ(ours->height, sh);
    EXPECT_EQ(std::memcmp(ours->data.data(), theirs, ours->data.size() * sizeof(float)), 0) << w << " x " << h;
    stbi_image_free(theirs);
  }
}

TEST(Rgbe, DecodesTheMantissaExponentPair) {
  std::vector<unsigned char> file = header("-Y 1 +X 3");
  append(file, {128, 64, 0, 129,  // (128, 64, 0) * 2^(129 - 136) = (1, 0.5, 0)
                255, 1, 10, 136,  // exponent 136: the mantissa bytes themselves
                200, 200, 200, 0});  // exponent 0 is black whatever the mantissas
  const Result<Image> image = decode_rgbe(file.data(), file.size(), limit);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->at(0, 0).r, 1.0);
  EXPECT_EQ(image->at(0, 0).g, 0.5);
  EXPECT_EQ(image->at(0, 0).b, 0.0);
  EXPECT_EQ(image->at(1, 0).r, 255.0);
  EXPECT_EQ(image->at(1, 0).g, 1.0);
  EXPECT_EQ(image->at(1, 0).b, 10.0);
  EXPECT_TRUE(image->at(2, 0).is_black());
}

TEST(Rgbe, EveryOrientation) {
  // Scan line data 0..5 (as the red mantissa, exponent 136) laid out by each resolution line; expected
  // image (3 wide, 2 high), row 0 on top, red values listed row by row.
  struct Case {
    const char* resolution;
    std::vector<int> expected;
  };
  const std::vector<Case> cases = {
      {"-Y 2 +X 3", {0, 1, 2, 3, 4, 5}}, {"+Y 2 +X 3", {3, 4, 5, 0, 1, 2}},
      {"-Y 2 -X 3", {2, 1, 0, 5, 4, 3}}, {"+Y 2 -X 3", {5, 4, 3, 2, 1, 0}},
      {"+X 3 -Y 2", {0, 2, 4, 1, 3, 5}}, {"+X 3 +Y 2", {1, 3, 5, 0, 2, 4}},
      {"-X 3 -Y 2", {4, 2, 0, 5, 3, 1}}, {"-X 3 +Y 2", {5, 3, 1, 4, 2, 0}},
  };
  for (const Case& c : cases) {
    std::vector<unsigned char> file = header(c.resolution);
    for (int k = 0; k < 6; ++k) {
      append(file, {k, 0, 0, 136});
    }
    const Result<Image> image = decode_rgbe(file.data(), file.size(), limit);
    ASSERT_TRUE(image) << c.resolution << ": " << image.error().message;
    ASSERT_EQ(image->width, 3) << c.resolution;
    ASSERT_EQ(image->height, 2) << c.resolution;
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 3; ++x) {
        EXPECT_EQ(image->at(x, y).r, c.expected[static_cast<std::size_t>(3 * y + x)])
            << c.resolution << " at " << x << "," << y;
      }
    }
  }
}

TEST(Rgbe, OriginalRunLengthPixels) {
  // (1,1,1,c) repeats the previous texel c times; a second one in a row repeats c << 8 times.
  std::vector<unsigned char> file = header("-Y 1 +X 300");
  append(file, {10, 20, 30, 136, 1, 1, 1, 3,   // texel, then 3 repeats: 4 texels
                40, 50, 60, 136, 1, 1, 1, 39, 1, 1, 1, 1});  // texel, 39 + 256 repeats: 296 texels
  const Result<Image> image = decode_rgbe(file.data(), file.size(), limit);
  ASSERT_TRUE(image) << image.error().message;
  for (int x = 0; x < 300; ++x) {
    EXPECT_EQ(image->at(x, 0).r, x < 4 ? 10.0 : 40.0) << x;
    EXPECT_EQ(image->at(x, 0).b, x < 4 ? 30.0 : 60.0) << x;
  }
}

TEST(Rgbe, MixedEncodingsAcrossScanLines) {
  // Scan line 0 run-length encoded per component, scan line 1 flat.
  std::vector<unsigned char> file = header("-Y 2 +X 8");
  append(file, {2, 2, 0, 8,
                128 + 8, 7,                      // red: 8 x 7
                8, 0, 1, 2, 3, 4, 5, 6, 7,       // green: literal 0..7
                128 + 4, 1, 128 + 4, 2,          // blue: 4 x 1, 4 x 2
                128 + 8, 136});                  // exponent: 8 x 136
  for (int k = 0; k < 8; ++k) {
    append(file, {k, 9, 9, 136});
  }
  const Result<Image> image = decode_rgbe(file.data(), file.size(), limit);
  ASSERT_TRUE(image) << image.error().message;
  for (int x = 0; x < 8; ++x) {
    EXPECT_EQ(image->at(x, 0).r, 7.0);
    EXPECT_EQ(image->at(x, 0).g, x);
    EXPECT_EQ(image->at(x, 0).b, x < 4 ? 1.0 : 2.0);
    EXPECT_EQ(image->at(x, 1).r, x);
    EXPECT_EQ(image->at(x, 1).g, 9.0);
  }
}

TEST(Rgbe, EveryTruncationIsAnError) {
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{{5, 3}, {40, 6}}) {
    const std::vector<unsigned char> file = stb_file(w, h, 77);
    ASSERT_TRUE(decode_rgbe(file.data(), file.size(), limit));
    for (std::size_t keep = 0; keep < file.size(); ++keep) {
      const Result<Image> image = decode_rgbe(file.data(), keep, limit);
      ASSERT_FALSE(image) << "kept " << keep << " of " << file.size() << " bytes";
    }
  }
}

TEST(Rgbe, CorruptDataIsAnError) {
  const auto fails = [](std::vector<unsigned char> file, const std::string& reason) {
    const Result<Image> image = decode_rgbe(file.data(), file.size(), limit);
    ASSERT_FALSE(image);
    EXPECT_NE(image.error().message.find(reason), std::string::npos) << image.error().message;
  };
  std::vector<unsigned char> zero_run = header("-Y 1 +X 8");
  append(zero_run, {2, 2, 0, 8, 0, 0, 0, 0, 0, 0, 0, 0});  // stb_image spins forever on this
  fails(zero_run, "zero-length run");
  std::vector<unsigned char> overrun = header("-Y 1 +X 8");
  append(overrun, {2, 2, 0, 8, 128 + 9, 1});
  fails(overrun, "overruns");
  std::vector<unsigned char> wrong_length = header("-Y 1 +X 8");
  append(wrong_length, {2, 2, 0, 9});
  fails(wrong_length, "does not match");
  std::vector<unsigned char> leading_repeat = header("-Y 1 +X 3");
  append(leading_repeat, {1, 1, 1, 2, 5, 5, 5, 136});
  fails(leading_repeat, "repeat texel");
  fails(header("-Y 1 +X 3", "FORMAT=32-bit_rle_xyze\n"), "unsupported Radiance FORMAT");
  fails(header("-Y 0 +X 3"), "bad resolution line");
  fails(header("-Y 2 -Y 3"), "bad resolution line");
  fails(header("Y 2 X 3"), "bad resolution line");
  fails(header("-Y 100000 +X 100000"), "too large");
  const std::string no_signature = "RADIANCE\n\n-Y 1 +X 1\n";
  fails({no_signature.begin(), no_signature.end()}, "signature");
}

}  // namespace
}  // namespace shadelab
