#include "shadelab/render/path_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "shadelab/core/constants.h"
#include "shadelab/core/frame.h"
#include "shadelab/render/accel.h"
#include "shadelab/render/camera_model.h"
#include "shadelab/render/env_light.h"
#include "shadelab/render/materials.h"
#include "shadelab/render/threads.h"
#include "shadelab/sampling/owen.h"
#include "shadelab/scene/limits.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

namespace {

// Power heuristic with beta = 2 (Veach 1997, eq. 9.13).
double power_heuristic(double pa, double pb) {
  const double a = pa * pa;
  const double b = pb * pb;
  return a + b > 0.0 ? a / (a + b) : 0.0;
}

struct LightRef {
  enum class Type { directional, point, spot, sphere_light, emissive_sphere, quad, disk, environment } type;
  int index = 0;  // into Scene::lights for the first four, into the shape lists otherwise
};

struct LightSample {
  Vec3 wi;
  double distance = std::numeric_limits<double>::infinity();
  Rgb value;          // radiance (area and environment lights) or E_perp (delta lights)
  double pdf = 0.0;   // per unit solid angle; 1 for delta lights
  bool delta = false;
  bool valid = false;
};

struct Counters {
  std::uint64_t rays = 0;
  std::uint64_t nonfinite = 0;  // samples whose radiance is NaN or infinite
};

struct FirstHit {
  bool hit = false;
  Rgb albedo;
  Vec3 normal;
  double depth = 0.0;
};

// Direction toward a uniformly chosen point of the cone a sphere subtends (PBR 4th ed. 6.2.4): exact pdf
// 1 / (2 pi (1 - cos_max)) over the cone.
double sphere_cone_cos(const Vec3& p, const Vec3& center, double radius) {
  const double d2 = dot(center - p, center - p);
  if (d2 <= radius * radius) return 2.0;  // inside: no cone
  return std::sqrt(std::max(0.0, 1.0 - radius * radius / d2));
}

// Distance along the unit direction w from p to the sphere, or infinity.
double sphere_distance(const Vec3& p, const Vec3& w, const Vec3& center, double radius) {
  const Vec3 oc = p - center;
  const double b = dot(oc, w);
  const double c = dot(oc, oc) - radius * radius;
  const double disc = b * b - c;
  if (disc < 0.0) return std::numeric_limits<double>::infinity();
  const double s = std::sqrt(disc);
  const double t0 = -b - s;
  if (t0 > 0.0) return t0;
  const double t1 = -b + s;
  return t1 > 0.0 ? t1 : std::numeric_limits<double>::infinity();
}

class Integrator {
 public:
  Integrator(const Scene& scene, SamplingMode mode, int max_depth)
      : m_scene(scene), m_mode(mode), m_max_depth(max_depth), m_accel(scene), m_env(scene) {}

  Result<bool> prepare();
  // The radiance along the camera ray `ray`, whose closest hit `camera_hit` (when found) was already traced.
  Rgb li(Ray ray, bool camera_found, const Hit& camera_hit, const PixelSampler& sampler, Counters& counters,
         FirstHit* first) const;
  Rgb li(const Ray& ray, const PixelSampler& sampler, Counters& counters, FirstHit* first) const {
    Hit hit;
    ++counters.rays;
    const bool found = m_accel.intersect(ray, hit);
    return li(ray, found, hit, sampler, counters, first);
  }
  const Accelerator& accel() const { return m_accel; }

 private:
  LightSample sample_light(const LightRef& l, const Vec3& p, Vec2 u, double u_extra) const;
  double light_pdf(const LightRef& l, const Vec3& p, const Vec3& wi, const Hit* hit) const;
  Rgb emitted(const Hit& hit, const Vec3& wo_world) const;
  int light_of_hit(const Hit& hit) const;
  bool roulette(int vertex) const { return m_scene.settings.rr_depth > 0 && vertex >= m_scene.settings.rr_depth; }

  const Scene& m_scene;
  SamplingMode m_mode;
  int m_max_depth;
  Accelerator m_accel;
  EnvironmentLight m_env;
  MaterialSet m_materials;
  std::vector<LightRef> m_lights;
  std::vector<int> m_sphere_shape_light, m_quad_light, m_disk_light;  // shape index -> light index or -1
  int m_env_light = -1;
};

Result<bool> Integrator::prepare() {
  if (auto ok = m_materials.prepare(m_scene); !ok) return ok.error();
  for (std::size_t i = 0; i < m_scene.lights.size(); ++i) {
    const auto& l = m_scene.lights[i];
    const int idx = static_cast<int>(i);
    if (std::holds_alternative<DirectionalLight>(l)) m_lights.push_back({LightRef::Type::directional, idx});
    if (std::holds_alternative<PointLight>(l)) m_lights.push_back({LightRef::Type::point, idx});
    if (std::holds_alternative<SpotLight>(l)) m_lights.push_back({LightRef::Type::spot, idx});
    if (std::holds_alternative<SphereLight>(l)) m_lights.push_back({LightRef::Type::sphere_light, idx});
  }
  auto emissive = [&](int material) {
    return material >= 0 && !m_scene.materials[static_cast<std::size_t>(material)].emission.is_black();
  };
  m_sphere_shape_light.assign(m_scene.spheres.size(), -1);
  for (std::size_t i = 0; i < m_scene.spheres.size(); ++i) {
    if (emissive(m_scene.spheres[i].material)) {
      m_sphere_shape_light[i] = static_cast<int>(m_lights.size());
      m_lights.push_back({LightRef::Type::emissive_sphere, static_cast<int>(i)});
    }
  }
  m_quad_light.assign(m_scene.quads.size(), -1);
  for (std::size_t i = 0; i < m_scene.quads.size(); ++i) {
    if (emissive(m_scene.quads[i].material)) {
      m_quad_light[i] = static_cast<int>(m_lights.size());
      m_lights.push_back({LightRef::Type::quad, static_cast<int>(i)});
    }
  }
  m_disk_light.assign(m_scene.disks.size(), -1);
  for (std::size_t i = 0; i < m_scene.disks.size(); ++i) {
    if (emissive(m_scene.disks[i].material)) {
      m_disk_light[i] = static_cast<int>(m_lights.size());
      m_lights.push_back({LightRef::Type::disk, static_cast<int>(i)});
    }
  }
  // A constant environment is left to BRDF sampling (MIS weight 1 when a BRDF ray escapes), as Cycles does with a
  // constant world ("Background MIS has been disabled"): every light sample then goes to the scene's other
  // lights. Light-only rendering still samples it (there, BRDF rays that escape do not count).
  if (m_env.has_light() && !(m_env.is_constant() && m_mode == SamplingMode::mis)) {
    m_env_light = static_cast<int>(m_lights.size());
    m_lights.push_back({LightRef::Type::environment, 0});
  }
  return true;
}

int Integrator::light_of_hit(const Hit& hit) const {
  switch (hit.kind) {
    case ShapeKind::sphere: return m_sphere_shape_light[static_cast<std::size_t>(hit.index)];
    case ShapeKind::quad: return m_quad_light[static_cast<std::size_t>(hit.index)];
    case ShapeKind::disk: return m_disk_light[static_cast<std::size_t>(hit.index)];
    case ShapeKind::sphere_light:
      for (std::size_t i = 0; i < m_lights.size(); ++i) {
        if (m_lights[i].type == LightRef::Type::sphere_light && m_lights[i].index == hit.index) return static_cast<int>(i);
      }
      return -1;
    case ShapeKind::mesh: return -1;  // emissive meshes are reached by BRDF sampling only (MIS weight 1)
  }
  return -1;
}

Rgb Integrator::emitted(const Hit& hit, const Vec3& wo_world) const {
  if (hit.kind == ShapeKind::sphere_light) {
    return std::get<SphereLight>(m_scene.lights[static_cast<std::size_t>(hit.index)]).radiance;
  }
  if (hit.material < 0) return {};
  const Rgb& e = m_scene.materials[static_cast<std::size_t>(hit.material)].emission;
  if (e.is_black()) return {};
  // Quads, disks and meshes emit on their normal's side; spheres outward (their normal points out).
  return dot(hit.geometric_normal, wo_world) > 0.0 ? e : Rgb{};
}

LightSample Integrator::sample_light(const LightRef& l, const Vec3& p, Vec2 u, double u_extra) const {
  LightSample s;
  switch (l.type) {
    case LightRef::Type::directional:
    case LightRef::Type::point:
    case LightRef::Type::spot: {
      const auto& light = m_scene.lights[static_cast<std::size_t>(l.index)];
      const LightIncidence in = std::visit(
          [&](const auto& x) -> LightIncidence {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, DirectionalLight> || std::is_same_v<T, PointLight> ||
                          std::is_same_v<T, SpotLight>) {
              return incident(x, p);
            } else {
              return {};
            }
          },
          light);
      if (in.irradiance_perp.is_black()) return s;
      s.wi = in.wi;
      s.distance = in.distance;
      s.value = in.irradiance_perp;
      s.pdf = 1.0;
      s.delta = true;
      s.valid = true;
      return s;
    }
    case LightRef::Type::sphere_light:
    case LightRef::Type::emissive_sphere: {
      Vec3 center;
      double radius = 1.0;
      Rgb radiance;
      if (l.type == LightRef::Type::sphere_light) {
        const auto& sl = std::get<SphereLight>(m_scene.lights[static_cast<std::size_t>(l.index)]);
        center = sl.center;
        radius = sl.radius;
        radiance = sl.radiance;
      } else {
        const auto& sp = m_scene.spheres[static_cast<std::size_t>(l.index)];
        center = sp.center;
        radius = sp.radius;
        radiance = m_scene.materials[static_cast<std::size_t>(sp.material)].emission;
      }
      const double cos_max = sphere_cone_cos(p, center, radius);
      if (cos_max > 1.0) return s;
      const Frame f = Frame::from_normal(normalize(center - p));
      s.wi = f.to_world(sample_spherical_cap(u, cos_max));
      s.distance = sphere_distance(p, s.wi, center, radius);
      if (!std::isfinite(s.distance)) return s;  // grazing the rim: rounding
      s.value = radiance;
      s.pdf = 1.0 / (two_pi * (1.0 - cos_max));
      s.valid = s.pdf > 0.0 && std::isfinite(s.pdf);
      return s;
    }
    case LightRef::Type::quad: {
      const auto& q = m_scene.quads[static_cast<std::size_t>(l.index)];
      const Vec3 x = q.corner + q.u * u.x + q.v * u.y;
      const Vec3 n = cross(q.u, q.v);
      const double area = length(n);
      const Vec3 d = x - p;
      const double dist2 = dot(d, d);
      s.distance = std::sqrt(dist2);
      s.wi = d / s.distance;
      const double cos_l = -dot(n / area, s.wi);
      if (cos_l <= 0.0) return s;  // the back of a one-sided emitter
      s.value = m_scene.materials[static_cast<std::size_t>(q.material)].emission;
      s.pdf = dist2 / (cos_l * area);  // area density 1/A turned into solid angle
      s.valid = true;
      return s;
    }
    case LightRef::Type::disk: {
      const auto& dk = m_scene.disks[static_cast<std::size_t>(l.index)];
      const Frame f = Frame::from_normal(dk.normal);
      const double r = dk.radius * std::sqrt(u.x);
      const double phi = two_pi * u.y;
      const Vec3 x = dk.center + f.to_world({r * std::cos(phi), r * std::sin(phi), 0.0});
      const Vec3 d = x - p;
      const double dist2 = dot(d, d);
      s.distance = std::sqrt(dist2);
      s.wi = d / s.distance;
      const double cos_l = -dot(dk.normal, s.wi);
      if (cos_l <= 0.0) return s;
      s.value = m_scene.materials[static_cast<std::size_t>(dk.material)].emission;
      s.pdf = dist2 / (cos_l * pi * dk.radius * dk.radius);
      s.valid = true;
      return s;
    }
    case LightRef::Type::environment: {
      const auto e = m_env.sample(u, u_extra);
      if (!(e.pdf > 0.0)) return s;
      s.wi = e.wi;
      s.value = e.radiance;
      s.pdf = e.pdf;
      s.valid = true;
      return s;
    }
  }
  return s;
}

double Integrator::light_pdf(const LightRef& l, const Vec3& p, const Vec3& wi, const Hit* hit) const {
  switch (l.type) {
    case LightRef::Type::directional:
    case LightRef::Type::point:
    case LightRef::Type::spot: return 0.0;
    case LightRef::Type::sphere_light:
    case LightRef::Type::emissive_sphere: {
      Vec3 center;
      double radius = 1.0;
      if (l.type == LightRef::Type::sphere_light) {
        const auto& sl = std::get<SphereLight>(m_scene.lights[static_cast<std::size_t>(l.index)]);
        center = sl.center;
        radius = sl.radius;
      } else {
        const auto& sp = m_scene.spheres[static_cast<std::size_t>(l.index)];
        center = sp.center;
        radius = sp.radius;
      }
      const double cos_max = sphere_cone_cos(p, center, radius);
      return cos_max > 1.0 ? 0.0 : 1.0 / (two_pi * (1.0 - cos_max));
    }
    case LightRef::Type::quad:
    case LightRef::Type::disk: {
      if (hit == nullptr) return 0.0;
      const double cos_l = -dot(hit->geometric_normal, wi);
      if (cos_l <= 0.0) return 0.0;
      double area = 0.0;
      if (l.type == LightRef::Type::quad) {
        const auto& q = m_scene.quads[static_cast<std::size_t>(l.index)];
        area = length(cross(q.u, q.v));
      } else {
        const double r = m_scene.disks[static_cast<std::size_t>(l.index)].radius;
        area = pi * r * r;
      }
      return hit->t * hit->t / (cos_l * area);
    }
    case LightRef::Type::environment: return m_env.pdf(wi);
  }
  return 0.0;
}

Rgb Integrator::li(Ray ray, bool camera_found, const Hit& camera_hit, const PixelSampler& sampler, Counters& counters,
                   FirstHit* first) const {
  Rgb radiance;
  Rgb beta = Rgb::gray(1.0);
  double prev_brdf_pdf = 0.0;  // density of the BRDF sample that produced `ray` (0 for the camera ray)
  Vec3 prev_position;
  const double n_lights = static_cast<double>(m_lights.size());
  Hit hit = camera_hit;
  bool found = camera_found;
  for (int vertex = 1;; ++vertex) {
    const bool camera_ray = vertex == 1;
    if (!camera_ray) {
      ++counters.rays;
      found = m_accel.intersect(ray, hit);
    }
    // MIS weight for light found by following the BRDF-sampled ray.
    auto brdf_weight = [&](double light_density) {
      if (camera_ray) return 1.0;
      switch (m_mode) {
        case SamplingMode::brdf: return 1.0;
        case SamplingMode::light: return light_density > 0.0 ? 0.0 : 1.0;  // unsampleable emitters still count
        case SamplingMode::mis: return power_heuristic(prev_brdf_pdf, light_density);
      }
      return 1.0;
    };
    if (!found) {
      if (m_env.has_light()) {
        const double lp = m_env_light >= 0 ? m_env.pdf(ray.direction) / n_lights : 0.0;
        radiance += beta * m_env.radiance(ray.direction) * brdf_weight(lp);
      }
      break;
    }
    const Vec3 wo_world = -ray.direction;
    const Rgb le = emitted(hit, wo_world);
    if (!le.is_black()) {
      const int li_index = light_of_hit(hit);
      const double lp = li_index >= 0 ? light_pdf(m_lights[static_cast<std::size_t>(li_index)], prev_position, ray.direction, &hit) / n_lights : 0.0;
      radiance += beta * le * brdf_weight(lp);
    }
    if (vertex > m_max_depth || hit.kind == ShapeKind::sphere_light) break;

    const ShadingFrame sf = shading_frame(m_scene, hit, wo_world);
    const Vec3& ng = sf.ng;
    const Vec3& ns = sf.frame.n;
    const Frame& frame = sf.frame;
    BrdfPtr holder;
    const Brdf* brdf = m_materials.brdf(hit.material, hit.uv, holder);
    if (brdf == nullptr) break;  // a purely emissive surface absorbs
    const Vec3 wo = frame.to_local(wo_world);

    // Dimension groups of this vertex (owen.h): one for the light sample (point, choice of light, choice within
    // the light), one for the BRDF sample (direction, lobe, Russian roulette). Fixed per vertex whatever the
    // sampling mode, so the two stratified dimensions always carry the 2D points.
    // Only the dimensions used are computed: the environment's choice between sun and sky (u_nee[3]) only with
    // an environment, Russian roulette (u_brdf[3]) only from rr_depth on.
    const auto u_brdf = sampler.group(static_cast<std::uint32_t>(2 * vertex), roulette(vertex) ? 4 : 3);

    // Next-event estimation.
    if (m_mode != SamplingMode::brdf && !m_lights.empty()) {
      const auto u_nee = sampler.group(static_cast<std::uint32_t>(2 * vertex - 1), m_env_light >= 0 ? 4 : 3);
      const double u_light = u_nee[2];
      const auto pick = std::min(static_cast<std::size_t>(u_light * n_lights), m_lights.size() - 1);
      const Vec2 u{u_nee[0], u_nee[1]};
      const double u_extra = u_nee[3];
      const LightSample ls = sample_light(m_lights[pick], hit.position, u, u_extra);
      if (ls.valid && dot(ls.wi, ng) > 0.0) {
        const Vec3 wi = frame.to_local(ls.wi);
        const Rgb f = brdf->eval(wi, wo);
        if (!f.is_black()) {
          // The shadow ray stops short of the light: Embree's float intersection of a sphere hit near its rim
          // is off by up to ~1e-4 relative, which would let the light occlude itself; 2e-3 is far outside that.
          Ray shadow{offset_origin(hit.position, ng, ls.wi), ls.wi,
                     std::isfinite(ls.distance) ? ls.distance * (1.0 - 2e-3) : ls.distance};
          ++counters.rays;
          if (!m_accel.occluded(shadow)) {
            double w = 1.0;
            if (!ls.delta && m_mode == SamplingMode::mis) w = power_heuristic(ls.pdf / n_lights, brdf->pdf(wi, wo));
            radiance += beta * f * ls.value * (wi.z * w * n_lights / ls.pdf);
          }
        }
      }
    }

    // BRDF sampling for the next direction.
    const BrdfSample bs = brdf->sample(wo, {u_brdf[0], u_brdf[1]}, u_brdf[2]);
    if (first != nullptr && camera_ray) {
      first->hit = true;
      first->albedo = bs.weight;
      first->normal = ns;
      first->depth = hit.t;
    }
    if (!(bs.pdf > 0.0) || bs.weight.is_black()) break;
    const Vec3 wi_world = frame.to_world(bs.wi);
    if (dot(wi_world, ng) <= 0.0) break;  // below the geometric surface: no transmission
    beta = beta * bs.weight;
    prev_brdf_pdf = bs.pdf;
    prev_position = hit.position;
    ray = Ray{offset_origin(hit.position, ng, wi_world), wi_world};
    // Russian roulette (unbiased: survivors are divided by the survival probability). Survival
    // min(1, sqrt(max throughput)), Cycles' path_state_continuation_probability: kills fewer paths than
    // min(1, max throughput) (pbrt's), which cost more error than it saved time (docs/renderer.md).
    if (roulette(vertex)) {
      const double q = std::min(1.0, std::sqrt(beta.max_component()));
      if (u_brdf[3] >= q) break;
      beta = beta / q;
    }
  }
  return radiance;
}

}  // namespace

Image image_from_sums(const std::vector<FixedRgb>& sums, const std::vector<std::uint32_t>& nonfinite, int width, int height,
                      std::uint64_t samples) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      const bool bad = !nonfinite.empty() && nonfinite[p] > 0;
      image.set(x, y, bad ? Rgb::gray(std::numeric_limits<double>::quiet_NaN()) : sums[p].mean(samples));
    }
  }
  return image;
}

std::pair<int, int> shard_sample_range(int spp, const ShardSpec& shard) {
  if (shard.split == ShardSplit::tiles) return {0, spp};
  const auto begin = static_cast<std::int64_t>(spp) * shard.index / shard.count;
  const auto end = static_cast<std::int64_t>(spp) * (shard.index + 1) / shard.count;
  return {static_cast<int>(begin), static_cast<int>(end)};
}

bool shard_owns_tile(int tile, const ShardSpec& shard) {
  return shard.split == ShardSplit::samples || tile % shard.count == shard.index;
}

Result<RenderResult> render_scene(const Scene& scene, const RenderOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const int spp = options.spp > 0 ? options.spp : scene.settings.spp;
  const int max_depth = options.max_depth > 0 ? options.max_depth : scene.settings.max_depth;
  const int threads = options.threads >= 0 ? options.threads : scene.settings.threads;
  if (spp < 1) return make_error("render: samples per pixel must be >= 1");
  if (auto limits = check_scene_limits(scene); !limits) return limits.error();
  const ShardSpec& shard = options.shard;
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count) {
    return make_error("render: shard " + std::to_string(shard.index) + "/" + std::to_string(shard.count) +
                      " is not one of 0/N .. (N-1)/N");
  }
  Integrator integrator(scene, options.mode, max_depth);
  auto ok = integrator.prepare();
  if (!ok) return ok.error();
  const auto t_render = std::chrono::steady_clock::now();  // after the BVH build and the light tables
  const CameraModel camera(scene.camera);
  const int w = scene.camera.width;
  const int h = scene.camera.height;
  const auto pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  RenderResult result;
  result.sums.assign(pixels, FixedRgb{});
  result.nonfinite.assign(pixels, 0);
  std::vector<Rgb> albedo_sum(options.aovs ? pixels : 0);
  std::vector<Vec3> normal_first(options.aovs ? pixels : 0);
  std::vector<double> depth_first(options.aovs ? pixels : 0, 0.0);
  std::atomic<std::uint64_t> rays{0}, nonfinite{0};
  // Fixed 16 x 16 tiles in row-major order (the unit of the tile split).
  constexpr int tile_size = render_tile_size;
  constexpr int packet = 8;
  static_assert(tile_size % packet == 0);
  const int tiles_x = (w + tile_size - 1) / tile_size;
  const int tiles_y = (h + tile_size - 1) / tile_size;
  std::vector<int> tiles;
  std::uint64_t covered = 0;  // pixels rendered
  for (int t = 0; t < tiles_x * tiles_y; ++t) {
    if (!shard_owns_tile(t, shard)) continue;
    tiles.push_back(t);
    const int x0 = (t % tiles_x) * tile_size, y0 = (t / tiles_x) * tile_size;
    covered += static_cast<std::uint64_t>(std::min(w, x0 + tile_size) - x0) * static_cast<std::uint64_t>(std::min(h, y0 + tile_size) - y0);
  }
  const auto [first_sample, end_sample] = shard_sample_range(spp, shard);
  result.sample_begin = first_sample;
  const int samples = end_sample - first_sample;
  // Passes of up to 8 samples: Ctrl-C and progress react within one pass.
  const int per_pass = std::clamp(samples / 32, 1, 8);
  tbb::task_arena arena(arena_threads(threads));
  int done = first_sample;
  while (done < end_sample) {
    if (options.cancel != nullptr && options.cancel->load() && done > first_sample) {
      result.stats.cancelled = true;
      break;
    }
    const int s0 = done;
    const int s1 = std::min(end_sample, done + per_pass);
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        Counters counters;
        for (std::size_t k = r.begin(); k != r.end(); ++k) {
          if (options.abort != nullptr && options.abort->load(std::memory_order_relaxed)) break;
          const int tile = tiles[k];
          const int x0 = (tile % tiles_x) * tile_size;
          const int y0 = (tile / tiles_x) * tile_size;
          const int x1 = std::min(w, x0 + tile_size);
          const int y1 = std::min(h, y0 + tile_size);
          for (int y = y0; y < y1; ++y) {
            // Camera rays go to Embree as packets of the 8 neighbouring pixels of a row that share a sample index
            // (tiles are multiples of 8 wide, so packets are the same however the image is split).
            for (int xp = x0; xp < x1; xp += packet) {
              const int n = std::min(packet, x1 - xp);
              const std::size_t p0 = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(xp);
              std::uint64_t pixel_seed[packet];
              for (int i = 0; i < n; ++i) pixel_seed[i] = mix64(scene.settings.seed ^ mix64(p0 + static_cast<std::size_t>(i)));
              for (int s = s0; s < s1; ++s) {
                Ray camera_rays[packet];
                for (int i = 0; i < n; ++i) {
                  const auto jitter = PixelSampler(pixel_seed[i], static_cast<std::uint32_t>(s), options.sampler).group(0, 2);
                  camera_rays[i] = camera.ray(xp + i + jitter[0], y + jitter[1]);
                }
                Hit hits[packet];
                bool found[packet];
                integrator.accel().intersect8(camera_rays, n, hits, found);
                counters.rays += static_cast<std::uint64_t>(n);
                for (int i = 0; i < n; ++i) {
                  const std::size_t pi_ = p0 + static_cast<std::size_t>(i);
                  const PixelSampler sampler(pixel_seed[i], static_cast<std::uint32_t>(s), options.sampler);
                  FirstHit first;
                  const Rgb l = integrator.li(camera_rays[i], found[i], hits[i], sampler, counters, options.aovs ? &first : nullptr);
                  if (!result.sums[pi_].add(l)) {
                    ++counters.nonfinite;
                    ++result.nonfinite[pi_];
                  }
                  if (options.aovs) {
                    albedo_sum[pi_] += first.albedo;
                    if (s == 0) {
                      normal_first[pi_] = first.hit ? first.normal : Vec3{};
                      depth_first[pi_] = first.hit ? first.depth : 0.0;
                    }
                  }
                }
              }
            }
          }
        }
        rays.fetch_add(counters.rays, std::memory_order_relaxed);
        nonfinite.fetch_add(counters.nonfinite, std::memory_order_relaxed);
      });
    });
    if (options.abort != nullptr && options.abort->load()) return make_error("render stopped");
    done = s1;
    if (options.progress) options.progress(static_cast<double>(done - first_sample) / std::max(1, samples), done - first_sample);
  }
  result.sample_end = done;
  result.stats.render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_render).count();
  const auto rendered = static_cast<std::uint64_t>(done - first_sample);
  result.beauty = image_from_sums(result.sums, result.nonfinite, w, h, rendered);
  if (options.aovs) {
    result.albedo = Image(w, h);
    result.normal = Image(w, h);
    result.depth = Image(w, h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        result.albedo.set(x, y, rendered > 0 ? albedo_sum[i] / static_cast<double>(rendered) : Rgb{});
        result.normal.set(x, y, {normal_first[i].x, normal_first[i].y, normal_first[i].z});
        result.depth.set(x, y, Rgb::gray(depth_first[i]));
      }
    }
  }
  result.stats.spp_done = static_cast<int>(rendered);
  result.stats.camera_rays = rendered * covered;
  result.stats.rays = rays.load();
  result.stats.nonfinite_samples = nonfinite.load();
  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

Result<RadianceEstimate> estimate_radiance(const Scene& scene, const Vec3& origin, const Vec3& direction, int samples,
                                           SamplingMode mode, int max_depth, std::uint64_t seed, SamplerKind sampler) {
  Integrator integrator(scene, mode, max_depth > 0 ? max_depth : scene.settings.max_depth);
  auto ok = integrator.prepare();
  if (!ok) return ok.error();
  if (samples < 1) return make_error("estimate_radiance: samples must be >= 1");
  // Randomized QMC: `replicas` independent scrambles (pixel seeds) of samples / replicas points each. Their
  // means are independent and unbiased, so the spread of the means gives an honest standard error (the
  // per-sample variance would overstate the error of stratified points).
  const int replicas = std::min(samples, 64);
  Counters counters;
  Rgb sum, sum2;
  int used = 0;
  for (int r = 0; r < replicas; ++r) {
    const int n = samples / replicas + (r < samples % replicas ? 1 : 0);
    const std::uint64_t pixel_seed = mix64(seed ^ mix64(static_cast<std::uint64_t>(r)));
    Rgb replica;
    for (int s = 0; s < n; ++s) {
      replica += integrator.li(Ray{origin, normalize(direction)}, PixelSampler(pixel_seed, static_cast<std::uint32_t>(s), sampler), counters, nullptr);
    }
    used += n;
    sum += replica;
    const Rgb mean = replica / n;
    sum2 += mean * mean * n;  // weighted by the replica's size
  }
  RadianceEstimate e;
  e.mean = sum / used;
  // Variance of the weighted mean: sum n_r (m_r - m)^2 / ((R - 1) N), the replicas' sizes differing by at most 1.
  const Rgb spread = sum2 / used - e.mean * e.mean;
  const double scale = replicas > 1 ? static_cast<double>(replicas) / (replicas - 1) / replicas : 0.0;
  e.standard_error = {std::sqrt(std::max(0.0, spread.r) * scale), std::sqrt(std::max(0.0, spread.g) * scale),
                      std::sqrt(std::max(0.0, spread.b) * scale)};
  return e;
}

}  // namespace shadelab
