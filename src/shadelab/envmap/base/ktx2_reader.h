// shadelab KTX 2.0 reader: the uncompressed float textures ktx2.h writes (cube maps with mip chains, 2D
// tables), read back for `shadelab shader verify --ibl`, which shades with exactly the files `bake ibl` wrote.
// Khronos, "KTX File Format Specification", version 2.0: the 12-byte identifier, nine uint32 header fields
// (vkFormat, typeSize, pixelWidth, pixelHeight, pixelDepth, layerCount, faceCount, levelCount,
// supercompressionScheme), the index (dfd and kvd offsets and lengths as uint32, sgd as uint64), then per
// level byteOffset, byteLength, uncompressedByteLength (uint64), level 0 first; key/value data as
// (uint32 length, key NUL value) entries padded to 4 bytes. Level data: faces +X, -X, +Y, -Y, +Z, -Z, rows
// top to bottom, no padding for these formats.
//
// Read: vkFormat 97 (R16G16B16A16_SFLOAT), 109 (R32G32B32A32_SFLOAT), 122 (B10G11R11_UFLOAT_PACK32),
// 123 (E5B9G9R9_UFLOAT_PACK32) and 83 (R16G16_SFLOAT); no supercompression, 2D (pixelDepth 0), no array
// layers, 1 or 6 faces. Everything else, and every offset or length that does not fit the file, is an error
// naming the file and the field, found before anything is allocated beyond the file's own bytes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "shadelab/core/error.h"

namespace shadelab {

struct Ktx2Texture {
  std::uint32_t vk_format = 0;
  int width = 0;   // of level 0
  int height = 0;
  int faces = 1;   // 1 or 6
  // Per level: faces x height_i x width_i texels of four floats (RGBA; a format without alpha reads alpha 1,
  // R16G16 reads B = 0, A = 1), face-major, rows top to bottom.
  std::vector<std::vector<float>> levels;
  std::vector<std::pair<std::string, std::string>> metadata;  // key/value data (values without their NUL)

  int level_width(int level) const { return std::max(1, width >> level); }
  int level_height(int level) const { return std::max(1, height >> level); }
  // Texel (x, y) of face f of level l: its four floats.
  const float* texel(int level, int face, int x, int y) const {
    const auto w = static_cast<std::size_t>(level_width(level));
    const auto h = static_cast<std::size_t>(level_height(level));
    return levels[static_cast<std::size_t>(level)].data() +
           4 * ((static_cast<std::size_t>(face) * h + static_cast<std::size_t>(y)) * w + static_cast<std::size_t>(x));
  }
  // The value of a key, or empty.
  std::string value(const std::string& key) const;
};

// Parses the bytes of a KTX 2 file; `name` names it in errors.
Result<Ktx2Texture> parse_ktx2(const std::vector<char>& bytes, const std::string& name);
// Reads and parses a file (at most 1 GiB).
Result<Ktx2Texture> read_ktx2(const std::filesystem::path& path);

}  // namespace shadelab
