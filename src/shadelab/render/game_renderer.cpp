#include "shadelab/render/game_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/envmap/specular/split_sum_lobes.h"
#include "shadelab/envmap/specular/split_sum_taps.h"
#include "shadelab/envmap/diffuse/irradiance.h"
#include "shadelab/envmap/specular/prefilter.h"
#include "shadelab/envmap/specular/prefilter_ggx.h"
#include "shadelab/render/camera_model.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/brdf/game_lobe.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/render/accel.h"
#include "shadelab/render/env_light.h"
#include "shadelab/render/materials.h"
#include "shadelab/render/threads.h"
#include "shadelab/scene/limits.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {

namespace {

class GameShader {
 public:
  GameShader(const Scene& scene, const GameOptions& options, const GameEnvironment* baked)
      : m_scene(scene), m_options(options), m_accel(scene), m_env(scene), m_baked(baked) {}
  GameShader(const GameShader&) = delete;  // m_baked may point into m_owned
  GameShader& operator=(const GameShader&) = delete;

  Result<bool> prepare() {
    if (auto ok = m_materials.prepare(m_scene); !ok) return ok.error();
    // Punctual lights as the engine sees them: radiometric E_perp here, the game colour is E_perp / pi.
    for (const auto& l : m_scene.lights) {
      const auto* d = std::get_if<DirectionalLight>(&l);
      if (d != nullptr && (d->game_sh || m_options.directional_in_sh) && m_options.diffuse == GameAmbient::sh9) {
        // D3DX-style: the delta pi c delta(w - d) projected and scaled by 16/17 (sh.h), c = E_perp / pi.
        m_sh_lights += sh9_directional_light(d->to_light, kernel::game_colour_from_irradiance(d->irradiance), true);
        m_has_sh_lights = true;
        continue;
      }
      if (std::holds_alternative<DirectionalLight>(l) || std::holds_alternative<PointLight>(l) ||
          std::holds_alternative<SpotLight>(l)) {
        m_punctual.push_back(l);
      } else if (const auto* s = std::get_if<SphereLight>(&l)) {
        // Point-light limit of a sphere light: I = pi L r0^2 (zoo article).
        m_punctual.push_back(PointLight{s->center, sphere_light_intensity(s->radiance, s->radius)});
      }
    }
    if (m_scene.environment.kind == Environment::Kind::sky) {
      m_punctual.push_back(DirectionalLight{m_scene.environment.sky.sun_direction, m_scene.environment.sky.sun_irradiance});
    }
    // The baked environment: SH9, irradiance cube and prefiltered specular chain.
    // The split sum's GGX chain only for a scene with a ggx or filament material.
    // A material takes the split sum when its BRDF answers split_sum_inputs() (brdf.h): the model says so.
    for (std::size_t i = 0; i < m_scene.materials.size(); ++i) {
      BrdfPtr holder;
      const Brdf* f = m_materials.brdf(static_cast<int>(i), {0.5, 0.5}, holder);
      m_split_sum.push_back(m_options.ggx_specular == GameGgxSpecular::split_sum && f != nullptr &&
                            f->split_sum_inputs().has_value());
    }
    const bool any_split_sum = std::find(m_split_sum.begin(), m_split_sum.end(), true) != m_split_sum.end();
    if (m_env.has_light() && m_baked != nullptr) {
      // A bake from the caller (render_game's third overload): it must hold what these options read.
      const GameEnvironment& b = *m_baked;
      if (!b.has_light) return make_error("game renderer: the baked environment is empty but the scene has one");
      if (m_options.diffuse == GameAmbient::irradiance_map && b.irradiance.size == 0) {
        return make_error("game renderer: the baked environment has no irradiance cube (diffuse irradiance_map)");
      }
      bool any_phong_chain = false;  // a material that reads the Phong chain (game_specular_ambients' rule)
      for (std::size_t i = 0; i < m_scene.materials.size(); ++i) {
        BrdfPtr holder;
        const Brdf* f = m_materials.brdf(static_cast<int>(i), {0.5, 0.5}, holder);
        if (!m_split_sum[i] && f != nullptr && f->game_phong_exponent() > 0.0) any_phong_chain = true;
      }
      if (m_options.specular_ambient && any_phong_chain && b.specular.levels.empty()) {
        return make_error("game renderer: the baked environment has no prefiltered chain (specular_ambient)");
      }
      if (m_options.specular_ambient && any_split_sum && b.specular_ggx.levels.empty()) {
        return make_error("game renderer: the baked environment has no GGX chain (split sum)");
      }
    } else if (m_env.has_light()) {
      GameOptions bake_options = m_options;
      if (!any_split_sum) bake_options.ggx_specular = GameGgxSpecular::phong;
      auto baked = bake_game_environment(m_env, bake_options);
      if (!baked) return baked.error();
      m_owned = std::move(*baked);
      m_baked = &m_owned;
    }
    if (m_baked != nullptr) m_sh = m_baked->sh;
    if (any_split_sum) {
      if (m_options.dfg_size < 1 || m_options.dfg_size > 4096) return make_error("dfg_size must be in [1, 4096]");
      if (m_options.split_sum_taps < 1 || m_options.split_sum_taps > split_sum_taps_max) {
        return make_error("split_sum_taps must be in [1, 1024]");
      }
      m_dfg = m_baked != nullptr && m_baked->dfg ? m_baked->dfg.get() : &game_dfg_table(m_options.dfg_size);
      // The lobe table's rows are computed as the pixels first read them (split_sum_lobes.h).
      if (m_options.split_sum_lookup == GameSplitSumLookup::lobes) {
        m_lobes = m_baked != nullptr && m_baked->lobes ? m_baked->lobes.get() : &split_sum_lobe_table();
      }
      // The chain and the DFG table as the kernels' fetches read them (kernels/game_ibl.sl), bound per pixel.
      if (m_baked != nullptr && !m_baked->specular_ggx.levels.empty()) {
        m_chain_texels.emplace(m_baked->specular_ggx);
        m_ibl_texels = m_chain_texels->texels(m_dfg);
        if (m_lobes != nullptr) bind_split_sum_lobe_table(m_ibl_texels, *m_lobes);
      }
    }
    m_sh += m_sh_lights;  // the environment's coefficients (zero without one) and the D3DX-style lights
    // Per material: Phong exponent, wrap and the specular lobe's directional albedo over cos(theta_o).
    for (std::size_t i = 0; i < m_scene.materials.size(); ++i) {
      const Material& m = m_scene.materials[i];
      GameLobe info;
      BrdfPtr holder;
      if (const Brdf* f = m_materials.brdf(static_cast<int>(i), {0.5, 0.5}, holder)) info = game_lobe(*f);
      if (!m.model.empty() && m.metallic_roughness_texture >= 0) {
        const ModelInfo* model = find_brdf_model(m.model);
        auto values = parse_params(model->name, model->params, m.params);
        if (!values) return values.error();
        info.roughness_factor = values->scalar("perceptual_roughness");
      }
      m_info.push_back(info);
      m_albedo_tables.push_back(game_specular_albedo_table(info));
    }
    return true;
  }

  Rgb shade(const Ray& ray) const {
    Hit hit;
    if (!m_accel.intersect(ray, hit)) return m_env.radiance(ray.direction);
    const Vec3 wo_world = -ray.direction;
    Rgb l;
    if (hit.kind == ShapeKind::sphere_light) return std::get<SphereLight>(m_scene.lights[static_cast<std::size_t>(hit.index)]).radiance;
    if (hit.material >= 0) {
      const Rgb& e = m_scene.materials[static_cast<std::size_t>(hit.material)].emission;
      if (!e.is_black() && dot(hit.geometric_normal, wo_world) > 0.0) l += e;
    }
    const ShadingFrame sf = shading_frame(m_scene, hit, wo_world);
    BrdfPtr holder;
    const Brdf* f = m_materials.brdf(hit.material, hit.uv, holder);
    if (f == nullptr) return l;
    const Vec3 wo = sf.frame.to_local(wo_world);
    const GameLobe& info = m_info[static_cast<std::size_t>(hit.material)];
    if (m_options.punctual) {
      for (const auto& light : m_punctual) {
        const LightIncidence in = std::visit(
            [&](const auto& x) -> LightIncidence {
              using T = std::decay_t<decltype(x)>;
              if constexpr (std::is_same_v<T, DirectionalLight> || std::is_same_v<T, PointLight> || std::is_same_v<T, SpotLight>) {
                return incident(x, hit.position);
              } else {
                return {};
              }
            },
            light);
        if (in.irradiance_perp.is_black() || dot(in.wi, sf.ng) <= 0.0) continue;
        const Vec3 wi = sf.frame.to_local(in.wi);
        if (wi.z <= 0.0) continue;
        if (m_options.shadows) {
          const Ray shadow{offset_origin(hit.position, sf.ng, in.wi), in.wi,
                           std::isfinite(in.distance) ? in.distance * (1.0 - 2e-3) : in.distance};
          if (m_accel.occluded(shadow)) continue;
        }
        const Rgb colour_game = kernel::game_colour_from_irradiance(in.irradiance_perp);  // E_perp = pi x colour
        // The game shading equation L = pi f c cos, the kernel kernels/game_shading.sl; drop_pi is the bug of
        // forgetting the pi: the game colour used as if it were the irradiance.
        const Rgb fr = f->eval(wi, wo);
        l += m_options.drop_pi ? kernel::punctual_radiometric(fr, colour_game, wi.z)
                               : kernel::punctual_game(fr, colour_game, wi.z);
      }
    }
    Rgb e_over_pi;  // the diffuse ambient's E/pi at n (zero with GameAmbient::none)
    if (m_env.has_light() || m_has_sh_lights) {
      const Vec3 n = sf.frame.n;
      if (m_options.diffuse != GameAmbient::none) {
        if (m_options.diffuse == GameAmbient::irradiance_map) {
          e_over_pi = m_baked->irradiance.sample(n);
        } else {
          e_over_pi = sh9_evaluate(m_sh, n, info.wrap > 0.0 ? wrapped_band_factors_over_pi(info.wrap) : cosine_band_factors_over_pi);
        }
        l += kernel::game_diffuse_ambient(f->diffuse_albedo(), e_over_pi);
      }
    }
    std::optional<SplitSumInputs> split;
    if (m_env.has_light() && m_options.specular_ambient && m_split_sum[static_cast<std::size_t>(hit.material)] &&
        m_baked != nullptr && !m_baked->specular_ggx.levels.empty() && m_dfg != nullptr) {
      split = f->split_sum_inputs();  // the hit's own BRDF: a textured hit's roughness and f0
    }
    if (split && m_chain_texels) {
      // The split sum of kernels/game_ambient.sl: prefiltered_ggx(d, r) (f0 A + f90 B), A and B at (N.V, r),
      // d the mirror direction R or the dominant direction (options.split_sum_lookup); the chain and the DFG
      // table read by the kernels of game_ibl.sl (the text the exported shaders run).
      const kernel::IblBinding bind(m_ibl_texels);
      kernel::SplitSumMaterial m = split->material;
      m.roughness = ggx_chain_roughness(m.roughness);  // NaN reads as 0
      if (m_options.split_sum_lookup == GameSplitSumLookup::filtered) {
        // Each part averaged over its own lobe by taps of the same chain (envmap/split_sum_taps.h).
        const double mu = std::isfinite(wo.z) ? std::clamp(wo.z, 0.0, 1.0) : 0.0;
        const kernel::DfgScaleBias ab = kernel::dfg_read(mu, m.roughness, m_dfg->size);
        const SplitSumReads reads =
            split_sum_filtered_reads(m_baked->specular_ggx, sf.frame, wo, m.roughness, m_options.split_sum_taps);
        const Rgb spec(kernel::game_split_sum_specular_lobes(reads.a, reads.b, m.f0, m.f90, ab.a, ab.b));
        l += Rgb(kernel::split_sum_energy_terms(spec, m, ab.a + ab.b, e_over_pi));
      } else {
        // The DFG read, the lookup (mirror, dominant or lobes), the chain reads, prefiltered (f0 A + f90 B) and
        // the model's energy terms: the kernel text game_split_sum_shade, which the exported shaders run.
        l += Rgb(kernel::game_split_sum_shade(sf.frame.n, wo_world, m, e_over_pi, static_cast<int>(m_options.split_sum_lookup),
                                              m_ibl_texels.cube_count, m_chain_texels->mapping, m_ibl_texels.dfg_size,
                                              m_ibl_texels.lobe_size));
      }
    } else if (m_env.has_light()) {
      const Vec3 n = sf.frame.n;
      if (m_options.specular_ambient && info.exponent > 0.0 && m_baked != nullptr && !m_baked->specular.levels.empty()) {
        double n_phong = info.exponent;
        const Material& m = m_scene.materials[static_cast<std::size_t>(hit.material)];
        if (!m.param_textures.empty()) n_phong = f->game_phong_exponent();  // the hit's textured roughness
        if (m.gloss_texture >= 0) {
          const Vec2 uv{hit.uv.x * m.uv_scale.x, hit.uv.y * m.uv_scale.y};
          const double g = sample_texture(m_scene.textures[static_cast<std::size_t>(m.gloss_texture)], uv).r;
          const double n_tex = m.gloss_encoding.exponent_from_gloss(g);
          n_phong = info.blinn_like ? phong_exponent_from_blinn_phong(n_tex) : n_tex;
        }
        if (m.metallic_roughness_texture >= 0) {  // glTF: roughness = factor x green (materials.cpp)
          const Vec2 uv{hit.uv.x * m.uv_scale.x, hit.uv.y * m.uv_scale.y};
          const double g = sample_texture(m_scene.textures[static_cast<std::size_t>(m.metallic_roughness_texture)], uv).g;
          n_phong = phong_exponent_from_alpha(std::clamp(info.roughness_factor * g, 0.01, 1.0));
        }
        // The specular ambient of kernels/game_ambient.sl: rho_s(cos theta_o) x prefiltered(R, n).
        const Vec3 r = kernel::game_reflect(wo_world, n);
        const Rgb rho_s = kernel::game_specular_albedo(m_albedo_tables[static_cast<std::size_t>(hit.material)], wo.z);
        l += kernel::game_specular_ambient(rho_s, prefiltered(r, n_phong));
      }
    }
    return l;
  }

 private:
  // The prefiltered radiance for a Phong exponent: the chain's level for it (kernels/game_ambient.sl, the
  // gloss mapping of prefilter.h inverted), linear between levels.
  Rgb prefiltered(const Vec3& r, double n) const {
    const auto levels = static_cast<int>(m_baked->specular.levels.size());
    const PrefilterOptions po;
    const double level = kernel::game_prefiltered_level(n, levels, po.gloss_scale, po.gloss_bias);
    const int i0 = static_cast<int>(level);
    const int i1 = std::min(i0 + 1, levels - 1);
    const double t = level - i0;
    return m_baked->specular.levels[static_cast<std::size_t>(i0)].sample(r) * (1.0 - t) +
           m_baked->specular.levels[static_cast<std::size_t>(i1)].sample(r) * t;
  }

  const Scene& m_scene;
  GameOptions m_options;
  Accelerator m_accel;
  EnvironmentLight m_env;
  MaterialSet m_materials;
  std::vector<SceneLight> m_punctual;
  Sh9 m_sh;
  Sh9 m_sh_lights;  // directional lights added D3DX-style (game_sh)
  bool m_has_sh_lights = false;
  const GameEnvironment* m_baked = nullptr;  // the caller's bake, or m_owned
  GameEnvironment m_owned;
  const DfgTable* m_dfg = nullptr;
  const SplitSumLobeTable* m_lobes = nullptr;  // the lobe-matched lookup's table (split_sum_lookup lobes)
  std::optional<GgxChainTexels> m_chain_texels;  // the GGX chain's levels for the kernels' fetches
  kernel::IblTexels m_ibl_texels;                // those and the DFG table, bound per pixel
  std::vector<bool> m_split_sum;  // per material: the split-sum specular ambient
  std::vector<GameLobe> m_info;
  std::vector<kernel::GameSpecularAlbedo> m_albedo_tables;
};

// The environment's mean radiance over texel (x, y) of face f of an n x n cube: ss x ss directions at the
// centres of a regular grid over the texel, each weighted by its solid angle, d omega = da db / (1 + a^2 +
// b^2)^(3/2) with (a, b) = (2s - 1, 2t - 1) the point on the face plane (the texel solid angle's integrand,
// envmap/cubemap.h). ss = 1 is the texel centre's radiance.
Rgb texel_mean(const EnvironmentLight& env, int f, int x, int y, int n, int ss) {
  if (ss <= 1) return env.radiance_without_sun(texel_direction(f, x, y, n));
  Rgb sum;
  double weight = 0.0;
  for (int j = 0; j < ss; ++j) {
    for (int i = 0; i < ss; ++i) {
      const double s = (x + (i + 0.5) / ss) / n;
      const double t = (y + (j + 0.5) / ss) / n;
      const double a = 2.0 * s - 1.0;
      const double b = 2.0 * t - 1.0;
      const double q = 1.0 + a * a + b * b;
      const double w = 1.0 / (q * std::sqrt(q));
      sum += env.radiance_without_sun(cube_direction(f, s, t)) * w;
      weight += w;
    }
  }
  return sum / weight;
}

// The environment resampled to an n x n cube (header: texel means, options.environment_supersample).
CubeMap environment_cube(const EnvironmentLight& env, int n, int ss) {
  CubeMap cube(n);
  tbb::parallel_for(tbb::blocked_range<int>(0, 6 * n), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row != r.end(); ++row) {
      const int f = row / n;
      const int y = row % n;
      for (int x = 0; x < n; ++x) cube.set(f, x, y, texel_mean(env, f, x, y, n, ss));
    }
  });
  return cube;
}

}  // namespace

Result<GameEnvironment> bake_game_environment(const EnvironmentLight& env, const GameOptions& options) {
  GameEnvironment out;
  if (!env.has_light()) return out;
  out.has_light = true;
  if (options.environment_supersample < 1 || options.environment_supersample > 32) {
    return make_error("environment_supersample must be in [1, 32]");
  }
  const int n = options.environment_size;
  CubeMap cube = environment_cube(env, n, options.environment_supersample);
  out.sh = project_sh9(cube);
  if (options.diffuse == GameAmbient::irradiance_map) out.irradiance = irradiance_cube(cube, 32, RadianceUnits::game);
  if (options.specular_ambient) {
    PrefilterOptions po;
    po.size = options.specular_size;
    auto chain = prefilter_specular(cube, po);
    if (!chain) return chain.error();
    out.specular = std::move(chain).value();
    if (options.ggx_specular == GameGgxSpecular::split_sum) {
      if (options.ggx_samples < 1 || options.ggx_samples > (1 << 20)) return make_error("ggx_samples must be in [1, 1048576]");
      // Level 0 (r = 0) is the environment resampled as above at the chain's size, options.specular_size.
      const int m = options.specular_size;
      const CubeMap base = m == n ? cube : environment_cube(env, m, options.environment_supersample);
      GgxPrefilterOptions go;
      go.method = options.ggx_method;
      go.samples = options.ggx_samples;
      try {
        out.specular_ggx = prefilter_ggx(base, go);
      } catch (const std::invalid_argument& e) {
        return make_error(std::string("GGX prefilter: ") + e.what());
      }
    }
  }
  out.radiance = std::move(cube);
  return out;
}

const char* game_specular_ambient_name(GameSpecularAmbient a) {
  switch (a) {
    case GameSpecularAmbient::split_sum: return "split-sum";
    case GameSpecularAmbient::phong_chain: return "phong-chain";
    case GameSpecularAmbient::none: break;
  }
  return "none";
}

Result<std::vector<GameSpecularAmbient>> game_specular_ambients(const Scene& scene, const GameOptions& options) {
  MaterialSet materials;
  if (auto ok = materials.prepare(scene); !ok) return ok.error();
  const bool lit = EnvironmentLight(scene).has_light() && options.specular_ambient;
  std::vector<GameSpecularAmbient> out;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    BrdfPtr holder;
    const Brdf* f = materials.brdf(static_cast<int>(i), {0.5, 0.5}, holder);
    GameSpecularAmbient a = GameSpecularAmbient::none;
    if (lit && f != nullptr) {
      // The same choice GameShader::prepare makes (split sum) and shade makes (a Phong exponent above 0).
      if (options.ggx_specular == GameGgxSpecular::split_sum && f->split_sum_inputs()) {
        a = GameSpecularAmbient::split_sum;
      } else if (f->game_phong_exponent() > 0.0) {
        a = GameSpecularAmbient::phong_chain;
      }
    }
    out.push_back(a);
  }
  return out;
}

const DfgTable& game_dfg_table(int size) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<const DfgTable>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& slot = tables[size];
  if (!slot) {
    DfgOptions o;
    o.size = size;
    o.tolerance = 1e-5;
    slot = std::make_unique<const DfgTable>(bake_dfg(o));
  }
  return *slot;
}

Result<GameEnvironment> bake_game_environment(const Scene& scene, const GameOptions& options) {
  const EnvironmentLight env(scene);
  return bake_game_environment(env, options);
}

namespace {

Result<RenderResult> render_game_with(const Scene& scene, const GameOptions& options, const GameEnvironment* baked) {
  const auto t0 = std::chrono::steady_clock::now();
  if (auto limits = check_scene_limits(scene); !limits) return limits.error();
  GameShader shader(scene, options, baked);
  if (auto ok = shader.prepare(); !ok) return ok.error();
  const auto cancelled = [&] { return options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed); };
  const int w = scene.camera.width;
  const int h = scene.camera.height;
  const CameraModel camera(scene.camera);
  const int spp_side = std::max(1, static_cast<int>(std::lround(std::sqrt(std::max(1, options.spp)))));
  RenderResult result;
  result.beauty = Image(w, h);
  const int threads = options.threads >= 0 ? options.threads : scene.settings.threads;
  tbb::task_arena arena(arena_threads(threads));
  std::atomic<std::uint64_t> nonfinite{0};
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range2d<int>(0, h, 16, 0, w, 16), [&](const tbb::blocked_range2d<int>& r) {
      if (cancelled()) return;
      for (int y = r.rows().begin(); y != r.rows().end(); ++y) {
        for (int x = r.cols().begin(); x != r.cols().end(); ++x) {
          Rgb sum;
          // Stratified, deterministic antialiasing: spp_side^2 sub-pixel positions.
          for (int j = 0; j < spp_side; ++j) {
            for (int i = 0; i < spp_side; ++i) {
              const double px = x + (i + 0.5) / spp_side;
              const double py = y + (j + 0.5) / spp_side;
              const Rgb l = shader.shade(camera.ray(px, py));
              if (!is_finite(l)) nonfinite.fetch_add(1, std::memory_order_relaxed);
              sum += l;
            }
          }
          result.beauty.set(x, y, sum / (spp_side * spp_side));
        }
      }
    });
  });
  result.stats.spp_done = spp_side * spp_side;
  result.stats.cancelled = cancelled();
  result.stats.nonfinite_samples = nonfinite.load();
  result.stats.camera_rays = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) * static_cast<std::uint64_t>(spp_side * spp_side);
  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace

Result<RenderResult> render_game(const Scene& scene, const GameOptions& options) {
  return render_game_with(scene, options, nullptr);
}

Result<RenderResult> render_game(const Scene& scene, const GameOptions& options, const GameEnvironment& baked) {
  return render_game_with(scene, options, &baked);
}

Result<Rgb> game_radiance(const Scene& scene, const Vec3& origin, const Vec3& direction, const GameOptions& options) {
  GameShader shader(scene, options, nullptr);
  if (auto ok = shader.prepare(); !ok) return ok.error();
  return shader.shade(Ray{origin, normalize(direction)});
}

}  // namespace shadelab
