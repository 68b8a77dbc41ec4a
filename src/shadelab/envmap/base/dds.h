// shadelab DDS cube maps with mip chains and the DX10 header extension (Microsoft, "DDS programming
// guide": DDS_HEADER, DDS_PIXELFORMAT, DDS_HEADER_DXT10): the container Direct3D engines and tools load
// (DirectXTex, Unreal, Unity, NVIDIA Texture Tools).
//
// Layout written (little-endian): "DDS "; DDS_HEADER (124 bytes) with flags CAPS | HEIGHT | WIDTH | PITCH |
// PIXELFORMAT | MIPMAPCOUNT, the face size, pitch = size x texel bytes, depth 0, the mip count, a
// DDS_PIXELFORMAT with fourCC "DX10", caps COMPLEX | TEXTURE | MIPMAP, caps2 CUBEMAP and all six faces;
// DDS_HEADER_DXT10 with the DXGI format (texel_format.h), TEXTURE2D (3), misc flag TEXTURECUBE (4), array size
// 1 (one cube), misc flags 2 alpha mode 0 (unknown). Then, as Direct3D lays out a cube texture, face by face
// (+X, -X, +Y, -Y, +Z, -Z) and within each face every mip level, level 0 first, rows top to bottom, no
// padding. Direct3D's cube faces have the same texel layout as OpenGL's (cubemap.h): the same bytes load in
// both.
#pragma once

#include <filesystem>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/base/texel_format.h"

namespace shadelab {

Result<std::vector<char>> encode_dds_cubemap(const std::vector<CubeMap>& levels, TexelFormat format,
                                             TexelEncodeInfo* info = nullptr);
Result<bool> write_dds_cubemap(const std::vector<CubeMap>& levels, const std::filesystem::path& path, TexelFormat format,
                               TexelEncodeInfo* info = nullptr);

}  // namespace shadelab
