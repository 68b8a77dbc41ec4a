// shadelab KTX 2.0 cube maps with mip chains (Khronos, "KTX File Format Specification", version 2.0, with
// the Data Format Descriptor of the "Khronos Data Format Specification" 1.3): the container Vulkan, WebGPU
// and glTF-era engines load (Babylon.js, three.js, Filament's loaders, the KTX-Software tools).
//
// Layout written (all little-endian): identifier «KTX 20»\r\n\x1A\n; vkFormat, typeSize (2 for RGBA16F, 4
// for RGBA32F and the packed formats), pixelWidth = pixelHeight = face size, pixelDepth 0, layerCount 0,
// faceCount 6, levelCount, supercompressionScheme 0; the index (dfd, kvd offsets and lengths, no sgd); the
// level index (byteOffset, byteLength, uncompressedByteLength per level, level 0 first); the DFD; the
// key/value data; then the levels, smallest first, each starting at a multiple of lcm(texel size, 4), each
// holding the six faces +X, -X, +Y, -Y, +Z, -Z (cubemap.h orientation), rows top to bottom, no padding.
//
// DFD: one basic descriptor block, version 1.3 (2), colour model RGBSDA, primaries BT.709, transfer linear,
// straight alpha, 1x1x1x1 texel blocks, bytesPlane0 = texel size; one sample per channel (float formats:
// F|S qualifiers, sampleLower -1.0f, sampleUpper 1.0f; B10G11R11: F, lower 0, upper 1.0f), and for
// E5B9G9R9 six samples: each channel's 9-bit mantissa (lower 0, upper 8448) and the shared 5-bit exponent
// (E qualifier, lower 15 = the bias, upper 31).
//
// Key/value data, sorted by key, each value a NUL-terminated UTF-8 string: KTXorientation "rd" (s to the
// right, t down: row 0 is t = 0), KTXwriter "shadelab <version>", plus the caller's keys (which must not
// start with "KTX"/"ktx", the reserved prefix).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/base/texel_format.h"

namespace shadelab {

using KtxMetadata = std::vector<std::pair<std::string, std::string>>;

inline constexpr const char* ktx2_writer_name = "shadelab 0.1.0";

// The file bytes for a mip chain (check_cube_chain). `info`, when given, receives what encoding clamped.
Result<std::vector<char>> encode_ktx2_cubemap(const std::vector<CubeMap>& levels, TexelFormat format,
                                              const KtxMetadata& metadata = {}, TexelEncodeInfo* info = nullptr);

// Encodes and writes atomically (write_file_atomically).
Result<bool> write_ktx2_cubemap(const std::vector<CubeMap>& levels, const std::filesystem::path& path, TexelFormat format,
                                const KtxMetadata& metadata = {}, TexelEncodeInfo* info = nullptr);

// A 2D texture (one level, one face; the DFG table of dfg.h): RG16F (VK_FORMAT_R16G16_SFLOAT, 83: the
// image's R and G, typeSize 2, DFD samples R and G as for RGBA16F) or RGBA16F (97: R, G, B, alpha 1). Rows
// top to bottom (row 0 at t = 0, KTXorientation "rd"); finite values beyond +-65504 are clamped and counted.
enum class Ktx2ImageFormat { rg16f, rgba16f };
std::uint32_t ktx2_image_vk_format(Ktx2ImageFormat f);        // 83, 97
const char* ktx2_image_vk_format_name(Ktx2ImageFormat f);     // "VK_FORMAT_R16G16_SFLOAT", ...
Result<std::vector<char>> encode_ktx2_image(const Image& image, Ktx2ImageFormat format, const KtxMetadata& metadata = {},
                                            TexelEncodeInfo* info = nullptr);
Result<bool> write_ktx2_image(const Image& image, const std::filesystem::path& path, Ktx2ImageFormat format,
                              const KtxMetadata& metadata = {}, TexelEncodeInfo* info = nullptr);

}  // namespace shadelab
