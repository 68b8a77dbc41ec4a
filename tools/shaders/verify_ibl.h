// shadelab shader verify --ibl: the exported environment lighting (export.h, ExportOptions::ibl) run on real
// drivers over the exact files `shadelab bake ibl` wrote, compared pixel by pixel with the C++ game renderer's
// image of the same view shaded with the same files (docs/shaders.md, "Environment lighting").
//
// The view: a unit sphere of the model at the origin, seen from (0, 0, 3) with a 45-degree vertical field of
// view, `size` x `size` pixels, one ray through each pixel's centre (render --mode game --spp 1), no punctual
// light: each pixel is SH9 diffuse plus the split sum (lookup lobes, the renderer's default). The pixels
// compared are those whose ray hits the sphere at N.V >= 0.05: at the silhouette whether a ray hits is the
// ray tracer's float arithmetic, not shading. The shader gets each pixel's normal and view direction (rounded
// to float); the error measure is verify.h's (relative, absolute below 1e-3 in the map's radiance units).
//
// Textures without filtering: the shader reads texels with texelFetch (HLSL Load) and interpolates in the
// kernels, seamlessly across faces, as the C++ does, so no sampler state enters the comparison. On Vulkan the
// fetches read one storage buffer (SHADELAB_IBL_FETCHES defined before the file: the exported texture fetches
// are skipped); in WebGL 2 they are the exported ones, over RGBA32F textures.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/envmap/base/ktx2_reader.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/envmap/specular/split_sum_lobes.h"
#include "verify.h"
#include "export.h"

namespace shadelab::shaders {

inline constexpr double kIblTolerance = 1e-3;
inline constexpr double kIblMinCosine = 0.05;  // pixels at N.V below it are left out (the silhouette)

// The files of one `bake ibl` run, read back: the KTX 2 specular chain, its mip mapping (manifest.json and the
// KTX 2 key shadelab.mip_mapping), the DFG table, the lobe table and the SH9 radiance coefficients.
struct IblBake {
  Ktx2Texture chain;
  int mapping = 0;  // kernels/game_ibl.sl GGX_MIP_MAPPING_*
  Ktx2Texture dfg;
  int lobe_size = 0;
  std::vector<SplitSumLobes> lobes;  // row-major, lobe_size^2
  Sh9 sh;                            // radiance_coefficients of sh9.json
};

// Reads dir/manifest.json and the files it names; errors name the file and field (a DDS bake: "--container
// ktx2" is needed, DDS holds no mip mapping).
Result<IblBake> read_ibl_bake(const std::filesystem::path& dir);

// The storage buffer of the Vulkan fetches (4 floats a texel: the chain level by level and face by face, then
// the DFG table, then the lobe table) and the GLSL or HLSL prelude that defines the fetches over it.
struct IblBuffer {
  std::vector<float> texels;
  std::string prelude;
};
IblBuffer ibl_storage_buffer(const IblBake& bake, bool hlsl);

// verify_shader's IBL path (options.ibl_dir set): `code` is the exported file (ex.text) or the user's.
Result<VerifyReport> verify_ibl(const VerifyOptions& options, const ShaderExport& ex, const std::string& code,
                                const std::string& display);

}  // namespace shadelab::shaders
