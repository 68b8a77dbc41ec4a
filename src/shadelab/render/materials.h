// shadelab materials at render time: one BRDF per material, built once, and per-hit BRDFs for materials
// whose parameters come from textures (kd, ks or f0, gloss -> n by the zoo's logarithmic encoding), with the
// material's texture tiling. Shared by the path tracer and the game renderer, so both shade with the same
// BRDF code.
#pragma once

#include <atomic>
#include <optional>
#include <vector>

#include "shadelab/core/frame.h"
#include "shadelab/render/accel.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

class MaterialSet {
 public:
  // Builds every material's model and validates that its textures drive parameters the model has.
  Result<bool> prepare(const Scene& scene);

  // The BRDF at a hit: the material's own, or for a textured material one built for this uv and kept in
  // `holder`. nullptr for material -1 (sphere lights).
  const Brdf* brdf(int material, Vec2 uv, BrdfPtr& holder) const;

 private:
  struct Runtime {
    const ModelInfo* info = nullptr;
    std::optional<ParamValues> base;
    std::shared_ptr<const Brdf> brdf;
    bool textured = false;
    std::string ks_param = "ks";  // the parameter the specular texture drives (ModelInfo::ks_texture_param)
  };
  const Scene* m_scene = nullptr;
  std::vector<Runtime> m_runtime;
  std::uint64_t m_id = next_id();  // for the per-thread parameter cache
  static std::uint64_t next_id() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
  }
};

// The shading frame at a hit, facing the viewer (surfaces are two-sided): the geometric normal ng turned
// toward wo, the shading normal (interpolated, or from the material's normal map, kept only when it faces
// the viewer), and the tangent along the shape's dpdu (for anisotropic models).
struct ShadingFrame {
  Frame frame;
  Vec3 ng;
};
ShadingFrame shading_frame(const Scene& scene, const Hit& hit, const Vec3& wo_world);

}  // namespace shadelab
