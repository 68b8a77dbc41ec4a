#include "shadelab/envmap/base/ktx2.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <functional>
#include <numeric>

#include <Imath/half.h>

#include "shadelab/image/image_io.h"

namespace shadelab {

namespace {

constexpr std::array<unsigned char, 12> ktx2_identifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32,
                                                           0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};

// Khronos Data Format Specification 1.3 enumerants (khr_df.h).
constexpr std::uint32_t df_version_1_3 = 2;
constexpr std::uint32_t df_model_rgbsda = 1;
constexpr std::uint32_t df_primaries_bt709 = 1;
constexpr std::uint32_t df_transfer_linear = 1;
constexpr std::uint32_t df_channel_alpha = 15;
constexpr std::uint32_t df_qualifier_float = 0x80;
constexpr std::uint32_t df_qualifier_signed = 0x40;
constexpr std::uint32_t df_qualifier_exponent = 0x20;

struct Sample {
  std::uint32_t bit_offset, bit_length, channel_type, lower, upper;
};

std::vector<Sample> dfd_samples(TexelFormat f) {
  const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);
  const std::uint32_t minus_one = std::bit_cast<std::uint32_t>(-1.0f);
  const std::uint32_t sfloat = df_qualifier_float | df_qualifier_signed;
  switch (f) {
    case TexelFormat::rgba16f:
    case TexelFormat::rgba32f: {
      const std::uint32_t bits = f == TexelFormat::rgba16f ? 16 : 32;
      return {{0, bits, sfloat | 0, minus_one, one},
              {bits, bits, sfloat | 1, minus_one, one},
              {2 * bits, bits, sfloat | 2, minus_one, one},
              {3 * bits, bits, sfloat | df_channel_alpha, minus_one, one}};
    }
    case TexelFormat::rg11b10f:
      return {{0, 11, df_qualifier_float | 0, 0, one},
              {11, 11, df_qualifier_float | 1, 0, one},
              {22, 10, df_qualifier_float | 2, 0, one}};
    case TexelFormat::rgb9e5: {
      // Mantissa upper 8448 and exponent lower/upper 15/31 as the Data Format Specification's E5B9G9R9 example.
      std::vector<Sample> s;
      for (std::uint32_t c = 0; c < 3; ++c) {
        s.push_back({9 * c, 9, c, 0, 8448});
        s.push_back({27, 5, c | df_qualifier_exponent, 15, 31});
      }
      return s;
    }
  }
  return {};
}

void put_u32(std::vector<char>& out, std::uint32_t v) {
  char b[4];
  std::memcpy(b, &v, 4);
  out.insert(out.end(), b, b + 4);
}

void put_u64(std::vector<char>& out, std::uint64_t v) {
  char b[8];
  std::memcpy(b, &v, 8);
  out.insert(out.end(), b, b + 8);
}

void set_u64(std::vector<char>& out, std::size_t at, std::uint64_t v) { std::memcpy(out.data() + at, &v, 8); }
void set_u32(std::vector<char>& out, std::size_t at, std::uint32_t v) { std::memcpy(out.data() + at, &v, 4); }

void pad_to(std::vector<char>& out, std::size_t alignment) {
  while (out.size() % alignment != 0) out.push_back(0);
}

}  // namespace

namespace {

// What differs between a cube map and a 2D texture: the header fields, the DFD samples, and the bytes of
// each level (appended by `append_level`, which returns false on an encoding it refuses).
struct Ktx2Layout {
  std::uint32_t vk_format = 0;
  std::uint32_t type_size = 0;
  std::uint32_t texel_bytes = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t faces = 1;
  std::size_t levels = 1;
  std::vector<Sample> samples;
};

Result<std::vector<char>> encode_ktx2(const Ktx2Layout& layout, const KtxMetadata& metadata,
                                      const std::function<void(std::vector<char>&, std::size_t)>& append_level) {
  KtxMetadata kv = {{"KTXorientation", "rd"}, {"KTXwriter", ktx2_writer_name}};
  for (const auto& [key, value] : metadata) {
    if (key.empty() || key.rfind("KTX", 0) == 0 || key.rfind("ktx", 0) == 0) {
      return make_error("ktx2: metadata key '" + key + "' is empty or uses the reserved prefix KTX/ktx");
    }
    if (key.find('\0') != std::string::npos || value.find('\0') != std::string::npos) {
      return make_error("ktx2: metadata key '" + key + "' holds a NUL byte");
    }
    kv.emplace_back(key, value);
  }
  std::sort(kv.begin(), kv.end(), [](const auto& a, const auto& b) { return a.first < b.first; });  // byte order
  for (std::size_t i = 1; i < kv.size(); ++i) {
    if (kv[i].first == kv[i - 1].first) return make_error("ktx2: metadata key '" + kv[i].first + "' given twice");
  }

  const auto level_count = static_cast<std::uint32_t>(layout.levels);
  std::vector<char> out;
  for (const unsigned char c : ktx2_identifier) out.push_back(static_cast<char>(c));
  put_u32(out, layout.vk_format);
  put_u32(out, layout.type_size);
  put_u32(out, layout.width);   // pixelWidth
  put_u32(out, layout.height);  // pixelHeight
  put_u32(out, 0);              // pixelDepth
  put_u32(out, 0);              // layerCount
  put_u32(out, layout.faces);   // faceCount
  put_u32(out, level_count);
  put_u32(out, 0);  // supercompressionScheme: none
  const std::size_t index_at = out.size();
  for (int i = 0; i < 4; ++i) put_u32(out, 0);  // dfdByteOffset, dfdByteLength, kvdByteOffset, kvdByteLength
  put_u64(out, 0);                              // sgdByteOffset
  put_u64(out, 0);                              // sgdByteLength
  const std::size_t level_index_at = out.size();
  for (std::uint32_t i = 0; i < 3 * level_count; ++i) put_u64(out, 0);

  // Data Format Descriptor.
  const std::size_t dfd_at = out.size();
  const auto block_size = static_cast<std::uint32_t>(24 + 16 * layout.samples.size());
  put_u32(out, 4 + block_size);                         // dfdTotalSize
  put_u32(out, 0);                                      // vendorId Khronos (0), descriptorType basic (0)
  put_u32(out, df_version_1_3 | (block_size << 16));    // versionNumber, descriptorBlockSize
  put_u32(out, df_model_rgbsda | (df_primaries_bt709 << 8) | (df_transfer_linear << 16));  // flags 0: straight alpha
  put_u32(out, 0);                                      // texelBlockDimension0..3 = 1 (stored minus 1)
  put_u32(out, layout.texel_bytes);                     // bytesPlane0 = texel size, bytesPlane1..3 = 0
  put_u32(out, 0);                                      // bytesPlane4..7
  for (const Sample& s : layout.samples) {
    put_u32(out, s.bit_offset | ((s.bit_length - 1) << 16) | (s.channel_type << 24));
    put_u32(out, 0);  // samplePosition0..3
    put_u32(out, s.lower);
    put_u32(out, s.upper);
  }
  const std::size_t dfd_length = out.size() - dfd_at;

  // Key/value data.
  const std::size_t kvd_at = out.size();
  for (const auto& [key, value] : kv) {
    put_u32(out, static_cast<std::uint32_t>(key.size() + 1 + value.size() + 1));
    out.insert(out.end(), key.begin(), key.end());
    out.push_back(0);
    out.insert(out.end(), value.begin(), value.end());
    out.push_back(0);
    pad_to(out, 4);
  }
  const std::size_t kvd_length = out.size() - kvd_at;
  set_u32(out, index_at, static_cast<std::uint32_t>(dfd_at));
  set_u32(out, index_at + 4, static_cast<std::uint32_t>(dfd_length));
  set_u32(out, index_at + 8, static_cast<std::uint32_t>(kvd_at));
  set_u32(out, index_at + 12, static_cast<std::uint32_t>(kvd_length));

  // Levels, smallest first, each aligned to lcm(texel size, 4).
  const std::size_t alignment = std::lcm(static_cast<std::size_t>(layout.texel_bytes), std::size_t{4});
  for (std::size_t m = layout.levels; m-- > 0;) {
    pad_to(out, alignment);
    const std::size_t at = out.size();
    append_level(out, m);
    const std::uint64_t length = out.size() - at;
    set_u64(out, level_index_at + 24 * m, at);
    set_u64(out, level_index_at + 24 * m + 8, length);
    set_u64(out, level_index_at + 24 * m + 16, length);  // uncompressedByteLength: no supercompression
  }
  return out;
}

}  // namespace

Result<std::vector<char>> encode_ktx2_cubemap(const std::vector<CubeMap>& levels, TexelFormat format,
                                              const KtxMetadata& metadata, TexelEncodeInfo* info) {
  if (auto ok = check_cube_chain(levels, "ktx2"); !ok) return ok.error();
  Ktx2Layout layout;
  layout.vk_format = vk_format(format);
  layout.type_size = format == TexelFormat::rgba16f ? 2 : 4;
  layout.texel_bytes = texel_bytes(format);
  layout.width = layout.height = static_cast<std::uint32_t>(levels[0].size);
  layout.faces = 6;
  layout.levels = levels.size();
  layout.samples = dfd_samples(format);
  TexelEncodeInfo local;
  auto out = encode_ktx2(layout, metadata, [&](std::vector<char>& bytes, std::size_t m) {
    for (const Image& face : levels[m].faces) append_texels(bytes, face, format, &local);
  });
  if (out && info != nullptr) *info = local;
  return out;
}

std::uint32_t ktx2_image_vk_format(Ktx2ImageFormat f) { return f == Ktx2ImageFormat::rg16f ? 83 : 97; }

const char* ktx2_image_vk_format_name(Ktx2ImageFormat f) {
  return f == Ktx2ImageFormat::rg16f ? "VK_FORMAT_R16G16_SFLOAT" : "VK_FORMAT_R16G16B16A16_SFLOAT";
}

Result<std::vector<char>> encode_ktx2_image(const Image& image, Ktx2ImageFormat format, const KtxMetadata& metadata,
                                            TexelEncodeInfo* info) {
  if (image.width < 1 || image.height < 1) return make_error("ktx2: the image is empty");
  Ktx2Layout layout;
  layout.vk_format = ktx2_image_vk_format(format);
  layout.type_size = 2;
  layout.width = static_cast<std::uint32_t>(image.width);
  layout.height = static_cast<std::uint32_t>(image.height);
  if (format == Ktx2ImageFormat::rgba16f) {
    layout.texel_bytes = 8;
    layout.samples = dfd_samples(TexelFormat::rgba16f);
  } else {
    const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);
    const std::uint32_t minus_one = std::bit_cast<std::uint32_t>(-1.0f);
    const std::uint32_t sfloat = df_qualifier_float | df_qualifier_signed;
    layout.texel_bytes = 4;
    layout.samples = {{0, 16, sfloat | 0, minus_one, one}, {16, 16, sfloat | 1, minus_one, one}};
  }
  TexelEncodeInfo local;
  auto out = encode_ktx2(layout, metadata, [&](std::vector<char>& bytes, std::size_t) {
    if (format == Ktx2ImageFormat::rgba16f) {
      append_texels(bytes, image, TexelFormat::rgba16f, &local);
      return;
    }
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const Rgb c = image.at(x, y);
        for (const double v : {c.r, c.g}) {
          float f = static_cast<float>(v);
          if (std::isfinite(f) && std::abs(f) > half_max) {  // as append_texels: clamp finite values, count them
            f = std::copysign(half_max, f);
            ++local.clamped_values;
          }
          const std::uint16_t h = Imath::half(f).bits();
          bytes.push_back(static_cast<char>(h & 0xFF));
          bytes.push_back(static_cast<char>(h >> 8));
        }
      }
    }
  });
  if (out && info != nullptr) *info = local;
  return out;
}

Result<bool> write_ktx2_image(const Image& image, const std::filesystem::path& path, Ktx2ImageFormat format,
                              const KtxMetadata& metadata, TexelEncodeInfo* info) {
  auto bytes = encode_ktx2_image(image, format, metadata, info);
  if (!bytes) return make_error(path.string() + ": " + bytes.error().message);
  return write_file_atomically(path, *bytes);
}

Result<bool> write_ktx2_cubemap(const std::vector<CubeMap>& levels, const std::filesystem::path& path, TexelFormat format,
                                const KtxMetadata& metadata, TexelEncodeInfo* info) {
  auto bytes = encode_ktx2_cubemap(levels, format, metadata, info);
  if (!bytes) return make_error(path.string() + ": " + bytes.error().message);
  return write_file_atomically(path, *bytes);
}

}  // namespace shadelab
