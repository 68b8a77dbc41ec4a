// shadelab BRDF registry: every model by the name a user types, with its parameters, defaults and ranges.
// The registry name of a model is the name of its file (phong.h holds phong and phong-modified).
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "shadelab/brdf/brdf.h"
#include "shadelab/brdf/params.h"
#include "shadelab/core/error.h"

namespace shadelab {

// How a model with a split-sum specular ambient (Brdf::split_sum_inputs) is swept by the split sum's error map
// (render/ibl_error.h): the parameter each row sets (its perceptual roughness), and the one assignment that
// leaves its specular lobe alone (no diffuse lobe beside it).
struct SplitSumSweep {
  std::string roughness_param;
  std::string specular_only_param;
  std::string specular_only_value;
};

struct ModelInfo {
  std::string name;
  std::string summary;  // one line: the formula
  std::string source;   // where the formula comes from
  std::vector<ParamSpec> params;
  std::function<Result<BrdfPtr>(const ParamValues&)> create;
  std::optional<SplitSumSweep> split_sum_sweep;  // set by the models whose BRDFs answer split_sum_inputs()
  // The parameter a scene's specular (ks) texture drives for these parameter values; unset: "ks".
  std::function<std::string(const ParamValues&)> ks_texture_param;
  // Set by a model without a kernel binding that is not stochastic: why it has no shader (the exporter's refusal
  // reads "model 'NAME' has no shader: " and this), e.g. openpbr's tables.
  std::string no_shader;
};

// All models, in a fixed order.
std::span<const ModelInfo> brdf_models();
const ModelInfo* find_brdf_model(std::string_view name);
// True for a model that cannot be built from its defaults: one of its parameters names a data file and has no
// default (measured). The loops over every model (tests, benchmarks, the explorer) give it a file or skip it.
bool needs_input_file(const ModelInfo& info);
// The names of the models with a split_sum_sweep, comma-separated in registry order ("ggx, filament"): for
// messages that list them.
std::string split_sum_model_names();

using ParamAssignments = std::vector<std::pair<std::string, std::string>>;
// Looks the model up, validates the parameters and builds it. Errors name the model and parameter.
Result<BrdfPtr> make_brdf(std::string_view name, const ParamAssignments& params = {});

// Parameter declarations shared by several models.
ParamSpec kd_param(std::string default_value = "0.5");
ParamSpec ks_param(std::string default_value = "0.5");
ParamSpec exponent_param(std::string name = "n", std::string default_value = "50");

// Per-model registration (defined in each model's file).
ModelInfo lambert_model();
ModelInfo phong_model();
ModelInfo phong_modified_model();
ModelInfo blinn_phong_model();
ModelInfo blinn_phong_modified_model();
ModelInfo cook_torrance_model();
ModelInfo minimalist_cook_torrance_model();
ModelInfo ward_model();
ModelInfo ward_anisotropic_model();
ModelInfo lafortune_model();
ModelInfo wrapped_diffuse_model();
ModelInfo ggx_model();
ModelInfo burley_model();
ModelInfo filament_model();
ModelInfo gltf_model();
ModelInfo layered_model();
ModelInfo principled_v1_model();
ModelInfo openpbr_model();
ModelInfo measured_model();

}  // namespace shadelab
