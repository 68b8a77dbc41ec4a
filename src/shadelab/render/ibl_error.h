// shadelab IBL error maps: how far the engine-side shortcuts of image-based lighting are from the truth, as
// a function of roughness and N.V (issue 11, section 5).
//
// For an environment (any Environment of a scene: a lat-long image, a uniform radiance, a sky), a unit sphere
// of the given material at the origin, lit by the environment alone (no other geometry: a convex sphere
// cannot shadow or see itself, so one bounce is the whole light transport), is rendered twice per roughness:
// - the reference: the path tracer (render_scene, max_depth 1, MIS), `spp` samples a pixel;
// - the shortcut: the game renderer's split sum (render_game, GameGgxSpecular::split_sum, no diffuse
//   ambient, no punctual light but a sky's sun, which game shading takes out of the environment and shades
//   per pixel, unshadowed: a sphere cannot shadow itself): prefiltered_ggx(R, r) (f0 A + f90 B), docs/renderer.md, read along the
//   mirror direction R as Karis 2013 publishes it (GameSplitSumLookup::mirror);
// - the corrected shortcut: the same chain and table read as options.correction says: by default each part
//   (f0 A, f90 B) along and at the roughness that match its true lobe's first moments
//   (GameSplitSumLookup::lobes, envmap/specular/split_sum_lobes.h), along the dominant direction
//   normalize(mix(R, n, alpha^2)) (GameSplitSumLookup::dominant, kernels/game_ambient.sl), or each part the
//   mean of game.split_sum_taps reads over its own lobe (GameSplitSumLookup::filtered,
//   envmap/specular/split_sum_taps.h); the same storage.
// The environment is baked once (bake_game_environment) for all the game renders of a map.
// The camera looks at the sphere from `view_direction` (default +Z, along the horizon) through a narrow
// field of view (distance 20, the sphere filling the frame), so each pixel's N.V is that of its centre ray
// (CameraModel), and pixels are grouped into `nv_bins` equal bins of N.V over (0, 1] by the N.V of their
// centre; a pixel whose footprint may cross the silhouette (its centre within 0.75 pixels of the rim) is
// left out. Both renderers average a pixel over the same footprint, so pixels compare like for like; near
// the rim one pixel spans a range of N.V (N.V < 0.3 is the outer 4.6% of the disk's radius: about 4 pixels
// at size 192), so the grazing bins need a large size. Per bin, the mean
// luminance (Rec. 709) of each image over the bin's pixels, and
//   error = (shortcut - reference) / reference
// of those means (bins, not pixels: the reference's noise averages out; its standard error is reported).
// The same for the diffuse shortcut: a white Lambert sphere (kd = 1) under GameAmbient::sh9 (the SH9
// irradiance, Ramamoorthi & Hanrahan 2001) against the path tracer.
// A cell with no signal: its reference is <= 0, or at most ibl_error_no_signal_fraction of the mean reference
// of its map's cells (the split-sum rows together, which the corrected rows share; the SH row alone); its
// relative error means nothing, so it is flagged (no_signal), its error left 0 and it is left out of the
// summary figures, which count it (no_signal_cells). A map in which no cell has signal is an Error, and so is
// an image environment whose texels are all 0 (found before any render).
// Summary figures: the mean and the largest |error| over the cells with signal, and the mean |error| over
// those with N.V below 0.3 (the grazing bins: their upper edge <= 0.3 + 1e-12).
// Deterministic: the renders are (seeded, any thread count).
// Errors (Result): a model whose specular ambient is not the split sum (only ggx and filament), an empty or
// out-of-range roughness list (each in (0, 1]), nv_bins outside [1, 64], size outside [16, 2048], spp
// outside [1, 65536], a zero view direction, or a scene without an environment.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shadelab/core/error.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/scene/scene.h"

namespace shadelab {

// A cell whose reference is at most this share of the map's mean reference has no signal (above).
inline constexpr double ibl_error_no_signal_fraction = 1e-6;

struct IblErrorOptions {
  std::vector<double> roughness{0.1, 0.25, 0.4, 0.55, 0.7, 0.85, 1.0};  // perceptual roughness of the rows
  int nv_bins = 8;
  int size = 192;   // pixels across each sphere image
  int spp = 256;    // path-traced samples per pixel of the reference
  std::uint64_t seed = 7;
  int threads = 0;  // 0: all cores
  Vec3 view_direction{0.0, 0.0, 1.0};  // from the sphere toward the camera
  GameOptions game;  // the shortcut's options; ggx_specular, diffuse, punctual, split_sum_lookup set per map
  // The corrected map's lookup: the lobe-matched reads (default), the dominant direction or the filtered taps
  // (game.split_sum_taps of them).
  GameSplitSumLookup correction = GameSplitSumLookup::lobes;
};

struct IblErrorCell {
  double nv_lo = 0.0, nv_hi = 0.0;  // the bin
  int pixels = 0;
  double shortcut = 0.0;            // mean luminance of the game renderer's pixels
  double reference = 0.0;           // mean luminance of the path tracer's pixels
  double reference_standard_error = 0.0;  // of that mean, from the spread of the bin's pixels
  double error = 0.0;               // (shortcut - reference) / reference; 0 when no_signal
  bool no_signal = false;           // pixels > 0 but the reference is too small to divide by (header)
};

struct IblErrorRow {
  double roughness = 0.0;  // perceptual; the Lambert row of the SH map has 0 here
  std::vector<IblErrorCell> cells;
};

struct IblErrorSummary {
  double mean_abs = 0.0;          // over every cell with pixels
  double max_abs = 0.0;
  double grazing_mean_abs = 0.0;  // over the cells with nv_hi <= 0.3
  int no_signal_cells = 0;        // cells with pixels left out because they have no signal
  int signal_cells = 0;           // cells the figures are over
};

struct IblErrorMap {
  std::string model;
  std::vector<IblErrorRow> split_sum;  // one row per roughness, read along R
  IblErrorSummary split_sum_summary;
  std::vector<IblErrorRow> corrected;  // the same rows read as `correction` says
  GameSplitSumLookup correction = GameSplitSumLookup::lobes;
  int taps = 0;  // correction filtered: options.game.split_sum_taps (0 otherwise)
  IblErrorSummary corrected_summary;
  // 1 - corrected.grazing_mean_abs / split_sum.grazing_mean_abs (0 when the latter is 0): the share of the
  // grazing error the correction removes (issue 11 asks for >= 0.25).
  double grazing_reduction = 0.0;
  IblErrorRow sh;                      // the Lambert sphere, SH9 irradiance against the path tracer
  IblErrorSummary sh_summary;
  double seconds = 0.0;
};

// The maps above for `model` with `params` under scene.environment (the rest of `scene` is ignored). The
// roughness parameter is set per row ("roughness" for ggx, "perceptual_roughness" for filament), and the
// split-sum map is of the specular lobe alone: ggx's kd is 0 and filament's metallic 1 (a metal has no
// diffuse lobe); giving either is an error. The diffuse shortcut is the SH map's.
Result<IblErrorMap> ibl_error_map(const Scene& scene, const std::string& model, const ParamAssignments& params,
                                  const IblErrorOptions& options = {});

// What a correction is, in one line (the JSON's corrected.direction, the page).
std::string split_sum_correction_text(GameSplitSumLookup correction);

// Flags the cells of rows (one map) that have no signal (header); returns how many cells have signal.
int mark_no_signal_cells(std::vector<IblErrorRow>& rows);

// The summary figures of a set of rows (what ibl_error_map fills in); cells with no signal are counted, not
// averaged.
IblErrorSummary summarize_ibl_error(const std::vector<IblErrorRow>& rows);

}  // namespace shadelab
