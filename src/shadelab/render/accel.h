// shadelab ray intersection with Embree 3 (Debian's libembree-dev): one device per process (Embree takes
// the thread count of the largest live device), one BVH per scene (high build quality).
//
// Shapes map to Embree's native primitives: spheres and sphere lights to RTC_GEOMETRY_TYPE_SPHERE_POINT,
// disks to RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT, quads to RTC_GEOMETRY_TYPE_QUAD, meshes to
// RTC_GEOMETRY_TYPE_TRIANGLE. Embree works in float; the hit is refined in double here (the sphere hit is
// projected back onto the sphere; the position is recomputed from the ray in double).
#pragma once

#include <embree3/rtcore.h>

#include <limits>
#include <memory>
#include <vector>

#include "shadelab/core/frame.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

enum class ShapeKind { sphere, quad, disk, mesh, sphere_light };

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit
  double t_max = std::numeric_limits<double>::infinity();
};

struct Hit {
  double t = 0.0;
  Vec3 position;
  Vec3 geometric_normal;  // unit, as the shape defines it (outward for spheres, u x v for quads)
  Vec3 shading_normal;    // unit; interpolated vertex normals for meshes, else the geometric normal
  Vec2 uv;                // texture coordinates (spheres: only when their material has a texture, else 0)
  Vec3 dpdu;              // tangent direction (for normal maps and anisotropic models), unit
  ShapeKind kind = ShapeKind::sphere;
  int index = 0;          // index into the scene's list for that kind (sphere lights: into Scene::lights)
  int primitive = 0;      // triangle index for meshes
  int material = -1;      // -1 for sphere lights (they carry their own radiance)
};

class Accelerator {
 public:
  explicit Accelerator(const Scene& scene);
  ~Accelerator();
  Accelerator(const Accelerator&) = delete;
  Accelerator& operator=(const Accelerator&) = delete;

  // Closest hit along the ray in (0, t_max), or nothing.
  bool intersect(const Ray& ray, Hit& hit) const;
  // Closest hits of up to 8 rays traced as one Embree packet (rtcIntersect8, for coherent camera rays):
  // found[i] tells whether hits[i] was filled, for i < count. Embree's packet traversal may differ from
  // intersect() in the last float bits, so a deterministic caller always forms the same packets.
  void intersect8(const Ray* rays, int count, Hit* hits, bool* found) const;
  // True when something blocks the ray in (0, t_max).
  bool occluded(const Ray& ray) const;

  // The Embree scene, for benchmarks that measure Embree alone on the same geometry.
  RTCScene handle() const { return m_rtc; }

  // Indices of the scene's sphere lights (Scene::lights entries that are SphereLight), in geometry order.
  const std::vector<int>& sphere_light_indices() const { return m_sphere_lights; }

 private:
  struct GeometryRef {
    ShapeKind kind;
    int mesh = 0;
  };
  // Fills hit from Embree's answer (hit refinement in double).
  void refine(const Ray& ray, unsigned geom_id, unsigned prim_id, float tfar, float bu, float bv, Hit& hit) const;

  const Scene& m_scene;
  RTCScene m_rtc = nullptr;
  std::vector<GeometryRef> m_geometries;  // by Embree geometry id
  std::vector<int> m_sphere_lights;
  std::vector<bool> m_sphere_needs_uv;  // by sphere: its material reads a texture (uv is computed only then)
};

// Origin offset along the normal, scaled with the coordinates' magnitude, so a ray leaving a surface does not
// hit it again through float rounding in Embree.
Vec3 offset_origin(const Vec3& p, const Vec3& n, const Vec3& direction);

}  // namespace shadelab
