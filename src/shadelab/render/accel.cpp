#include "shadelab/render/accel.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "shadelab/core/constants.h"

namespace shadelab {

namespace {

RTCDevice device() {
  static RTCDevice d = [] {
    RTCDevice dev = rtcNewDevice(nullptr);
    if (dev == nullptr) throw std::runtime_error("Embree: cannot create a device");
    return dev;
  }();
  return d;
}

float f(double v) { return static_cast<float>(v); }

}  // namespace

Vec3 offset_origin(const Vec3& p, const Vec3& n, const Vec3& direction) {
  const double scale = 1e-4 * (1.0 + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
  return p + n * (dot(direction, n) >= 0.0 ? scale : -scale);
}

Accelerator::Accelerator(const Scene& scene) : m_scene(scene) {
  RTCDevice dev = device();
  m_rtc = rtcNewScene(dev);
  rtcSetSceneBuildQuality(m_rtc, RTC_BUILD_QUALITY_HIGH);
  auto attach = [&](RTCGeometry g, GeometryRef ref) {
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(m_rtc, g);
    rtcReleaseGeometry(g);
    if (m_geometries.size() <= id) m_geometries.resize(id + 1, GeometryRef{ShapeKind::sphere, 0});
    m_geometries[id] = ref;
  };
  auto spheres = [&](const std::vector<Vec3>& centers, const std::vector<double>& radii, ShapeKind kind) {
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                          4 * sizeof(float), centers.size()));
    for (std::size_t i = 0; i < centers.size(); ++i) {
      v[4 * i] = f(centers[i].x);
      v[4 * i + 1] = f(centers[i].y);
      v[4 * i + 2] = f(centers[i].z);
      v[4 * i + 3] = f(radii[i]);
    }
    attach(g, {kind, 0});
  };
  if (!scene.spheres.empty()) {
    std::vector<Vec3> c;
    std::vector<double> r;
    for (const auto& s : scene.spheres) {
      c.push_back(s.center);
      r.push_back(s.radius);
      const Material& m = scene.materials[static_cast<std::size_t>(s.material)];
      m_sphere_needs_uv.push_back(m.textured() || m.normal_texture >= 0);
    }
    spheres(c, r, ShapeKind::sphere);
  }
  {
    std::vector<Vec3> c;
    std::vector<double> r;
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
      if (const auto* s = std::get_if<SphereLight>(&scene.lights[i])) {
        c.push_back(s->center);
        r.push_back(s->radius);
        m_sphere_lights.push_back(static_cast<int>(i));
      }
    }
    if (!c.empty()) spheres(c, r, ShapeKind::sphere_light);
  }
  if (!scene.quads.empty()) {
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_QUAD);
    const std::size_t n = scene.quads.size();
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4 * n));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), n));
    for (std::size_t i = 0; i < n; ++i) {
      const auto& q = scene.quads[i];
      const Vec3 corners[4] = {q.corner, q.corner + q.u, q.corner + q.u + q.v, q.corner + q.v};
      for (int k = 0; k < 4; ++k) {
        v[3 * (4 * i + static_cast<std::size_t>(k))] = f(corners[k].x);
        v[3 * (4 * i + static_cast<std::size_t>(k)) + 1] = f(corners[k].y);
        v[3 * (4 * i + static_cast<std::size_t>(k)) + 2] = f(corners[k].z);
        idx[4 * i + static_cast<std::size_t>(k)] = static_cast<unsigned>(4 * i + static_cast<std::size_t>(k));
      }
    }
    attach(g, {ShapeKind::quad, 0});
  }
  if (!scene.disks.empty()) {
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT);
    const std::size_t n = scene.disks.size();
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), n));
    auto* nb = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), n));
    for (std::size_t i = 0; i < n; ++i) {
      const auto& d = scene.disks[i];
      v[4 * i] = f(d.center.x);
      v[4 * i + 1] = f(d.center.y);
      v[4 * i + 2] = f(d.center.z);
      v[4 * i + 3] = f(d.radius);
      nb[3 * i] = f(d.normal.x);
      nb[3 * i + 1] = f(d.normal.y);
      nb[3 * i + 2] = f(d.normal.z);
    }
    attach(g, {ShapeKind::disk, 0});
  }
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const auto& mesh = scene.meshes[m];
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.positions.size()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      v[3 * i] = f(mesh.positions[i].x);
      v[3 * i + 1] = f(mesh.positions[i].y);
      v[3 * i + 2] = f(mesh.positions[i].z);
    }
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), mesh.indices.size() / 3));
    std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
    attach(g, {ShapeKind::mesh, static_cast<int>(m)});
  }
  rtcCommitScene(m_rtc);
}

Accelerator::~Accelerator() {
  if (m_rtc != nullptr) rtcReleaseScene(m_rtc);
}

namespace {

void set_ray(RTCRay& r, const Ray& ray) {
  r.org_x = f(ray.origin.x);
  r.org_y = f(ray.origin.y);
  r.org_z = f(ray.origin.z);
  r.dir_x = f(ray.direction.x);
  r.dir_y = f(ray.direction.y);
  r.dir_z = f(ray.direction.z);
  r.tnear = 0.0f;
  r.tfar = std::isfinite(ray.t_max) ? f(ray.t_max) : std::numeric_limits<float>::infinity();
  r.time = 0.0f;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
}

// Solves p - corner = s u + t v in the least-squares sense (exact for points on the quad).
Vec2 quad_uv(const QuadShape& q, const Vec3& p) {
  const Vec3 d = p - q.corner;
  const double uu = dot(q.u, q.u), uv = dot(q.u, q.v), vv = dot(q.v, q.v);
  const double du = dot(d, q.u), dv = dot(d, q.v);
  const double det = uu * vv - uv * uv;
  return {(du * vv - dv * uv) / det, (dv * uu - du * uv) / det};
}

}  // namespace

bool Accelerator::intersect(const Ray& ray, Hit& hit) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  set_ray(rh.ray, ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(m_rtc, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  refine(ray, rh.hit.geomID, rh.hit.primID, rh.ray.tfar, rh.hit.u, rh.hit.v, hit);
  return true;
}

void Accelerator::intersect8(const Ray* rays, int count, Hit* hits, bool* found) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(32) int valid[8];
  alignas(32) RTCRayHit8 rh;
  for (int i = 0; i < 8; ++i) {
    valid[i] = i < count ? -1 : 0;
    const Ray& r = rays[i < count ? i : 0];
    rh.ray.org_x[i] = f(r.origin.x);
    rh.ray.org_y[i] = f(r.origin.y);
    rh.ray.org_z[i] = f(r.origin.z);
    rh.ray.dir_x[i] = f(r.direction.x);
    rh.ray.dir_y[i] = f(r.direction.y);
    rh.ray.dir_z[i] = f(r.direction.z);
    rh.ray.tnear[i] = 0.0f;
    rh.ray.tfar[i] = std::isfinite(r.t_max) ? f(r.t_max) : std::numeric_limits<float>::infinity();
    rh.ray.time[i] = 0.0f;
    rh.ray.mask[i] = 0xFFFFFFFFu;
    rh.ray.id[i] = 0;
    rh.ray.flags[i] = 0;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect8(valid, m_rtc, &ctx, &rh);
  for (int i = 0; i < count; ++i) {
    found[i] = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
    if (found[i]) refine(rays[i], rh.hit.geomID[i], rh.hit.primID[i], rh.ray.tfar[i], rh.hit.u[i], rh.hit.v[i], hits[i]);
  }
}

void Accelerator::refine(const Ray& ray, unsigned geom_id, unsigned prim_id, float tfar, float bu, float bv, Hit& hit) const {
  const GeometryRef& ref = m_geometries[geom_id];
  const auto prim = static_cast<int>(prim_id);
  hit.t = static_cast<double>(tfar);
  hit.position = ray.origin + ray.direction * hit.t;
  hit.kind = ref.kind;
  hit.primitive = prim;
  switch (ref.kind) {
    case ShapeKind::sphere:
    case ShapeKind::sphere_light: {
      Vec3 center;
      double radius = 1.0;
      if (ref.kind == ShapeKind::sphere) {
        const auto& s = m_scene.spheres[static_cast<std::size_t>(prim)];
        center = s.center;
        radius = s.radius;
        hit.material = s.material;
        hit.index = prim;
      } else {
        hit.index = m_sphere_lights[static_cast<std::size_t>(prim)];
        const auto& s = std::get<SphereLight>(m_scene.lights[static_cast<std::size_t>(hit.index)]);
        center = s.center;
        radius = s.radius;
        hit.material = -1;
      }
      const Vec3 n = normalize(hit.position - center);
      hit.position = center + n * radius;  // refined onto the sphere in double
      hit.geometric_normal = n;
      hit.shading_normal = n;
      // Lat-long uv about +Y, as the environment mapping; only textured spheres need it (two inverse trig calls).
      if (ref.kind == ShapeKind::sphere && m_sphere_needs_uv[static_cast<std::size_t>(prim)]) {
        hit.uv = {0.5 + std::atan2(n.z, n.x) * inv_two_pi, std::acos(std::clamp(n.y, -1.0, 1.0)) * inv_pi};
      } else {
        hit.uv = {};
      }
      const Vec3 t{-n.z, 0.0, n.x};
      hit.dpdu = length(t) > 1e-12 ? normalize(t) : Vec3{1.0, 0.0, 0.0};
      break;
    }
    case ShapeKind::quad: {
      const auto& q = m_scene.quads[static_cast<std::size_t>(prim)];
      hit.index = prim;
      hit.material = q.material;
      hit.geometric_normal = normalize(cross(q.u, q.v));
      hit.shading_normal = hit.geometric_normal;
      hit.uv = quad_uv(q, hit.position);
      hit.dpdu = normalize(q.u);
      break;
    }
    case ShapeKind::disk: {
      const auto& d = m_scene.disks[static_cast<std::size_t>(prim)];
      hit.index = prim;
      hit.material = d.material;
      hit.geometric_normal = d.normal;
      hit.shading_normal = d.normal;
      const Frame fr = Frame::from_normal(d.normal);
      const Vec3 local = fr.to_local(hit.position - d.center);
      hit.uv = {0.5 + local.x / (2.0 * d.radius), 0.5 + local.y / (2.0 * d.radius)};
      hit.dpdu = fr.s;
      break;
    }
    case ShapeKind::mesh: {
      const auto& mesh = m_scene.meshes[static_cast<std::size_t>(ref.mesh)];
      hit.index = ref.mesh;
      hit.material = mesh.material;
      const auto p = static_cast<std::size_t>(prim);
      const std::uint32_t i0 = mesh.indices[3 * p], i1 = mesh.indices[3 * p + 1], i2 = mesh.indices[3 * p + 2];
      const Vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
      const Vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
      hit.geometric_normal = normalize(cross(e1, e2));
      const double b1 = static_cast<double>(bu);
      const double b2 = static_cast<double>(bv);
      const double b0 = 1.0 - b1 - b2;
      hit.position = mesh.positions[i0] * b0 + mesh.positions[i1] * b1 + mesh.positions[i2] * b2;
      if (!mesh.normals.empty()) {
        const Vec3 n = mesh.normals[i0] * b0 + mesh.normals[i1] * b1 + mesh.normals[i2] * b2;
        hit.shading_normal = length(n) > 0.0 ? normalize(n) : hit.geometric_normal;
      } else {
        hit.shading_normal = hit.geometric_normal;
      }
      if (!mesh.uvs.empty()) {
        hit.uv = {mesh.uvs[i0].x * b0 + mesh.uvs[i1].x * b1 + mesh.uvs[i2].x * b2,
                  mesh.uvs[i0].y * b0 + mesh.uvs[i1].y * b1 + mesh.uvs[i2].y * b2};
      } else {
        hit.uv = {b1, b2};
      }
      hit.dpdu = normalize(e1);
      break;
    }
  }
}

bool Accelerator::occluded(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  set_ray(r, ray);
  rtcOccluded1(m_rtc, &ctx, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace shadelab
