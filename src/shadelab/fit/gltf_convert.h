// shadelab glTF material conversion: a KHR_materials_pbrSpecularGlossiness material (brdf/spec_gloss.h) as a
// metallic-roughness material with KHR_materials_specular and KHR_materials_ior (the gltf model, brdf/gltf.h), its
// factors chosen to minimise the difference of the directional albedo.
//
// The start is the analytic conversion of Khronos glTF PR #1719 (github.com/KhronosGroup/glTF/pull/1719, the
// comment gltf-transform's metalRough() cites and implements): baseColor = diffuse, metallic = 0, roughness =
// 1 - glossiness, ior = 1000 ("infinite": f0 = ((ior - 1)/(ior + 1))^2 specularColor ~ 0.996 specularColor),
// specularFactor = 1, specularColorFactor = specular. It matches spec-gloss at normal incidence of V.H but weighs
// the diffuse by 1 - max3(F(V.H)) where spec-gloss weighs it by the constant 1 - max3(specular) (spec_gloss.h).
//
// The fit: BOBYQA (NLopt, as fit/fit.h) over base_color (3), metallic, roughness, specular and specular_color (3)
// with ior held at 1000, in their glTF ranges (specular_color up to 1 / 0.996, so that f0 reaches 1), minimising
// the ROOT MEAN SQUARE over theta_o in the grid and over the three channels of rho_gltf(theta_o) - rho_sg(theta_o),
// rho the directional albedo (analysis/albedo.h; quadrature to 1e-8 relative). It runs from two starts, the PR's
// and the metal one (metallic = 1, baseColor = specular, roughness = 1 - glossiness: exact when diffuse = 0), and
// keeps the better. The report is the MAXIMUM over theta_o and channels of |rho_gltf - rho_sg|, for the start and
// for the result; the result is never worse than the start in the objective.
// Deterministic: the same factors give the same result.
#pragma once

#include <cstdint>
#include <vector>

#include "shadelab/brdf/gltf.h"
#include "shadelab/brdf/spec_gloss.h"

namespace shadelab {

struct MetalRoughFactors {
  Rgb base_color{1.0, 1.0, 1.0};
  double metallic = 1.0;
  double roughness = 1.0;
  double ior = 1.5;
  double specular = 1.0;
  Rgb specular_color{1.0, 1.0, 1.0};
};

// The gltf model's parameters for the factors (no anisotropy, sheen or clearcoat).
Gltf::Params gltf_params(const MetalRoughFactors& m);

// PR #1719's conversion (above).
MetalRoughFactors pr1719_conversion(const SpecGloss::Params& sg);

struct AlbedoDifference {
  Rgb max_abs;        // per channel, max over theta_o of |rho_gltf - rho_sg|
  double max = 0.0;   // the largest channel of max_abs
  double rms = 0.0;   // over theta_o and channels
  double worst_theta_deg = 0.0;
};

struct GltfConvertOptions {
  std::vector<double> theta_deg = {0, 10, 20, 30, 40, 50, 60, 70, 80};
  int max_evaluations = 300;  // BOBYQA's objective evaluations (0: the better start, no fit)
};

// The difference of the directional albedos on the grid.
AlbedoDifference albedo_difference(const SpecGloss::Params& sg, const MetalRoughFactors& m,
                                   const GltfConvertOptions& options = {});

struct GltfMaterialConversion {
  MetalRoughFactors start;  // PR #1719's
  AlbedoDifference start_difference;
  MetalRoughFactors result;
  AlbedoDifference difference;
  std::int64_t evaluations = 0;  // objective evaluations, both starts
};

GltfMaterialConversion convert_spec_gloss(const SpecGloss::Params& sg, const GltfConvertOptions& options = {});

}  // namespace shadelab
