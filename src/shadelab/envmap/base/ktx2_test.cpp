// KTX 2.0 cube maps read back by an independent reader: Node's ktx-parse (tools/containers/ktx2_dump.mjs,
// installed by scripts/setup.sh), which also checks the layout rules and decodes the texels itself.
#include "shadelab/envmap/base/ktx2.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>

#include "shadelab/envmap/base/container_test_util.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

using testing::container_temp_dir;
using testing::exact_chain;
using testing::exact_texel;

nlohmann::json dump(const std::filesystem::path& file, const std::string& queries) { return testing::ktx2_dump(file, queries); }

// The DFD samples each format must have (Khronos Data Format Specification 1.3; KTX-Software writes the same):
// {bitOffset, bitLength - 1, channelType (channel id | qualifiers F 0x80, S 0x40, E 0x20), lower, upper}.
struct ExpectedSample {
  int offset, length_minus_1, channel_type;
  long long lower, upper;
};

std::vector<ExpectedSample> expected_samples(TexelFormat f) {
  const long long one = 0x3F800000;        // 1.0f
  const long long minus_one = -0x40800000;  // -1.0f (0xBF800000) as the signed int32 ktx-parse reads for S samples
  switch (f) {
    case TexelFormat::rgba16f:
      return {{0, 15, 0xC0, minus_one, one}, {16, 15, 0xC1, minus_one, one}, {32, 15, 0xC2, minus_one, one}, {48, 15, 0xCF, minus_one, one}};
    case TexelFormat::rgba32f:
      return {{0, 31, 0xC0, minus_one, one}, {32, 31, 0xC1, minus_one, one}, {64, 31, 0xC2, minus_one, one}, {96, 31, 0xCF, minus_one, one}};
    case TexelFormat::rg11b10f:
      return {{0, 10, 0x80, 0, one}, {11, 10, 0x81, 0, one}, {22, 9, 0x82, 0, one}};
    case TexelFormat::rgb9e5:
      return {{0, 8, 0x00, 0, 8448}, {27, 4, 0x20, 15, 31}, {9, 8, 0x01, 0, 8448},
              {27, 4, 0x21, 15, 31}, {18, 8, 0x02, 0, 8448}, {27, 4, 0x22, 15, 31}};
  }
  return {};
}

TEST(Ktx2, EveryFormatReadsBackWithKtxParse) {
  const int size = 8;
  const auto chain = exact_chain(size);
  const auto queries = testing::texel_queries(size);
  for (TexelFormat f : all_texel_formats) {
    SCOPED_TRACE(texel_format_name(f));
    const auto path = container_temp_dir() / (std::string("exact_") + texel_format_name(f) + ".ktx2");
    const KtxMetadata meta = {{"shadelab.mip_mapping", R"({"lobe":"phong","exponents":[2048,256,32,2]})"}};
    ASSERT_TRUE(write_ktx2_cubemap(chain, path, f, meta).has_value());
    const auto j = dump(path, testing::query_args(queries));
    ASSERT_TRUE(j.is_object());
    EXPECT_TRUE(j["problems"].empty()) << j["problems"].dump();
    EXPECT_EQ(j["vkFormat"], vk_format(f));
    EXPECT_EQ(j["vkFormatName"], vk_format_name(f));
    EXPECT_EQ(j["pixelWidth"], size);
    EXPECT_EQ(j["pixelHeight"], size);
    EXPECT_EQ(j["pixelDepth"], 0);
    EXPECT_EQ(j["layerCount"], 0);
    EXPECT_EQ(j["faceCount"], 6);
    EXPECT_EQ(j["levelCount"], 4);  // 8, 4, 2, 1: the full chain
    EXPECT_EQ(j["supercompressionScheme"], 0);
    const auto& d = j["dfd"];
    EXPECT_EQ(d["vendorId"], 0);
    EXPECT_EQ(d["descriptorType"], 0);
    EXPECT_EQ(d["versionNumber"], 2);
    EXPECT_EQ(d["colorModel"], 1);
    EXPECT_EQ(d["colorPrimaries"], 1);
    EXPECT_EQ(d["transferFunction"], 1);
    EXPECT_EQ(d["flags"], 0);
    EXPECT_EQ(d["texelBlockDimension"], nlohmann::json::array({0, 0, 0, 0}));
    EXPECT_EQ(d["bytesPlane"][0], texel_bytes(f));
    const auto want = expected_samples(f);
    ASSERT_EQ(d["samples"].size(), want.size());
    for (std::size_t i = 0; i < want.size(); ++i) {
      const auto& s = d["samples"][i];
      EXPECT_EQ(s["bitOffset"], want[i].offset) << i;
      EXPECT_EQ(s["bitLength"], want[i].length_minus_1) << i;
      EXPECT_EQ(s["channelType"], want[i].channel_type) << i;
      EXPECT_EQ(s["sampleLower"].get<long long>(), want[i].lower) << i;
      EXPECT_EQ(s["sampleUpper"].get<long long>(), want[i].upper) << i;
    }
    EXPECT_EQ(j["keyValue"]["KTXorientation"], "rd");
    EXPECT_EQ(j["keyValue"]["KTXwriter"], ktx2_writer_name);
    EXPECT_EQ(j["keyValue"]["shadelab.mip_mapping"], meta[0].second);
    ASSERT_EQ(j["texels"].size(), queries.size());
    for (const auto& t : j["texels"]) {
      const Rgb want_rgb = exact_texel(t["level"].get<int>(), t["face"].get<int>(), t["x"].get<int>(), t["y"].get<int>());
      EXPECT_EQ(t["value"][0].get<double>(), want_rgb.r) << t.dump();
      EXPECT_EQ(t["value"][1].get<double>(), want_rgb.g) << t.dump();
      EXPECT_EQ(t["value"][2].get<double>(), want_rgb.b) << t.dump();
      if (f == TexelFormat::rgba16f || f == TexelFormat::rgba32f) {
        EXPECT_EQ(t["value"][3].get<double>(), 1.0);
      }
    }
  }
}

// Values that are not exact: what ktx-parse's side decodes is within each format's rounding bound of the input.
TEST(Ktx2, RoundedValuesWithinTheFormatsBound) {
  const int size = 4;
  std::vector<CubeMap> chain;
  Pcg32 rng(11);
  for (int n = size; n >= 1; n /= 2) {
    CubeMap c(n);
    for (int f = 0; f < 6; ++f)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) c.set(f, x, y, {std::exp(8 * rng.next_double() - 4), std::exp(8 * rng.next_double() - 4), std::exp(8 * rng.next_double() - 4)});
    chain.push_back(c);
  }
  const auto queries = testing::texel_queries(size);
  for (TexelFormat f : all_texel_formats) {
    SCOPED_TRACE(texel_format_name(f));
    const auto path = container_temp_dir() / (std::string("rounded_") + texel_format_name(f) + ".ktx2");
    ASSERT_TRUE(write_ktx2_cubemap(chain, path, f).has_value());
    const auto j = dump(path, testing::query_args(queries));
    EXPECT_TRUE(j["problems"].empty()) << j["problems"].dump();
    for (const auto& t : j["texels"]) {
      const Rgb in = chain[t["level"].get<std::size_t>()].texel(t["face"].get<int>(), t["x"].get<int>(), t["y"].get<int>());
      const double v[3] = {in.r, in.g, in.b};
      const double maxc = std::max({in.r, in.g, in.b});
      for (int c = 0; c < 3; ++c) {
        const double got = t["value"][c].get<double>();
        // Half a unit in the last place: 2^-11 (half), 2^-24 (float), 2^-7 / 2^-6 (11 / 10-bit), and for
        // RGB9E5 half a step of the shared exponent, at most 1/511.5 of the largest channel.
        double bound = 0.0;
        switch (f) {
          case TexelFormat::rgba16f: bound = std::ldexp(v[c], -11); break;
          case TexelFormat::rgba32f: bound = std::ldexp(v[c], -24); break;
          case TexelFormat::rg11b10f: bound = std::ldexp(v[c], c < 2 ? -7 : -6); break;
          case TexelFormat::rgb9e5: bound = maxc / 511.5; break;
        }
        EXPECT_LE(std::abs(got - v[c]), bound) << t.dump() << " channel " << c << " input " << v[c];
      }
    }
  }
}

TEST(Ktx2, LayoutRulesInTheBytes) {
  // The parts ktx-parse does not check: levels stored smallest first at aligned offsets, index values.
  const auto bytes = encode_ktx2_cubemap(exact_chain(4), TexelFormat::rgba32f).value();
  auto u32 = [&](std::size_t at) { std::uint32_t v; std::memcpy(&v, bytes.data() + at, 4); return v; };
  auto u64 = [&](std::size_t at) { std::uint64_t v; std::memcpy(&v, bytes.data() + at, 8); return v; };
  const unsigned char id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  EXPECT_EQ(std::memcmp(bytes.data(), id, 12), 0);
  EXPECT_EQ(u32(48), 80u + 3 * 24);  // the DFD follows the level index of 3 levels
  EXPECT_EQ(u64(64), 0u);            // no supercompression global data
  EXPECT_EQ(u64(72), 0u);
  const std::uint64_t l0 = u64(80), l1 = u64(104), l2 = u64(128);
  EXPECT_LT(l2, l1);
  EXPECT_LT(l1, l0);
  EXPECT_EQ(l0 % 16, 0u);
  EXPECT_EQ(l0 + u64(88), bytes.size());  // level 0 ends the file
  EXPECT_EQ(u64(88), 6u * 4 * 4 * 16);
}

TEST(Ktx2, RefusesBadChainsAndKeys) {
  auto chain = exact_chain(8);
  chain[2] = CubeMap(3);
  EXPECT_FALSE(encode_ktx2_cubemap(chain, TexelFormat::rgba16f).has_value());
  EXPECT_FALSE(encode_ktx2_cubemap({}, TexelFormat::rgba16f).has_value());
  EXPECT_FALSE(encode_ktx2_cubemap(exact_chain(2), TexelFormat::rgba16f, {{"KTXorientation", "ru"}}).has_value());
  EXPECT_FALSE(encode_ktx2_cubemap(exact_chain(2), TexelFormat::rgba16f, {{"", "x"}}).has_value());
  EXPECT_FALSE(encode_ktx2_cubemap(exact_chain(2), TexelFormat::rgba16f, {{"a", "x"}, {"a", "y"}}).has_value());
  const auto path = container_temp_dir() / "refused.ktx2";
  EXPECT_FALSE(write_ktx2_cubemap({}, path, TexelFormat::rgba16f).has_value());
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace shadelab
