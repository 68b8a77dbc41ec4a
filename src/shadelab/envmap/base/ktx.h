// shadelab KTX 1.1 cube maps with mip chains (Khronos, "KTX File Format Specification", version 1.1):
// the container glTF-era engines and tools load for prefiltered environments (Filament, bgfx, Babylon.js,
// PVRTexTool, the KTX-Software tools).
//
// Layout: 64-byte header (identifier, endianness 0x04030201, glType, glTypeSize, glFormat,
// glInternalFormat, glBaseInternalFormat, width, height, depth 0, array elements 0, faces 6, mip levels,
// key/value bytes 0), then per mip level a uint32 imageSize (bytes of one face) followed by the six faces in
// OpenGL order +X, -X, +Y, -Y, +Z, -Z, rows top to bottom as in cubemap.h. Pixels are RGBA (alpha 1) as
// GL_RGBA16F (half, default) or GL_RGBA32F; every row is a multiple of 4 bytes, so no padding occurs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/envmap/base/cubemap.h"

namespace shadelab {

enum class KtxPixelType { half, float32 };

// What encoding did beyond copying: RGBA16F holds at most 65504 (the largest finite half), so finite values
// beyond +-65504 are clamped to it (as the EXR half writer does) instead of becoming +-inf; NaN and inf stay.
struct KtxEncodeInfo {
  std::uint64_t clamped_values = 0;  // channel values clamped to +-65504
};
inline constexpr float ktx_half_max = 65504.0f;

// The file bytes for a mip chain (level i has face size max(1, size0 >> i)). Errors on an empty chain or a
// level whose size does not halve. `info`, when given, receives the count of clamped values.
Result<std::vector<char>> encode_ktx_cubemap(const std::vector<CubeMap>& levels, KtxPixelType type = KtxPixelType::half,
                                             KtxEncodeInfo* info = nullptr);
// Reads back what encode_ktx_cubemap writes (RGBA16F or RGBA32F cube maps); errors name what is wrong.
Result<std::vector<CubeMap>> decode_ktx_cubemap(const std::vector<char>& bytes);

// Encodes and writes atomically.
Result<bool> write_ktx_cubemap(const std::vector<CubeMap>& levels, const std::filesystem::path& path,
                               KtxPixelType type = KtxPixelType::half, KtxEncodeInfo* info = nullptr);

}  // namespace shadelab
