// Pieces the bake commands share (cmd_bake.cpp, cmd_bake_dfg.cpp, cmd_bake_ibl.cpp): the GGX specular chain
// and its mip-mapping record, the SH9 JSON, the DFG table's image, conventions and KTX 2 key/value data.
// Defined in the command file that owns each piece; `bake ibl` calls the same code as the single bakes.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/base/ktx2.h"
#include "shadelab/envmap/diffuse/irradiance.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/envmap/specular/prefilter_ggx.h"
#include "shadelab/image/image.h"

namespace shadelab::cli {

// cmd_bake.cpp ------------------------------------------------------------------------------------------

// The face order and orientation every cube container holds (the KTX 2 key shadelab.cube_convention).
extern const char* const cube_convention_text;

// The key/value data of a KTX 2 cube output (ktx2.h adds KTXorientation and KTXwriter).
KtxMetadata ktx2_metadata(const std::string& content, const nlohmann::json& mip_mapping = nullptr);

// Reads INPUT (EXR, HDR, PNG), warning about repaired NaN/Inf values.
Image read_environment(const std::string& input);
bool is_latlong_image(const Image& img);
// The image (read from `input`) as a cube: a lat-long at face size width/4 (at most 512), a cross as it is.
CubeMap environment_cube(const Image& img, const std::string& input);
// The image as a cube of face size `size`: a lat-long is resampled to it (area filtered), a cross of that
// face size is returned as it is (bit for bit), another cross is resampled.
CubeMap environment_cube_at(const Image& img, const std::string& input, int size);

// The GGX mip chain of `env` (level 0 = env) and the record of its roughness-to-mip mapping that goes into a
// KTX 2 file's shadelab.mip_mapping, `bake specular --json` and the `bake ibl` manifest.
GgxPrefilteredCube bake_ggx_chain(const CubeMap& env, int levels, GgxRoughnessMapping mapping, GgxFilterMethod method, int samples,
                                  bool progress);
// --method NAME of the GGX bakes: sum (the default) or sampled; --samples given without --method means sampled
// (as before --method existed), with --method sum it is refused. UsageError naming the option otherwise.
GgxFilterMethod ggx_method_option(const std::string& name, bool method_given, bool samples_given);
nlohmann::json ggx_mip_mapping_json(const GgxPrefilteredCube& chain);

// The JSON `bake sh` prints (and writes with --out) for SH9 radiance coefficients `sh`.
nlohmann::json sh9_json(const Sh9& sh, RadianceUnits units, ShWindow window, const std::string& window_name,
                        const nlohmann::json& lights, const std::string& light_normalization);

// cmd_bake_dfg.cpp --------------------------------------------------------------------------------------

// The table as an image: R = A, G = B, B = A + B (multiscatter) or 0; row j = roughness (j + 0.5)/size.
Image dfg_image(const DfgTable& t);
// Its conventions: x, y, orientation, channels, specular (the keys of `bake dfg --json`).
nlohmann::json dfg_conventions_json(bool multiscatter);
// KTX 2 key/value data of a DFG table (content, axes, channels).
KtxMetadata dfg_ktx2_metadata(bool multiscatter);
// What the `error` of a table by the fixed rule (bake_dfg's default) is.
inline constexpr const char* dfg_error_meaning =
    "largest difference to a 1.5x finer quadrature rule over the first two and last rows and columns and every "
    "8th row and column (the rule is within 1e-6 of the adaptive quadrature, tests)";

}  // namespace shadelab::cli
