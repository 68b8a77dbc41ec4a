#include "shadelab/scene/limits.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>

namespace shadelab {

namespace {

std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

struct Checker {
  std::string error;

  bool ok() const { return error.empty(); }
  void fail(const std::string& what, const std::string& message) {
    if (error.empty()) error = what + ": " + message;
  }
  void position(const std::string& what, const Vec3& p) {
    for (double c : {p.x, p.y, p.z}) {
      if (!std::isfinite(c) || std::abs(c) > max_scene_coordinate) {
        fail(what, "coordinate " + num(c) + " is beyond +-" + num(max_scene_coordinate));
        return;
      }
    }
  }
  void length_of(const std::string& what, double v) {
    if (!std::isfinite(v) || v < min_scene_length || v > max_scene_coordinate) {
      fail(what, num(v) + " is outside [" + num(min_scene_length) + ", " + num(max_scene_coordinate) + "]");
    }
  }
  void unit(const std::string& what, const Vec3& d) {
    const double len = length(d);
    if (!is_finite(d) || !(std::abs(len - 1.0) < 1e-6)) fail(what, "is not a unit vector");
  }
  void light(const std::string& what, const Rgb& v) {
    for (double c : {v.r, v.g, v.b}) {
      if (!std::isfinite(c) || c < 0.0 || c > max_light_value) {
        fail(what, num(c) + " is outside [0, " + num(max_light_value) + "]");
        return;
      }
    }
  }
};

}  // namespace

Result<bool> check_scene_limits(const Scene& scene) {
  Checker c;
  const Camera& cam = scene.camera;
  c.position("camera position", cam.position);
  c.position("camera look_at", cam.look_at);
  if (cam.width < 1 || cam.height < 1 || cam.width > max_camera_side || cam.height > max_camera_side ||
      static_cast<long long>(cam.width) * cam.height > max_render_pixels) {
    c.fail("camera", std::to_string(cam.width) + " x " + std::to_string(cam.height) + " pixels is outside the limits (" +
                         std::to_string(max_camera_side) + " on a side, " + std::to_string(max_render_pixels) + " in all)");
  }
  c.unit("camera up", cam.up);
  if (c.ok() && !(length(cam.look_at - cam.position) > 0.0)) c.fail("camera", "look_at equals position");
  for (std::size_t i = 0; i < scene.spheres.size() && c.ok(); ++i) {
    const std::string what = "sphere " + std::to_string(i);
    c.position(what + " center", scene.spheres[i].center);
    c.length_of(what + " radius", scene.spheres[i].radius);
  }
  for (std::size_t i = 0; i < scene.quads.size() && c.ok(); ++i) {
    const QuadShape& q = scene.quads[i];
    const std::string what = "quad " + std::to_string(i);
    c.position(what + " corner", q.corner);
    c.length_of(what + " |u|", length(q.u));
    c.length_of(what + " |v|", length(q.v));
    c.position(what + " far corner", q.corner + q.u + q.v);
    const double area = length(cross(q.u, q.v));
    if (c.ok() && !(area >= min_scene_length * min_scene_length)) c.fail(what, "has no area (|u x v| = " + num(area) + ")");
  }
  for (std::size_t i = 0; i < scene.disks.size() && c.ok(); ++i) {
    const std::string what = "disk " + std::to_string(i);
    c.position(what + " center", scene.disks[i].center);
    c.length_of(what + " radius", scene.disks[i].radius);
    c.unit(what + " normal", scene.disks[i].normal);
  }
  std::uint64_t triangles = 0;
  for (std::size_t m = 0; m < scene.meshes.size() && c.ok(); ++m) {
    const MeshShape& mesh = scene.meshes[m];
    triangles += mesh.indices.size() / 3;
    for (std::size_t i = 0; i < mesh.positions.size() && c.ok(); ++i) {
      c.position("mesh " + std::to_string(m) + " (" + mesh.source + ") vertex " + std::to_string(i), mesh.positions[i]);
    }
  }
  if (c.ok() && triangles > max_scene_triangles) {
    c.fail("meshes", std::to_string(triangles) + " triangles in all; the limit is " + std::to_string(max_scene_triangles));
  }
  for (std::size_t m = 0; m < scene.materials.size() && c.ok(); ++m) {
    const Material& mat = scene.materials[m];
    c.light("material '" + mat.name + "' emission", mat.emission);
    if (!(mat.uv_scale.x > 0.0 && mat.uv_scale.x <= max_uv_scale && mat.uv_scale.y > 0.0 &&
          mat.uv_scale.y <= max_uv_scale)) {
      c.fail("material '" + mat.name + "' uv_scale", "is outside (0, " + num(max_uv_scale) + "]");
    }
    const GlossEncoding& g = mat.gloss_encoding;
    if (c.ok() && !(g.n_black > 0.0 && g.n_black < g.n_white && g.n_white <= max_gloss_exponent)) {
      c.fail("material '" + mat.name + "' gloss_range", "is not 0 < n_black < n_white <= " + num(max_gloss_exponent));
    }
  }
  for (std::size_t i = 0; i < scene.lights.size() && c.ok(); ++i) {
    const std::string what = "light " + std::to_string(i);
    std::visit(
        [&](const auto& l) {
          using T = std::decay_t<decltype(l)>;
          if constexpr (std::is_same_v<T, DirectionalLight>) {
            c.unit(what + " direction", l.to_light);
            c.light(what + " irradiance", l.irradiance);
          } else if constexpr (std::is_same_v<T, PointLight>) {
            c.position(what + " position", l.position);
            c.light(what + " intensity", l.intensity);
          } else if constexpr (std::is_same_v<T, SpotLight>) {
            c.position(what + " position", l.position);
            c.unit(what + " direction", l.axis);
            c.light(what + " intensity", l.intensity);
          } else if constexpr (std::is_same_v<T, SphereLight>) {
            c.position(what + " center", l.center);
            c.length_of(what + " radius", l.radius);
            c.light(what + " radiance", l.radiance);
          } else {
            c.unit(what + " up", l.up);
            c.light(what + " sky", l.sky);
            c.light(what + " ground", l.ground);
          }
        },
        scene.lights[i]);
  }
  const Environment& env = scene.environment;
  if (c.ok() && env.kind == Environment::Kind::uniform) c.light("environment uniform", env.uniform);
  if (c.ok() && env.kind == Environment::Kind::sky) {
    const SkyModel& s = env.sky;
    c.unit("sky sun_direction", s.sun_direction);
    if (!(s.sun_angular_radius_deg >= min_sun_angular_radius_deg && s.sun_angular_radius_deg <= 45.0)) {
      c.fail("sky sun_angular_radius", num(s.sun_angular_radius_deg) + " is outside [" +
                                           num(min_sun_angular_radius_deg) + ", 45] degrees");
    }
    c.light("sky sun_irradiance", s.sun_irradiance);
    c.light("sky zenith", s.zenith);
    c.light("sky horizon", s.horizon);
    c.light("sky ground", s.ground);
  }
  if (c.ok() && env.kind == Environment::Kind::image) {
    if (!std::isfinite(env.scale) || env.scale < 0.0) c.fail("environment scale", num(env.scale) + " is not >= 0");
    float peak = 0.0f;
    for (float v : env.latlong.data) peak = std::max(peak, std::isfinite(v) ? std::abs(v) : HUGE_VALF);
    if (c.ok() && !(static_cast<double>(peak) * env.scale <= max_light_value)) {
      c.fail("environment '" + env.source + "'", "its brightest texel times the scale (" +
                                                     num(static_cast<double>(peak) * env.scale) + ") is above " +
                                                     num(max_light_value));
    }
  }
  if (!c.ok()) return make_error(c.error);
  return true;
}

}  // namespace shadelab
