// shadelab layering error: how far a shipped material's layering shortcut is from the true layered BSDF
// (issue 37, section 2: "the measurement no anchor has").
//
// A glTF clearcoat (KHR_materials_clearcoat) darkens the layers below by the mirror Fresnel at N.V and adds the
// coat's GGX lobe: f = (1 - c Fc(N.V)) f_base + c Fc(N.V) D V. The truth for the same description is a rough
// dielectric coat (ior 1.5, alpha = clearcoat_roughness^2) over the same base with light scattering between them,
// the `layered` model's random walk, mixed by the coat's weight: f_true = (1 - c) f_base + c f_layered (coverage,
// as OpenPBR defines a coat's weight). Beside the specification's form it measures the albedo-scaled form that
// engines are asked to use instead (glTF-Sample-Viewer #546): f = (1 - c E_c(N.V)) f_base + c f_c, f_c = D V
// F_schlick(0.04, V.H) the coat's lobe and E_c its directional albedo (by quadrature).
//
// The base must be one the ground truth holds exactly: metallic = 1 (a conductor with Schlick's F, f0 = base_color:
// `layered` base=conductor with F82 tint 1) or metallic = 0 with specular = 0 (Lambert of albedo base_color); no
// anisotropy and no sheen. Anything else is an Error naming the parameter.
//
// Measured per configuration:
// - directional albedo over theta_o of the truth (its sampler's mean, with its standard error), of the glTF form
//   and of the albedo-scaled form (quadrature), and their differences;
// - the lobe's RMSE: for each theta_o, sqrt(mean over wi of ((f_form - f_true) cos theta_i)^2) with wi on a grid
//   uniform in (cos theta_i, phi_i) (16 x 32 cell centres), and the truth's own noise over the same grid (the
//   RMS of its per-eval standard error times cos), which the RMSE includes.
#pragma once

#include <string>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/error.h"

namespace shadelab {

struct LayeringErrorOptions {
  std::vector<double> thetas_deg = {0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0};
  int walks = 64;                  // walk_samples of each truth eval (the lobe grid)
  int albedo_samples = 100000;     // samples of the truth's albedo per theta
  std::uint64_t seed = 1;
};

struct LayeringAlbedoRow {
  double theta_deg = 0.0;
  double truth = 0.0;           // green channel (the grey channel for white materials)
  double truth_error = 0.0;     // its standard error
  double model = 0.0;           // the glTF form
  double albedo_scaled = 0.0;   // the albedo-scaled form
  // The truth's own white furnace: `layered` with the same coat over a white base (base_color 1). Its coat
  // scatters multiply on its microsurface (coat_scattering = multiple, Heitz et al. 2016), so over Lambert this
  // is 1 within noise; over a metal it is the base's own single-scattering loss. (With a single-scattering coat it
  // was 0.93 at coat roughness 0.3, 0.65 at 0.6, 0.32 at 1.) Where it is well below 1, the truth is not one a
  // conserving shortcut can meet, and the difference says so.
  double truth_furnace = 0.0;
};

struct LayeringLobeRow {
  double theta_deg = 0.0;
  double truth_rms = 0.0;       // RMS of f_true cos over the grid (the scale of the lobe)
  double truth_noise_rms = 0.0; // RMS of the truth's standard error times cos
  double model_rmse = 0.0;
  double albedo_scaled_rmse = 0.0;
};

struct LayeringErrorReport {
  std::string model;
  ParamAssignments params;       // the model's parameters as given
  ParamAssignments truth_params; // the `layered` model's
  std::vector<LayeringAlbedoRow> albedo;
  std::vector<LayeringLobeRow> lobe;
  double max_albedo_difference = 0.0;          // max over theta of |model - truth|
  double max_albedo_scaled_difference = 0.0;   // the same for the albedo-scaled form
};

Result<LayeringErrorReport> layering_error(const std::string& model, const ParamAssignments& params,
                                           const LayeringErrorOptions& options = {});

}  // namespace shadelab
