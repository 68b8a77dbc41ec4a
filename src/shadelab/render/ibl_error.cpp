// shadelab IBL error maps (ibl_error.h): path tracer against the game renderer's split sum and SH9 ambient,
// per roughness and N.V bin.
#include "shadelab/render/ibl_error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "shadelab/brdf/registry.h"
#include "shadelab/color/rgb.h"
#include "shadelab/core/text.h"
#include "shadelab/render/camera_model.h"
#include "shadelab/render/path_tracer.h"

namespace shadelab {

namespace {

constexpr double camera_distance = 20.0;

// The scene of one sphere of (model, params) under the environment, seen from view_direction.
Scene sphere_scene(const Scene& base, const std::string& model, ParamAssignments params, const IblErrorOptions& o) {
  Scene s;
  s.source = base.source;
  s.environment = base.environment;
  Material m;
  m.name = model;
  m.model = model;
  m.params = std::move(params);
  s.materials.push_back(std::move(m));
  s.spheres.push_back({{0.0, 0.0, 0.0}, 1.0, 0});
  const Vec3 v = normalize(o.view_direction);
  s.camera.position = v * camera_distance;
  s.camera.look_at = {0.0, 0.0, 0.0};
  // Any up that is not along the view: +Y unless the view is (nearly) vertical.
  s.camera.up = std::abs(v.y) > 0.99 ? Vec3{0.0, 0.0, 1.0} : Vec3{0.0, 1.0, 0.0};
  // The sphere's angular radius asin(1/d), and a 2% margin.
  s.camera.vfov_deg = 2.0 * rad_to_deg(std::asin(1.0 / camera_distance)) * 1.02;
  s.camera.width = o.size;
  s.camera.height = o.size;
  s.settings.max_depth = 1;
  s.settings.spp = o.spp;
  s.settings.seed = o.seed;
  s.settings.threads = o.threads;
  s.settings.rr_depth = 0;
  return s;
}

// Per bin: sums of the two images' luminance over the pixels whose centre ray meets the sphere at N.V in
// the bin, away from the rim.
IblErrorRow bin_images(const Scene& s, const Image& shortcut, const Image& reference, int bins, double roughness) {
  const CameraModel camera(s.camera);
  IblErrorRow row;
  row.roughness = roughness;
  std::vector<double> sum_s(static_cast<std::size_t>(bins), 0.0), sum_r(sum_s), sum_r2(sum_s);
  std::vector<int> count(static_cast<std::size_t>(bins), 0);
  // Angular size of a pixel against the sphere's angular radius: a pixel whose centre is within 0.75 of
  // them of the rim is left out (its footprint, half a diagonal = 0.71 pixels around the centre, may reach
  // the background). The others are compared pixel for pixel: both renderers average over the same footprint.
  const double pixel_angle = 2.0 * camera.tan_half / s.camera.height;
  const double rim = std::asin(1.0 / camera_distance);
  for (int y = 0; y < s.camera.height; ++y) {
    for (int x = 0; x < s.camera.width; ++x) {
      const Ray r = camera.ray(x + 0.5, y + 0.5);
      // The unit sphere at the origin: |o + t d| = 1, the nearer root.
      const double b = dot(r.origin, r.direction);
      const double c = dot(r.origin, r.origin) - 1.0;
      const double disc = b * b - c;
      if (disc <= 0.0) continue;
      const double off_axis = std::acos(std::clamp(dot(r.direction, -normalize(r.origin)), -1.0, 1.0));
      if (off_axis > rim - 0.75 * pixel_angle) continue;
      const double t = -b - std::sqrt(disc);
      const Vec3 n = normalize(r.origin + r.direction * t);
      const double nv = -dot(n, r.direction);
      if (!(nv > 0.0)) continue;
      const int k = std::min(bins - 1, static_cast<int>(nv * bins));
      const double ls = luminance(shortcut.at(x, y));
      const double lr = luminance(reference.at(x, y));
      const auto kk = static_cast<std::size_t>(k);
      sum_s[kk] += ls;
      sum_r[kk] += lr;
      sum_r2[kk] += lr * lr;
      ++count[kk];
    }
  }
  for (int k = 0; k < bins; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    IblErrorCell cell;
    cell.nv_lo = static_cast<double>(k) / bins;
    cell.nv_hi = static_cast<double>(k + 1) / bins;
    cell.pixels = count[kk];
    if (cell.pixels > 0) {
      const double n = cell.pixels;
      cell.shortcut = sum_s[kk] / n;
      cell.reference = sum_r[kk] / n;
      const double var = std::max(0.0, sum_r2[kk] / n - cell.reference * cell.reference);
      cell.reference_standard_error = n > 1 ? std::sqrt(var / (n - 1.0)) : 0.0;
      cell.error = cell.reference > 0.0 ? (cell.shortcut - cell.reference) / cell.reference : 0.0;
    }
    row.cells.push_back(cell);
  }
  return row;
}

Result<Image> reference_image(const Scene& s) {
  RenderOptions ro;
  ro.mode = SamplingMode::mis;
  auto r = render_scene(s, ro);
  if (!r) return r.error();
  if (r->stats.nonfinite_samples > 0) return make_error("ibl-error: the reference render had non-finite samples");
  return std::move(r->beauty);
}

Result<Image> shortcut_image(const Scene& s, GameOptions g, const GameEnvironment& baked) {
  // The sphere scene has no lights: the only punctual light is a sky's sun, which the game renderer shades
  // per pixel (and bakes out of the environment), as the path tracer sees it in the sky.
  g.punctual = true;
  g.shadows = false;
  g.threads = s.settings.threads;
  auto r = render_game(s, g, baked);
  if (!r) return r.error();
  if (r->stats.nonfinite_samples > 0) return make_error("ibl-error: the game render had non-finite samples");
  return std::move(r->beauty);
}

}  // namespace

std::string split_sum_correction_text(GameSplitSumLookup correction) {
  switch (correction) {
    case GameSplitSumLookup::mirror: return "mirror: R, uncorrected";
    case GameSplitSumLookup::dominant: return "dominant: normalize(mix(R, n, alpha^2)), alpha = roughness^2";
    case GameSplitSumLookup::lobes:
      return "lobes: f0 A read along and at the roughness of the A lobe's first moments, f90 B of the B lobe's "
             "(envmap/specular/split_sum_lobes.h)";
    case GameSplitSumLookup::filtered:
      return "filtered: f0 A and f90 B each the mean of its own lobe over taps of the chain, each read with its "
             "share of solid angle (envmap/specular/split_sum_taps.h)";
  }
  return "";
}

int mark_no_signal_cells(std::vector<IblErrorRow>& rows) {
  double sum = 0.0;
  int n = 0;
  for (const IblErrorRow& row : rows) {
    for (const IblErrorCell& c : row.cells) {
      if (c.pixels == 0) continue;
      sum += std::max(0.0, c.reference);
      ++n;
    }
  }
  // The threshold is relative to the map's own mean, so the map's units do not matter; a reference <= 0
  // never has signal (the division would flip or explode).
  const double threshold = n > 0 ? ibl_error_no_signal_fraction * (sum / n) : 0.0;
  int signal = 0;
  for (IblErrorRow& row : rows) {
    for (IblErrorCell& c : row.cells) {
      if (c.pixels == 0) continue;
      c.no_signal = !(c.reference > 0.0 && c.reference > threshold);
      if (c.no_signal) {
        c.error = 0.0;
      } else {
        ++signal;
      }
    }
  }
  return signal;
}

IblErrorSummary summarize_ibl_error(const std::vector<IblErrorRow>& rows) {
  IblErrorSummary s;
  int n = 0, g = 0;
  for (const IblErrorRow& row : rows) {
    for (const IblErrorCell& c : row.cells) {
      if (c.pixels == 0) continue;
      if (c.no_signal) {
        ++s.no_signal_cells;
        continue;
      }
      const double e = std::abs(c.error);
      s.mean_abs += e;
      s.max_abs = std::max(s.max_abs, e);
      ++n;
      if (c.nv_hi <= 0.3 + 1e-12) {
        s.grazing_mean_abs += e;
        ++g;
      }
    }
  }
  s.signal_cells = n;
  if (n > 0) s.mean_abs /= n;
  if (g > 0) s.grazing_mean_abs /= g;
  return s;
}

Result<IblErrorMap> ibl_error_map(const Scene& scene, const std::string& model, const ParamAssignments& params,
                                  const IblErrorOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  // The specular lobe alone (header): the parameter that would add a diffuse lobe is fixed.
  const ModelInfo* info = find_brdf_model(model);
  if (info == nullptr || !info->split_sum_sweep) {
    return make_error("ibl-error: model '" + printable(model) + "' has no split-sum specular ambient (" +
                      split_sum_model_names() + ")");
  }
  const std::string roughness_param = info->split_sum_sweep->roughness_param;
  const std::pair<std::string, std::string> fixed{info->split_sum_sweep->specular_only_param,
                                                  info->split_sum_sweep->specular_only_value};
  if (o.roughness.empty()) return make_error("ibl-error: roughness: the list is empty");
  for (const double r : o.roughness) {
    if (!(r > 0.0 && r <= 1.0)) return make_error("ibl-error: roughness: " + std::to_string(r) + " is not in (0, 1]");
  }
  if (o.nv_bins < 1 || o.nv_bins > 64) return make_error("ibl-error: nv_bins must be in [1, 64]");
  if (o.size < 16 || o.size > 2048) return make_error("ibl-error: size must be in [16, 2048]");
  if (o.spp < 1 || o.spp > 65536) return make_error("ibl-error: spp must be in [1, 65536]");
  const Vec3 v = o.view_direction;
  if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) || dot(v, v) < 1e-24) {
    return make_error("ibl-error: view_direction must be a finite non-zero vector");
  }
  if (scene.environment.kind == Environment::Kind::none) return make_error("ibl-error: the scene has no environment");
  const auto source = [&] { return "'" + printable(scene.environment.source) + "'"; };
  if (scene.environment.kind == Environment::Kind::image) {
    // Before any render: a black map has no signal anywhere (the cells would all be refused below).
    const auto& d = scene.environment.latlong.data;
    if (std::none_of(d.begin(), d.end(), [](float t) { return t > 0.0f; })) {
      return make_error("ibl-error: " + source() + ": every texel is 0 or less; a black environment gives no signal "
                        "to measure an error against");
    }
  }
  for (const auto& [key, value] : params) {
    if (key == roughness_param) return make_error("ibl-error: " + key + " is set per row (use the roughness list)");
    if (key == fixed.first) {
      return make_error("ibl-error: " + key + " is " + fixed.second + " in the split-sum map (the specular lobe alone; "
                        "the diffuse shortcut is the SH map)");
    }
  }

  IblErrorMap map;
  map.model = model;
  map.correction = o.correction;
  if (o.correction == GameSplitSumLookup::filtered) map.taps = o.game.split_sum_taps;
  GameOptions split = o.game;
  split.ggx_specular = GameGgxSpecular::split_sum;
  split.diffuse = GameAmbient::none;
  split.specular_ambient = true;
  // One bake of the environment for every game render of the map (the SH map's too: the bake always projects
  // SH9, and diffuse none/sh9 bake the same).
  auto baked = bake_game_environment(scene, split);
  if (!baked) return baked.error();
  for (const double r : o.roughness) {
    ParamAssignments p = params;
    p.push_back(fixed);
    p.emplace_back(roughness_param, std::to_string(r));
    const Scene s = sphere_scene(scene, model, p, o);
    auto ref = reference_image(s);
    if (!ref) return ref.error();
    split.split_sum_lookup = GameSplitSumLookup::mirror;
    auto game = shortcut_image(s, split, *baked);
    if (!game) return game.error();
    map.split_sum.push_back(bin_images(s, *game, *ref, o.nv_bins, r));
    split.split_sum_lookup = o.correction;
    auto corrected = shortcut_image(s, split, *baked);
    if (!corrected) return corrected.error();
    map.corrected.push_back(bin_images(s, *corrected, *ref, o.nv_bins, r));
  }
  // The corrected rows share the split-sum rows' references, so they share their flags.
  if (mark_no_signal_cells(map.split_sum) == 0) {
    return make_error("ibl-error: " + source() + ": no cell of the split-sum map has signal (the reference is 0, or "
                      "below 1e-6 of the mean, in every N.V bin)");
  }
  for (std::size_t i = 0; i < map.corrected.size(); ++i) {
    for (std::size_t k = 0; k < map.corrected[i].cells.size(); ++k) {
      IblErrorCell& c = map.corrected[i].cells[k];
      c.no_signal = map.split_sum[i].cells[k].no_signal;
      if (c.no_signal) c.error = 0.0;
    }
  }
  map.split_sum_summary = summarize_ibl_error(map.split_sum);
  map.corrected_summary = summarize_ibl_error(map.corrected);
  map.grazing_reduction = map.split_sum_summary.grazing_mean_abs > 0.0
                              ? 1.0 - map.corrected_summary.grazing_mean_abs / map.split_sum_summary.grazing_mean_abs
                              : 0.0;

  GameOptions sh = o.game;
  sh.diffuse = GameAmbient::sh9;
  sh.specular_ambient = false;
  const Scene s = sphere_scene(scene, "lambert", {{"kd", "1"}}, o);
  auto ref = reference_image(s);
  if (!ref) return ref.error();
  auto game = shortcut_image(s, sh, *baked);
  if (!game) return game.error();
  map.sh = bin_images(s, *game, *ref, o.nv_bins, 0.0);
  std::vector<IblErrorRow> sh_rows{std::move(map.sh)};
  if (mark_no_signal_cells(sh_rows) == 0) {
    return make_error("ibl-error: " + source() + ": no cell of the SH9 map has signal (the reference is 0, or below 1e-6 "
                      "of the mean, in every N.V bin)");
  }
  map.sh = std::move(sh_rows.front());
  map.sh_summary = summarize_ibl_error({map.sh});
  map.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return map;
}

}  // namespace shadelab
