#include "shadelab/render/materials.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "shadelab/core/text.h"

namespace shadelab {

namespace {

const ParamSpec* find_spec(const ModelInfo& info, std::string_view name) {
  for (const ParamSpec& s : info.params) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

// A parameter texture drives a colour or scalar parameter of the model, with a channel that fits it, from a
// texture of the scene (scene.h, ParamTexture); scene_json checks the same with the field's pointer.
Result<bool> check_param_texture(const ModelInfo& info, const Scene& scene, const ParamTexture& p) {
  if (p.texture < 0 || static_cast<std::size_t>(p.texture) >= scene.textures.size()) {
    return make_error("texture " + std::to_string(p.texture) + " for parameter '" + printable(p.param) + "' does not exist");
  }
  const ParamSpec* spec = find_spec(info, p.param);
  if (spec == nullptr) return make_error("model '" + info.name + "' has no parameter '" + printable(p.param) + "' for its texture");
  if (p.use == ParamTexture::Use::anisotropy) {
    if (p.param != "anisotropy_strength" || find_spec(info, "anisotropy_rotation") == nullptr) {
      return make_error("an anisotropy texture drives anisotropy_strength and anisotropy_rotation");
    }
    return true;
  }
  if (spec->kind == ParamKind::color ? p.channel != -1 : !(spec->kind == ParamKind::scalar && p.channel >= 0 && p.channel <= 2)) {
    return make_error("parameter '" + p.param + "' cannot take a texture with channel " + std::to_string(p.channel));
  }
  return true;
}

}  // namespace

Result<bool> MaterialSet::prepare(const Scene& scene) {
  m_scene = &scene;
  m_runtime.clear();
  for (const Material& m : scene.materials) {
    Runtime rt;
    const std::string where = "material '" + printable(m.name) + "'";  // the name as the scene file spells it
    if (!m.model.empty()) {
      rt.info = find_brdf_model(m.model);
      if (rt.info == nullptr) return make_error(where + ": unknown model '" + printable(m.model) + "'");
      auto values = parse_params(rt.info->name, rt.info->params, m.params);
      if (!values) return make_error(where + ": " + values.error().message);
      rt.base = std::move(values).value();
      if (m.brdf) {
        rt.brdf = m.brdf;
      } else {
        auto b = rt.info->create(*rt.base);
        if (!b) return make_error(where + ": " + b.error().message);
        rt.brdf = std::shared_ptr<const Brdf>(std::move(b).value());
      }
      rt.textured = m.textured();
      auto has = [&](const char* name) {
        return std::any_of(rt.info->params.begin(), rt.info->params.end(), [&](const ParamSpec& s) { return s.name == name; });
      };
      if (m.kd_texture >= 0 && !has("kd")) return make_error(where + ": model '" + m.model + "' has no parameter kd for its kd texture");
      if (m.gloss_texture >= 0 && !has("n")) return make_error(where + ": model '" + m.model + "' has no exponent n for its gloss texture");
      if (rt.info->ks_texture_param) rt.ks_param = rt.info->ks_texture_param(*rt.base);
      if (m.ks_texture >= 0 && !has(rt.ks_param.c_str())) return make_error(where + ": model '" + m.model + "' has no parameter " + rt.ks_param + " for its ks texture");
      if (m.base_color_texture >= 0 && !has("base_color")) return make_error(where + ": model '" + m.model + "' has no parameter base_color for its base_color texture");
      if (m.metallic_roughness_texture >= 0 && !(has("metallic") && has("perceptual_roughness"))) return make_error(where + ": model '" + m.model + "' has no parameters metallic and perceptual_roughness for its metallic_roughness texture");
      for (const ParamTexture& p : m.param_textures) {
        if (auto ok = check_param_texture(*rt.info, scene, p); !ok) return make_error(where + ": " + ok.error().message);
      }
    } else if (m.brdf) {
      rt.brdf = m.brdf;
    }
    m_runtime.push_back(std::move(rt));
  }
  return true;
}

const Brdf* MaterialSet::brdf(int material, Vec2 uv, BrdfPtr& holder) const {
  if (material < 0) return nullptr;
  const Runtime& rt = m_runtime[static_cast<std::size_t>(material)];
  if (!rt.textured || rt.info == nullptr) return rt.brdf.get();
  const Material& m = m_scene->materials[static_cast<std::size_t>(material)];
  uv = {uv.x * m.uv_scale.x, uv.y * m.uv_scale.y};  // texture tiling
  // A per-thread working copy of the material's parameters, so a textured hit only overwrites the numbers
  // the textures drive instead of copying the whole parameter set.
  thread_local std::vector<std::optional<ParamValues>> scratch;
  thread_local std::uint64_t scratch_owner = 0;
  if (scratch_owner != m_id) {  // another material set (scene) used this thread before
    scratch.clear();
    scratch_owner = m_id;
  }
  if (scratch.size() <= static_cast<std::size_t>(material)) scratch.resize(static_cast<std::size_t>(material) + 1);
  auto& slot = scratch[static_cast<std::size_t>(material)];
  if (!slot) slot = *rt.base;
  ParamValues& v = *slot;
  if (m.kd_texture >= 0) {
    const Rgb c = sample_texture(m_scene->textures[static_cast<std::size_t>(m.kd_texture)], uv);
    v.set_numbers("kd", {c.r, c.g, c.b});
  }
  if (m.ks_texture >= 0) {
    const Rgb c = sample_texture(m_scene->textures[static_cast<std::size_t>(m.ks_texture)], uv);
    v.set_numbers(rt.ks_param, {c.r, c.g, c.b});
  }
  if (m.gloss_texture >= 0) {
    const double g = sample_texture(m_scene->textures[static_cast<std::size_t>(m.gloss_texture)], uv).r;
    v.set_numbers("n", {m.gloss_encoding.exponent_from_gloss(g)});  // the zoo's logarithmic gloss encoding
  }
  // glTF metallic-roughness: the textures multiply the material's factors (glTF 2.0, section 3.9.2).
  if (m.base_color_texture >= 0) {
    const Rgb c = sample_texture(m_scene->textures[static_cast<std::size_t>(m.base_color_texture)], uv);
    const Rgb f = rt.base->color("base_color");
    v.set_numbers("base_color", {f.r * c.r, f.g * c.g, f.b * c.b});
  }
  if (m.metallic_roughness_texture >= 0) {
    const Rgb t = sample_texture(m_scene->textures[static_cast<std::size_t>(m.metallic_roughness_texture)], uv);
    v.set_numbers("metallic", {std::clamp(rt.base->scalar("metallic") * t.b, 0.0, 1.0)});
    // perceptual_roughness' range starts at 0.01 (filament.cpp): a black texel is the smoothest it allows.
    v.set_numbers("perceptual_roughness", {std::clamp(rt.base->scalar("perceptual_roughness") * t.g, 0.01, 1.0)});
  }
  // Parameter textures (gltf, principled-v1, layered, glTF files): factor x texel, clamped to the range.
  for (const ParamTexture& p : m.param_textures) {
    const ParamSpec* spec = find_spec(*rt.info, p.param);
    const Rgb t = sample_texture(m_scene->textures[static_cast<std::size_t>(p.texture)], p.transform.apply(uv));
    if (p.use == ParamTexture::Use::anisotropy) {
      // KHR_materials_anisotropy: strength x blue; the direction (2 red - 1, 2 green - 1) in the tangent frame turns
      // the factor's rotation by its angle (a texel of (1, 0.5) leaves it; (0.5, 0.5) has no direction: kept).
      v.set_numbers("anisotropy_strength", {std::clamp(rt.base->scalar("anisotropy_strength") * t.b, spec->min, spec->max)});
      const double x = 2.0 * t.r - 1.0;
      const double y = 2.0 * t.g - 1.0;
      const ParamSpec* rotation = find_spec(*rt.info, "anisotropy_rotation");
      const double angle = x == 0.0 && y == 0.0 ? 0.0 : std::atan2(y, x);
      v.set_numbers("anisotropy_rotation", {std::clamp(rt.base->scalar("anisotropy_rotation") + angle, rotation->min, rotation->max)});
    } else if (p.channel < 0) {
      const Rgb f = rt.base->color(p.param);
      v.set_numbers(p.param, {std::clamp(f.r * t.r, spec->min, spec->max), std::clamp(f.g * t.g, spec->min, spec->max),
                              std::clamp(f.b * t.b, spec->min, spec->max)});
    } else {
      v.set_numbers(p.param, {std::clamp(rt.base->scalar(p.param) * t[p.channel], spec->min, spec->max)});
    }
  }
  auto b = rt.info->create(v);
  if (!b) return rt.brdf.get();  // validated at load; a texture cannot make it fail
  holder = std::move(b).value();
  return holder.get();
}

ShadingFrame shading_frame(const Scene& scene, const Hit& hit, const Vec3& wo_world) {
  Vec3 ng = hit.geometric_normal;
  Vec3 ns = hit.shading_normal;
  if (dot(ng, wo_world) < 0.0) {
    ng = -ng;
    ns = -ns;
  }
  if (dot(ns, wo_world) <= 0.0) ns = ng;  // interpolated normal facing away: fall back
  const Material* material = hit.material >= 0 ? &scene.materials[static_cast<std::size_t>(hit.material)] : nullptr;
  if (material != nullptr && material->normal_texture >= 0) {
    const Vec2 uv{hit.uv.x * material->uv_scale.x, hit.uv.y * material->uv_scale.y};
    const Rgb t = sample_texture(scene.textures[static_cast<std::size_t>(material->normal_texture)], uv);
    Vec3 tangent = hit.dpdu - ns * dot(hit.dpdu, ns);
    tangent = length(tangent) > 1e-12 ? normalize(tangent) : Frame::from_normal(ns).s;
    const Vec3 bitangent = cross(ns, tangent);
    const Vec3 nt = normalize(Vec3{2.0 * t.r - 1.0, 2.0 * t.g - 1.0, 2.0 * t.b - 1.0});
    const Vec3 mapped = normalize(tangent * nt.x + bitangent * nt.y + ns * nt.z);
    if (dot(mapped, wo_world) > 0.0) ns = mapped;
  }
  Vec3 tangent = hit.dpdu - ns * dot(hit.dpdu, ns);
  Frame frame;
  if (length(tangent) > 1e-9) {
    frame.n = ns;
    frame.s = normalize(tangent);
    frame.t = cross(frame.n, frame.s);
  } else {
    frame = Frame::from_normal(ns);
  }
  return {frame, ng};
}

}  // namespace shadelab
