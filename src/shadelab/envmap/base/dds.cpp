#include "shadelab/envmap/base/dds.h"

#include <array>
#include <cstdint>
#include <cstring>

#include "shadelab/image/image_io.h"

namespace shadelab {

namespace {

// DDS header enumerants (ddraw.h / dds.h of the DirectX SDK documentation).
constexpr std::uint32_t ddsd_caps = 0x1, ddsd_height = 0x2, ddsd_width = 0x4, ddsd_pitch = 0x8,
                        ddsd_pixelformat = 0x1000, ddsd_mipmapcount = 0x20000;
constexpr std::uint32_t ddpf_fourcc = 0x4;
constexpr std::uint32_t ddscaps_complex = 0x8, ddscaps_texture = 0x1000, ddscaps_mipmap = 0x400000;
constexpr std::uint32_t ddscaps2_cubemap_all_faces = 0x200 | 0x400 | 0x800 | 0x1000 | 0x2000 | 0x4000 | 0x8000;
constexpr std::uint32_t d3d10_resource_dimension_texture2d = 3;
constexpr std::uint32_t dds_resource_misc_texturecube = 0x4;

std::uint32_t fourcc(const char (&s)[5]) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(s[0])) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(s[1])) << 8) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(s[2])) << 16) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(s[3])) << 24);
}

}  // namespace

Result<std::vector<char>> encode_dds_cubemap(const std::vector<CubeMap>& levels, TexelFormat format, TexelEncodeInfo* info) {
  if (auto ok = check_cube_chain(levels, "dds"); !ok) return ok.error();
  const auto size = static_cast<std::uint32_t>(levels[0].size);
  // The 148 header bytes as 37 little-endian words: magic, DDS_HEADER (31), DDS_HEADER_DXT10 (5).
  std::array<std::uint32_t, 37> h{};
  h[0] = fourcc("DDS ");
  h[1] = 124;  // dwSize
  h[2] = ddsd_caps | ddsd_height | ddsd_width | ddsd_pitch | ddsd_pixelformat | ddsd_mipmapcount;
  h[3] = size;                        // dwHeight
  h[4] = size;                        // dwWidth
  h[5] = size * texel_bytes(format);  // dwPitchOrLinearSize: bytes of one row of level 0
  h[6] = 0;                           // dwDepth
  h[7] = static_cast<std::uint32_t>(levels.size());  // dwMipMapCount; h[8..18] dwReserved1
  h[19] = 32;                         // DDS_PIXELFORMAT: dwSize
  h[20] = ddpf_fourcc;
  h[21] = fourcc("DX10");             // h[22..26]: RGB bit count and masks, unused with a fourCC
  h[27] = ddscaps_complex | ddscaps_texture | ddscaps_mipmap;
  h[28] = ddscaps2_cubemap_all_faces;  // h[29..31]: dwCaps3, dwCaps4, dwReserved2
  h[32] = dxgi_format(format);         // DDS_HEADER_DXT10
  h[33] = d3d10_resource_dimension_texture2d;
  h[34] = dds_resource_misc_texturecube;
  h[35] = 1;  // arraySize: one cube (six faces)
  h[36] = 0;  // miscFlags2: DDS_ALPHA_MODE_UNKNOWN
  std::vector<char> out(sizeof(h));
  std::memcpy(out.data(), h.data(), sizeof(h));  // little-endian machines, as the format
  TexelEncodeInfo local;
  for (std::size_t f = 0; f < 6; ++f) {
    for (const CubeMap& level : levels) append_texels(out, level.faces[f], format, &local);
  }
  if (info != nullptr) *info = local;
  return out;
}

Result<bool> write_dds_cubemap(const std::vector<CubeMap>& levels, const std::filesystem::path& path, TexelFormat format,
                               TexelEncodeInfo* info) {
  auto bytes = encode_dds_cubemap(levels, format, info);
  if (!bytes) return make_error(path.string() + ": " + bytes.error().message);
  return write_file_atomically(path, *bytes);
}

}  // namespace shadelab
