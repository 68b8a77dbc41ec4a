// shadelab image metrics: how far image A is from image B (the reference), in numbers and in pictures.
//
// Contract (details, sources and advice in docs/compare.md):
// - Both images are linear RGB (image.h) of the same size; B is the reference. Different sizes, an empty
//   image and a non-finite value are Errors whose one-line message names the image (CompareOptions::name_a,
//   name_b: the CLI passes the file names) and, for a non-finite value, the pixel.
// - N = width * height pixels, 3N channel values a_i, b_i. Sums are taken in double, row by row, so the same
//   images give the same figures on every run.
//     mse              = (1 / 3N) sum_i (a_i - b_i)^2
//     rmse             = sqrt(mse)
//     relative_mse     = (1 / 3N) sum_i (a_i - b_i)^2 / (b_i^2 + eps), eps = 0.01 (the reference B in the
//                        denominator; Rousselle, Knaus, Zwicker 2011, "Adaptive Sampling and Reconstruction
//                        using Greedy Error Minimization", ACM TOG 30(6))
//     max_abs_error    = max_i |a_i - b_i|, at (max_x, max_y) in channel max_channel (0 R, 1 G, 2 B); the
//                        first in row-major order, R before G before B, when several tie
//     mean_luminance_X = (1 / N) sum_p Y(X_p), Y = 0.2126 R + 0.7152 G + 0.0722 B (ITU-R BT.709-6, 3.2)
//     mean_luminance_ratio = mean_luminance_a / mean_luminance_b; 1 when both are 0, NaN when only B's is 0
//     ssim             = mean SSIM (Wang, Bovik, Sheikh, Simoncelli 2004, "Image Quality Assessment: From
//                        Error Visibility to Structural Similarity", IEEE TIP 13(4), eq. 13 per window and
//                        eq. 17 for the mean) over every 11 x 11 window that lies wholly inside the image, with
//                        the normalised Gaussian weights of sigma 1.5, K1 = 0.01, K2 = 0.03, L = 1, computed on
//                        the display value V = sRGB_encode(clamp(2^EV * Y, 0, 1)) of each pixel's luminance
//                        (EV = CompareOptions::exposure_stops). NaN, with ssim_windows = 0, when the image is
//                        smaller than 11 x 11.
// - The heat map shows a per-pixel error e (ErrorMetric) through a ramp from black to white (heat_ramp):
//   t = e / scale clamped to [0, 1], the scale given or the 99th percentile of e. It has the images' size.
//   The side-by-side image is A | B | heat map.
// - Nothing prints; nothing throws.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "shadelab/color/rgb.h"
#include "shadelab/core/error.h"
#include "shadelab/image/image.h"

namespace shadelab {

// eps in the relative MSE's denominator b^2 + eps (docs/compare.md: papers also use 1e-3; quote it).
inline constexpr double default_relative_mse_epsilon = 0.01;

// SSIM constants of Wang et al. 2004 (section III.C and the authors' reference implementation).
inline constexpr int ssim_window = 11;       // window side, pixels
inline constexpr double ssim_sigma = 1.5;    // Gaussian standard deviation, pixels
inline constexpr double ssim_k1 = 0.01;      // C1 = (K1 L)^2
inline constexpr double ssim_k2 = 0.03;      // C2 = (K2 L)^2
inline constexpr double ssim_range = 1.0;    // L: the dynamic range of the display value V

// Per-pixel error drawn by the heat map.
enum class ErrorMetric {
  absolute,  // e = max_c |a_c - b_c|: its largest value is max_abs_error
  relative,  // e = max_c |a_c - b_c| / sqrt(b_c^2 + eps): the square root of the relative MSE's term (default)
};

struct CompareOptions {
  std::string name_a = "A";  // how errors name the images
  std::string name_b = "B";
  double relative_mse_epsilon = default_relative_mse_epsilon;
  double exposure_stops = 0.0;  // SSIM's display transform and the side-by-side's A and B panels
  ErrorMetric heatmap_metric = ErrorMetric::relative;
  double heatmap_scale = 0.0;  // the error drawn white; 0: automatic (Heatmap::scale)
};

struct ImageDifference {
  int width = 0;
  int height = 0;
  double mse = 0.0;
  double rmse = 0.0;
  double relative_mse = 0.0;
  double relative_mse_epsilon = default_relative_mse_epsilon;
  double max_abs_error = 0.0;
  int max_x = 0;
  int max_y = 0;
  int max_channel = 0;  // 0 R, 1 G, 2 B
  double mean_luminance_a = 0.0;
  double mean_luminance_b = 0.0;
  double mean_luminance_ratio = 1.0;
  double ssim = 1.0;
  long long ssim_windows = 0;  // windows averaged: (width - 10) * (height - 10), or 0
  double ssim_exposure_stops = 0.0;
};

// A single-channel image of doubles, row-major, row 0 at the top.
struct Plane {
  int width = 0;
  int height = 0;
  std::vector<double> values;

  double at(int x, int y) const {
    return values[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  }
};

// OK when a and b are valid, non-empty, of the same size and finite; else the Error that compare_images gives.
Result<bool> check_comparable(const Image& a, const Image& b, const CompareOptions& options = {});

// Every figure above. B is the reference.
Result<ImageDifference> compare_images(const Image& a, const Image& b, const CompareOptions& options = {});

// The 11 one-dimensional Gaussian weights of the SSIM window, normalised to sum 1; the 2D weight of offset
// (i, j) is w[i] * w[j].
const std::vector<double>& ssim_weights();

// SSIM's input: V = sRGB_encode(clamp(2^exposure * Y, 0, 1)) per pixel, Y the Rec.709 luminance.
Plane ssim_display_plane(const Image& image, double exposure_stops);

// The SSIM of every 11 x 11 window wholly inside x and y (same size): a (width - 10) x (height - 10) plane
// whose (i, j) is the window centred on pixel (i + 5, j + 5). Empty when smaller than 11 x 11 or the sizes
// differ.
Plane ssim_map(const Plane& x, const Plane& y);

// The mean of ssim_map (Wang et al. eq. 17); NaN when the map is empty.
double mean_ssim(const Plane& x, const Plane& y);

// The heat map's per-pixel error e of pixel a against reference pixel b.
double pixel_error(const Rgb& a, const Rgb& b, ErrorMetric metric, double epsilon = default_relative_mse_epsilon);

// The heat map's colour ramp at t in [0, 1] (clamped; NaN is 0), as linear RGB ready for write_image. It is
// Green's cubehelix (D. A. Green 2011, "A colour scheme for the display of astronomical intensity images",
// Bull. Astr. Soc. India 39, 289) with start 0.25, rotations 0.45, hue 2.2, gamma 1: black, purple, red,
// orange, yellow, white, its brightness rising steadily; each encoded channel is clamped to [0, 1] and
// decoded from sRGB.
Rgb heat_ramp(double t);

// The automatic heat-map scale is this percentile of the per-pixel errors.
inline constexpr double heatmap_auto_percentile = 0.99;

struct Heatmap {
  Image image;                    // the images' size; linear RGB of heat_ramp(e / scale)
  double scale = 1.0;             // the error drawn white: CompareOptions::heatmap_scale, or automatic: the 99th
                                  // percentile of e, else (when that is 0) the largest e, else 1
  double max_error = 0.0;         // the largest per-pixel error e
  double percentile_error = 0.0;  // the 99th percentile of e (automatic scale only; 0 otherwise)
};

// The heat map of A against the reference B (options: metric, scale, eps, names).
Result<Heatmap> error_heatmap(const Image& a, const Image& b, const CompareOptions& options = {});

// Pixels of neutral grey between the side-by-side's panels.
inline constexpr int side_by_side_gap = 4;

// A | B | heat map in one image of (3 width + 2 gap) x height: A and B multiplied by 2^exposure_stops (write
// it with exposure 0), the heat map as it is, the gaps grey. All three must have the same size.
Result<Image> side_by_side(const Image& a, const Image& b, const Image& heatmap, const CompareOptions& options = {});

}  // namespace shadelab
