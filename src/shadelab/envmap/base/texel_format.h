// shadelab texel formats of the engine containers (KTX 2.0 and DDS): the four HDR formats engines sample
// environment cubes in, their encoders and decoders.
//
//   rgba16f   VK_FORMAT_R16G16B16A16_SFLOAT (97)   DXGI_FORMAT_R16G16B16A16_FLOAT (10)   8 bytes, alpha 1
//   rgba32f   VK_FORMAT_R32G32B32A32_SFLOAT (109)  DXGI_FORMAT_R32G32B32A32_FLOAT (2)    16 bytes, alpha 1
//   rg11b10f  VK_FORMAT_B10G11R11_UFLOAT_PACK32 (122)  DXGI_FORMAT_R11G11B10_FLOAT (26)  4 bytes, no alpha
//   rgb9e5    VK_FORMAT_E5B9G9R9_UFLOAT_PACK32 (123)   DXGI_FORMAT_R9G9B9E5_SHAREDEXP (67) 4 bytes, no alpha
// The packed formats have the same bits in both APIs (Vulkan names the fields from the high bit, DXGI from
// the low bit): rg11b10f holds R in bits 0..10, G in 11..21, B in 22..31 of a little-endian uint32;
// rgb9e5 holds the R, G, B mantissas in bits 0..8, 9..17, 18..26 and the shared exponent in 27..31.
//
// Definitions (Vulkan 1.3 specification, "Unsigned 11-Bit / 10-Bit Floating-Point Numbers" and "Shared
// Exponent"; the D3D11 functional specification states the same formats):
//   ufloat with 5 exponent bits (bias 15) and m mantissa bits (m = 6 for 11-bit, 5 for 10-bit):
//     E = 0: M 2^-14 / 2^m;  0 < E < 31: 2^(E-15) (1 + M / 2^m);  E = 31: inf (M = 0) or NaN (M != 0).
//   rgb9e5: value = M 2^(E - 15 - 9); encoding per the specification's algorithm: clamp each channel to
//     [0, 65408] (NaN -> 0), exp' = max(-16, floor(log2(max channel))) + 16, max_s = floor(max / 2^(exp' - 24)
//     + 1/2), exp = exp' + 1 if max_s = 512 else exp', channel_s = floor(c / 2^(exp - 24) + 1/2).
// Our ufloat encoder rounds to nearest, ties to even; negative values and -inf become 0, finite values above
// the largest finite (65024 for 11-bit, 64512 for 10-bit) become it, +inf and NaN stay inf and NaN. Half
// floats clamp finite values to +-65504 (as the KTX 1 writer does); NaN and inf stay.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/image/image.h"

namespace shadelab {

enum class TexelFormat { rgba16f, rgba32f, rg11b10f, rgb9e5 };
inline constexpr std::array<TexelFormat, 4> all_texel_formats = {TexelFormat::rgba16f, TexelFormat::rgba32f,
                                                                 TexelFormat::rg11b10f, TexelFormat::rgb9e5};

const char* texel_format_name(TexelFormat f);                    // "rgba16f", ...
std::optional<TexelFormat> parse_texel_format(const std::string& name);
std::uint32_t texel_bytes(TexelFormat f);                       // 8, 16, 4, 4
std::uint32_t vk_format(TexelFormat f);                         // 97, 109, 122, 123
const char* vk_format_name(TexelFormat f);                      // "VK_FORMAT_R16G16B16A16_SFLOAT", ...
std::uint32_t dxgi_format(TexelFormat f);                       // 10, 2, 26, 67
const char* dxgi_format_name(TexelFormat f);                    // "DXGI_FORMAT_R16G16B16A16_FLOAT", ...

// Largest finite values.
inline constexpr float ufloat11_max = 65024.0f;   // 2^15 (1 + 63/64)
inline constexpr float ufloat10_max = 64512.0f;   // 2^15 (1 + 31/32)
inline constexpr float rgb9e5_max = 65408.0f;     // 511/512 2^16
inline constexpr float half_max = 65504.0f;

// Unsigned small floats with 5 exponent bits and `mantissa_bits` (6 or 5) mantissa bits.
std::uint32_t encode_ufloat(float v, int mantissa_bits);
float decode_ufloat(std::uint32_t bits, int mantissa_bits);
std::uint32_t encode_rg11b10(float r, float g, float b);
std::array<float, 3> decode_rg11b10(std::uint32_t packed);
std::uint32_t encode_rgb9e5(float r, float g, float b);
std::array<float, 3> decode_rgb9e5(std::uint32_t packed);

// What encoding changed beyond rounding.
struct TexelEncodeInfo {
  std::uint64_t clamped_values = 0;   // finite channel values beyond the format's largest, set to it
  std::uint64_t negative_values = 0;  // negative values (or NaN for rgb9e5) of an unsigned format, set to 0
};

// Appends the texels of `face` (rows top to bottom, RGB plus alpha 1 where the format has alpha) in `f`.
void append_texels(std::vector<char>& out, const Image& face, TexelFormat f, TexelEncodeInfo* info = nullptr);
// Decodes `count` texels starting at `data` back to RGB floats.
std::vector<float> decode_texels(const char* data, std::size_t count, TexelFormat f);

// Checks a mip chain for a container: at least one level, level 0 of size >= 1, level i of size
// max(1, size0 >> i), at most 32 levels. Errors start with `what` ("ktx2", "dds").
Result<bool> check_cube_chain(const std::vector<CubeMap>& levels, const std::string& what);

}  // namespace shadelab
