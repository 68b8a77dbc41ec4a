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

#include <array>
#include <cstdint>
#include <vector>

#include "shadelab/brdf/gltf.h"
#include "shadelab/brdf/spec_gloss.h"

namespace shadelab {

// The factors of a metallic-roughness material with KHR_materials_specular and KHR_materials_ior: the gltf model's
// parameters (base_color, metallic, roughness, ior, specular, specular_color; no anisotropy, sheen or clearcoat).
using MetalRoughFactors = Gltf::Params;

// The gltf model's parameters for the factors (the identity since MetalRoughFactors is Gltf::Params; kept for callers).
inline Gltf::Params gltf_params(const MetalRoughFactors& m) { return m; }

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

// ---- The fast per-texel rule (textured materials; docs/conversions.md) ----
//
// Both directional albedos on the default grid theta_k = 0, 10, ..., 80 degrees are linear in three integrals:
//   E_k(alpha)  = integral D V cos(theta_i) d(wi)                 (GGX, height-correlated Smith V, F = 1)
//   E5_k(alpha) = integral (1 - V.H)^5 D V cos(theta_i) d(wi)     (the Schlick weight's share)
//   L5_k        = integral (1 - V.H)^5 / pi cos(theta_i) d(wi)    (the diffuse weight's Schlick share; no alpha)
// so that (spec_gloss.h; kernels/gltf.sl with max3(F) = max3(f0) (1 - w) + w, w = (1 - V.H)^5 shared by the channels)
//   rho_sg   = c_diff + specular (E - E5) + E5                       at alpha_sg = max((1 - glossiness)^2, 1e-4)
//   rho_gltf = (1 - metallic) [base (1 - s (max3(f0) (1 - L5) + L5)) + s (f0 (E - E5) + E5)]
//              + metallic [base (E - E5) + E5]                          at alpha = max(roughness^2, 1e-4),
//   s = specularFactor, f0 = min(((ior - 1)/(ior + 1))^2 specularColor, 1).
// E and E5 are tabulated per grid angle over roughness r_j = j / (nodes - 1) (alpha = max(r^2, 1e-4)) by a fixed
// product rule in GGX's warped half-vector domain (gltf_convert.cpp, ggx_energies: about 0.1 s for the whole table),
// read by Catmull-Rom in r with linearly extrapolated ghost nodes; L5 by the adaptive quadrature of analysis/albedo.h.
// Built once, at first use (thread-safe). The test checks the tables' albedos against adaptive quadrature of the two
// models themselves (SpecGloss, Gltf) between the nodes.
struct GltfAlbedoTables {
  static constexpr int angles = 9;  // theta_k = 10 k degrees
  int nodes = 0;
  std::vector<double> e, e5;  // [k * nodes + j]
  std::vector<double> l5;     // [k]
};
const GltfAlbedoTables& gltf_albedo_tables();

// E_k, E5_k at roughness r in [0, 1] (the tables' interpolant) and their derivatives in r.
struct GltfEnergies {
  std::array<double, GltfAlbedoTables::angles> e{}, e5{}, de{}, de5{};
};
GltfEnergies gltf_energies(double roughness);

using GridAlbedo = std::array<Rgb, GltfAlbedoTables::angles>;
// The directional albedos on the grid from the tables (formulas above).
GridAlbedo table_albedo(const SpecGloss::Params& sg);
GridAlbedo table_albedo(const MetalRoughFactors& m);
// max and RMS over the grid and channels of the tables' rho_gltf - rho_sg (worst_theta_deg as albedo_difference's).
AlbedoDifference table_albedo_difference(const SpecGloss::Params& sg, const MetalRoughFactors& m);

struct FastConversion {
  MetalRoughFactors result;
  int iterations = 0;  // Levenberg-Marquardt steps tried
};
// The rule: metallic 0, ior 1000, and base_color (3), roughness (within FastOptions::roughness_band of 1 - glossiness),
// specularFactor and f0 (3; specularColor = f0 / 0.996) by a projected Levenberg-Marquardt (Marquardt 1963: the
// normal equations damped by lambda diag(J^T J), lambda / 4 after a step that lowers the sum of squares, x 8 after
// one that does not) on the 27 residuals of the tables' rho_gltf - rho_sg (the exact fit's objective, least RMS, on
// the tables), the Jacobian analytic (max3(f0) by its first largest channel), from PR #1719's start, at most
// max_steps steps. Deterministic.
struct FastOptions {
  // The roughness stays within this of the source's 1 - glossiness. The albedo cannot see the lobe's width: left
  // free (1), the fit trades it for albedo and turns a glossy highlight (glossiness 0.9) into a mirror (roughness 0);
  // the exact fit moves it by 0.03 on the plastic (docs/conversions.md, "The fast rule").
  double roughness_band = 0.05;
  int max_steps = 60;
};
FastConversion convert_spec_gloss_fast(const SpecGloss::Params& sg, const FastOptions& options = {});

}  // namespace shadelab
