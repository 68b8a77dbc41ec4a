#include "shadelab/envmap/base/ktx.h"

#include <Imath/half.h>

#include <array>
#include <bit>
#include <cstdint>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "shadelab/envmap/base/texel_format.h"
#include "shadelab/image/image_io.h"

namespace shadelab {

namespace {

constexpr std::array<unsigned char, 12> ktx_identifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31,
                                                          0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
// OpenGL enumerants (the KTX header stores them).
constexpr std::uint32_t gl_half_float = 0x140B;
constexpr std::uint32_t gl_float = 0x1406;
constexpr std::uint32_t gl_rgba = 0x1908;
constexpr std::uint32_t gl_rgba16f = 0x881A;
constexpr std::uint32_t gl_rgba32f = 0x8814;

void put_u32(std::vector<char>& out, std::uint32_t v) {
  char b[4];
  std::memcpy(b, &v, 4);  // little-endian machines: the endianness field tells readers
  out.insert(out.end(), b, b + 4);
}

std::uint32_t get_u32(const std::vector<char>& in, std::size_t offset) {
  std::uint32_t v = 0;
  std::memcpy(&v, in.data() + offset, 4);
  return v;
}


}  // namespace

Result<std::vector<char>> encode_ktx_cubemap(const std::vector<CubeMap>& levels, KtxPixelType type, KtxEncodeInfo* info) {
  std::uint64_t clamped = 0;
  if (levels.empty() || levels[0].size < 1) return make_error("ktx: nothing to write (no mip levels)");
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const int expected = std::max(1, levels[0].size >> i);
    if (levels[i].size != expected) {
      return make_error("ktx: mip level " + std::to_string(i) + " has size " + std::to_string(levels[i].size) +
                        ", expected " + std::to_string(expected));
    }
  }
  const bool half = type == KtxPixelType::half;
  const std::uint32_t bytes_per_channel = half ? 2 : 4;
  std::vector<char> out;
  for (const unsigned char c : ktx_identifier) out.push_back(static_cast<char>(c));
  put_u32(out, 0x04030201);                          // endianness
  put_u32(out, half ? gl_half_float : gl_float);     // glType
  put_u32(out, bytes_per_channel);                   // glTypeSize
  put_u32(out, gl_rgba);                             // glFormat
  put_u32(out, half ? gl_rgba16f : gl_rgba32f);      // glInternalFormat
  put_u32(out, gl_rgba);                             // glBaseInternalFormat
  put_u32(out, static_cast<std::uint32_t>(levels[0].size));  // pixelWidth
  put_u32(out, static_cast<std::uint32_t>(levels[0].size));  // pixelHeight
  put_u32(out, 0);                                   // pixelDepth
  put_u32(out, 0);                                   // numberOfArrayElements
  put_u32(out, 6);                                   // numberOfFaces
  put_u32(out, static_cast<std::uint32_t>(levels.size()));  // numberOfMipmapLevels
  put_u32(out, 0);                                   // bytesOfKeyValueData
  TexelEncodeInfo encoded;
  for (const CubeMap& level : levels) {
    const auto n = static_cast<std::uint32_t>(level.size);
    put_u32(out, n * n * 4 * bytes_per_channel);  // imageSize: one face of a non-array cube map
    // RGBA16F / RGBA32F texels, alpha 1, half values clamped to +-65504 (texel_format.h, shared with KTX 2 / DDS).
    for (const Image& face : level.faces) append_texels(out, face, half ? TexelFormat::rgba16f : TexelFormat::rgba32f, &encoded);
  }
  clamped = encoded.clamped_values;
  if (info != nullptr) info->clamped_values = clamped;
  return out;
}

Result<std::vector<CubeMap>> decode_ktx_cubemap(const std::vector<char>& in) {
  if (in.size() < 64 || std::memcmp(in.data(), ktx_identifier.data(), 12) != 0) {
    return make_error("ktx: not a KTX 1.1 file (bad identifier)");
  }
  if (get_u32(in, 12) != 0x04030201) return make_error("ktx: big-endian files are not supported");
  const std::uint32_t gl_type = get_u32(in, 16);
  const std::uint32_t internal = get_u32(in, 28);
  const bool half = gl_type == gl_half_float && internal == gl_rgba16f;
  const bool full = gl_type == gl_float && internal == gl_rgba32f;
  if (!half && !full) return make_error("ktx: only RGBA16F and RGBA32F are supported");
  const std::uint32_t width = get_u32(in, 36);
  const std::uint32_t height = get_u32(in, 40);
  const std::uint32_t faces = get_u32(in, 52);
  const std::uint32_t mips = get_u32(in, 56);
  const std::uint32_t kv = get_u32(in, 60);  // bytesOfKeyValueData
  if (faces != 6) return make_error("ktx: not a cube map (numberOfFaces = " + std::to_string(faces) + ")");
  // A face side beyond max_image_side would overflow the imageSize product (and int) before the size check.
  if (width == 0 || width > static_cast<std::uint32_t>(max_image_side)) {
    return make_error("ktx: pixelWidth " + std::to_string(width) + " is out of range (1 .. " +
                      std::to_string(max_image_side) + ")");
  }
  if (height != width) {
    return make_error("ktx: cube faces must be square (pixelWidth " + std::to_string(width) + ", pixelHeight " +
                      std::to_string(height) + ")");
  }
  const std::uint32_t full_chain = static_cast<std::uint32_t>(std::bit_width(width));  // 1 + floor(log2 width)
  if (mips == 0 || mips > full_chain) {
    return make_error("ktx: numberOfMipmapLevels " + std::to_string(mips) + " is out of range (1 .. " +
                      std::to_string(full_chain) + " for a " + std::to_string(width) + "-texel face)");
  }
  std::size_t offset = 64 + kv;
  const std::size_t bpc = half ? 2 : 4;
  std::vector<CubeMap> levels;
  for (std::uint32_t m = 0; m < mips; ++m) {
    const int n = std::max(1, static_cast<int>(width >> m));
    if (offset + 4 > in.size()) return make_error("ktx: truncated at mip level " + std::to_string(m));
    const std::size_t image_size = get_u32(in, offset);
    offset += 4;
    const std::size_t expected = static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * 4 * bpc;
    if (image_size != expected) return make_error("ktx: mip level " + std::to_string(m) + " has the wrong imageSize");
    if (offset + 6 * image_size > in.size()) return make_error("ktx: truncated at mip level " + std::to_string(m));
    CubeMap level(n);
    for (Image& face : level.faces) {
      for (std::size_t p = 0; p < face.pixel_count(); ++p) {
        for (std::size_t c = 0; c < 4; ++c) {
          float v = 0.0f;
          if (half) {
            std::uint16_t bits = 0;
            std::memcpy(&bits, in.data() + offset, 2);
            Imath::half h;
            h.setBits(bits);
            v = static_cast<float>(h);
          } else {
            std::memcpy(&v, in.data() + offset, 4);
          }
          offset += bpc;
          if (c < 3) face.data[3 * p + c] = v;
        }
      }
    }
    levels.push_back(std::move(level));
  }
  return levels;
}

Result<bool> write_ktx_cubemap(const std::vector<CubeMap>& levels, const std::filesystem::path& path, KtxPixelType type,
                               KtxEncodeInfo* info) {
  auto bytes = encode_ktx_cubemap(levels, type, info);
  if (!bytes) return make_error(path.string() + ": " + bytes.error().message);
  return write_file_atomically(path, *bytes);
}

}  // namespace shadelab
