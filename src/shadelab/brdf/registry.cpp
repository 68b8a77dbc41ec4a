#include "shadelab/brdf/registry.h"

#include "shadelab/core/text.h"

namespace shadelab {

std::span<const ModelInfo> brdf_models() {
  static const std::vector<ModelInfo> models = {
      lambert_model(),
      phong_model(),
      phong_modified_model(),
      blinn_phong_model(),
      blinn_phong_modified_model(),
      cook_torrance_model(),
      minimalist_cook_torrance_model(),
      ward_model(),
      ward_anisotropic_model(),
      lafortune_model(),
      wrapped_diffuse_model(),
      ggx_model(),
      burley_model(),
      filament_model(),
      gltf_model(),
      layered_model(),
      principled_v1_model(),
      openpbr_model(),
      measured_model(),
  };
  return models;
}

const ModelInfo* find_brdf_model(std::string_view name) {
  for (const auto& m : brdf_models()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

bool needs_input_file(const ModelInfo& info) {
  for (const auto& spec : info.params) {
    if (is_required(spec)) return true;
  }
  return false;
}

std::string split_sum_model_names() {
  std::string list;
  for (const auto& m : brdf_models()) {
    if (m.split_sum_sweep) list += (list.empty() ? "" : ", ") + m.name;
  }
  return list;
}

Result<BrdfPtr> make_brdf(std::string_view name, const ParamAssignments& params) {
  const ModelInfo* info = find_brdf_model(name);
  if (info == nullptr) {
    std::string list;
    for (const auto& m : brdf_models()) list += (list.empty() ? "" : ", ") + m.name;
    return make_error("unknown BRDF model '" + printable(name) + "' (models: " + list + ")");
  }
  auto values = parse_params(info->name, info->params, params);
  if (!values) return values.error();
  for (const auto& spec : info->params) {
    if (is_required(spec) && !values->is_set(spec.name)) {
      return make_error("brdf " + info->name + ": parameter '" + spec.name + "' is required (" + spec.description + ")");
    }
  }
  return info->create(*values);
}

// Upper limits: reflectances beyond 1 are allowed up to 1e3 so unnormalized forms can be explored; the
// energy check reports them. Exponents up to 1e6 stay finite in double precision.
ParamSpec kd_param(std::string default_value) {
  return {"kd", ParamKind::color, std::move(default_value), 0.0, 1e3, {}, "diffuse reflectance (albedo)", 0, {}};
}
ParamSpec ks_param(std::string default_value) {
  return {"ks", ParamKind::color, std::move(default_value), 0.0, 1e3, {}, "specular reflectance", 0, {}};
}
ParamSpec exponent_param(std::string name, std::string default_value) {
  return {std::move(name), ParamKind::scalar, std::move(default_value), 0.0, 1e6, {}, "specular exponent", 0, {}};
}

}  // namespace shadelab
