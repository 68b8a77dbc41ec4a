// Image metrics: RMSE, relative MSE, maximum error, mean luminance, SSIM, the error heat map and the
// side-by-side picture. Formulas and sources are in metrics.h and docs/compare.md.
#include "shadelab/image/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <sstream>

#include "shadelab/image/srgb.h"

namespace shadelab {

namespace {

std::string size_text(const Image& image) { return std::to_string(image.width) + " x " + std::to_string(image.height); }

// A double with 6 significant digits, for error messages.
std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The first non-finite value of an image, if any: "(x, y)".
bool find_nonfinite(const Image& image, int& x, int& y) {
  for (std::size_t i = 0; i < image.data.size(); ++i) {
    if (!std::isfinite(image.data[i])) {
      const std::size_t pixel = i / 3;
      x = static_cast<int>(pixel % static_cast<std::size_t>(image.width));
      y = static_cast<int>(pixel / static_cast<std::size_t>(image.width));
      return true;
    }
  }
  return false;
}

Result<bool> check_one(const Image& image, const std::string& name) {
  if (image.empty()) return make_error("compare: " + name + " is empty (" + size_text(image) + ")");
  if (!image.is_valid()) {
    return make_error("compare: " + name + " holds " + std::to_string(image.data.size()) + " floats, not 3 x " +
                      size_text(image));
  }
  int x = 0;
  int y = 0;
  if (find_nonfinite(image, x, y)) {
    return make_error("compare: " + name + " has a NaN or infinite value at pixel (" + std::to_string(x) + ", " +
                      std::to_string(y) + ")");
  }
  return true;
}

// Luminance of a linear Rec.709 pixel stored as floats: ITU-R BT.709-6 item 3.2 (color/rgb.h).
double pixel_luminance(const float* p) {
  return luminance(Rgb{static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])});
}

}  // namespace

Result<bool> check_comparable(const Image& a, const Image& b, const CompareOptions& options) {
  if (auto ok = check_one(a, options.name_a); !ok) return ok;
  if (auto ok = check_one(b, options.name_b); !ok) return ok;
  if (a.width != b.width || a.height != b.height) {
    return make_error("compare: " + options.name_a + " is " + size_text(a) + ", " + options.name_b + " is " + size_text(b) +
                      "; the images must have the same size");
  }
  return true;
}

const std::vector<double>& ssim_weights() {
  static const std::vector<double> weights = [] {
    // Gaussian exp(-k^2 / (2 sigma^2)) for k = -5..5, normalised so the 11 x 11 product window sums to 1
    // (Wang et al. 2004, section III.C).
    std::vector<double> w(static_cast<std::size_t>(ssim_window));
    const int half = ssim_window / 2;
    double sum = 0.0;
    for (int k = -half; k <= half; ++k) {
      const double v = std::exp(-static_cast<double>(k * k) / (2.0 * ssim_sigma * ssim_sigma));
      w[static_cast<std::size_t>(k + half)] = v;
      sum += v;
    }
    for (double& v : w) v /= sum;
    return w;
  }();
  return weights;
}

Plane ssim_display_plane(const Image& image, double exposure_stops) {
  Plane plane;
  plane.width = image.width;
  plane.height = image.height;
  plane.values.resize(image.pixel_count());
  const double gain = std::exp2(exposure_stops);
  for (std::size_t p = 0; p < plane.values.size(); ++p) {
    // V = sRGB_encode(clamp(2^EV Y, 0, 1)): IEC 61966-2-1 encoding of the clamped luminance.
    const double y = std::clamp(gain * pixel_luminance(&image.data[3 * p]), 0.0, 1.0);
    plane.values[p] = linear_to_srgb(y);
  }
  return plane;
}

Plane ssim_map(const Plane& x, const Plane& y) {
  Plane map;
  if (x.width != y.width || x.height != y.height || x.width < ssim_window || x.height < ssim_window) return map;
  const int out_w = x.width - ssim_window + 1;
  const int out_h = x.height - ssim_window + 1;
  map.width = out_w;
  map.height = out_h;
  map.values.resize(static_cast<std::size_t>(out_w) * static_cast<std::size_t>(out_h));
  const std::vector<double>& w = ssim_weights();
  // C1 = (K1 L)^2 and C2 = (K2 L)^2: Wang et al. 2004, section III.B.
  const double c1 = (ssim_k1 * ssim_range) * (ssim_k1 * ssim_range);
  const double c2 = (ssim_k2 * ssim_range) * (ssim_k2 * ssim_range);

  // Separable filtering: each input row is filtered horizontally once into a ring of 11 rows of the five
  // signals x, y, x^2, y^2, xy; an output row is the vertical weighted sum of the ring.
  constexpr int signals = 5;
  const auto row_len = static_cast<std::size_t>(out_w);
  std::vector<double> ring(static_cast<std::size_t>(ssim_window * signals) * row_len);
  auto ring_row = [&](int input_row, int signal) {
    return ring.data() + (static_cast<std::size_t>((input_row % ssim_window) * signals + signal)) * row_len;
  };
  auto filter_row = [&](int r) {
    const double* xr = &x.values[static_cast<std::size_t>(r) * static_cast<std::size_t>(x.width)];
    const double* yr = &y.values[static_cast<std::size_t>(r) * static_cast<std::size_t>(y.width)];
    double* s[signals];
    for (int k = 0; k < signals; ++k) s[k] = ring_row(r, k);
    for (int i = 0; i < out_w; ++i) {
      double mx = 0.0, my = 0.0, mxx = 0.0, myy = 0.0, mxy = 0.0;
      for (int k = 0; k < ssim_window; ++k) {
        const double wk = w[static_cast<std::size_t>(k)];
        const double a = xr[i + k];
        const double b = yr[i + k];
        mx += wk * a;
        my += wk * b;
        mxx += wk * a * a;
        myy += wk * b * b;
        mxy += wk * a * b;
      }
      s[0][i] = mx;
      s[1][i] = my;
      s[2][i] = mxx;
      s[3][i] = myy;
      s[4][i] = mxy;
    }
  };
  for (int r = 0; r < ssim_window - 1; ++r) filter_row(r);
  for (int j = 0; j < out_h; ++j) {
    filter_row(j + ssim_window - 1);
    double* out = &map.values[static_cast<std::size_t>(j) * row_len];
    for (int i = 0; i < out_w; ++i) {
      double m[signals] = {0.0, 0.0, 0.0, 0.0, 0.0};
      for (int k = 0; k < ssim_window; ++k) {
        const double wk = w[static_cast<std::size_t>(k)];
        for (int sgn = 0; sgn < signals; ++sgn) m[sgn] += wk * ring_row(j + k, sgn)[i];
      }
      const double mu_x = m[0];
      const double mu_y = m[1];
      // Weighted (co)variances, Wang et al. eqs. 14-16: sigma^2 = sum w x^2 - mu^2.
      const double var_x = m[2] - mu_x * mu_x;
      const double var_y = m[3] - mu_y * mu_y;
      const double cov = m[4] - mu_x * mu_y;
      // SSIM, Wang et al. eq. 13.
      out[i] = ((2.0 * mu_x * mu_y + c1) * (2.0 * cov + c2)) /
               ((mu_x * mu_x + mu_y * mu_y + c1) * (var_x + var_y + c2));
    }
  }
  return map;
}

double mean_ssim(const Plane& x, const Plane& y) {
  const Plane map = ssim_map(x, y);
  if (map.values.empty()) return std::numeric_limits<double>::quiet_NaN();
  // MSSIM, Wang et al. eq. 17: the mean over the windows (summed row by row).
  double sum = 0.0;
  for (int j = 0; j < map.height; ++j) {
    double row = 0.0;
    for (int i = 0; i < map.width; ++i) row += map.at(i, j);
    sum += row;
  }
  return sum / static_cast<double>(map.values.size());
}

Result<ImageDifference> compare_images(const Image& a, const Image& b, const CompareOptions& options) {
  if (auto ok = check_comparable(a, b, options); !ok) return ok.error();
  if (!(options.relative_mse_epsilon > 0.0) || !std::isfinite(options.relative_mse_epsilon)) {
    return make_error("compare: the relative MSE's epsilon " + number_text(options.relative_mse_epsilon) +
                      " must be finite and > 0");
  }
  if (!std::isfinite(options.exposure_stops)) return make_error("compare: the exposure must be finite");
  ImageDifference d;
  d.width = a.width;
  d.height = a.height;
  d.relative_mse_epsilon = options.relative_mse_epsilon;
  d.ssim_exposure_stops = options.exposure_stops;
  const double eps = options.relative_mse_epsilon;
  const auto w = static_cast<std::size_t>(a.width);
  double sum_sq = 0.0;
  double sum_rel = 0.0;
  double sum_ya = 0.0;
  double sum_yb = 0.0;
  d.max_abs_error = -1.0;
  for (int y = 0; y < a.height; ++y) {
    double row_sq = 0.0, row_rel = 0.0, row_ya = 0.0, row_yb = 0.0;
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * w + x) * 3;
      for (int c = 0; c < 3; ++c) {
        const double av = static_cast<double>(a.data[i + static_cast<std::size_t>(c)]);
        const double bv = static_cast<double>(b.data[i + static_cast<std::size_t>(c)]);
        const double diff = av - bv;
        row_sq += diff * diff;                     // squared error
        row_rel += diff * diff / (bv * bv + eps);  // Rousselle et al. 2011: (a - b)^2 / (b^2 + eps)
        if (std::abs(diff) > d.max_abs_error) {
          d.max_abs_error = std::abs(diff);
          d.max_x = static_cast<int>(x);
          d.max_y = y;
          d.max_channel = c;
        }
      }
      row_ya += pixel_luminance(&a.data[i]);
      row_yb += pixel_luminance(&b.data[i]);
    }
    sum_sq += row_sq;
    sum_rel += row_rel;
    sum_ya += row_ya;
    sum_yb += row_yb;
  }
  const double values = 3.0 * static_cast<double>(a.pixel_count());
  d.mse = sum_sq / values;
  d.rmse = std::sqrt(d.mse);
  d.relative_mse = sum_rel / values;
  d.mean_luminance_a = sum_ya / static_cast<double>(a.pixel_count());
  d.mean_luminance_b = sum_yb / static_cast<double>(a.pixel_count());
  if (d.mean_luminance_b != 0.0) {
    d.mean_luminance_ratio = d.mean_luminance_a / d.mean_luminance_b;
  } else {
    d.mean_luminance_ratio = d.mean_luminance_a == 0.0 ? 1.0 : std::numeric_limits<double>::quiet_NaN();
  }
  const Plane pa = ssim_display_plane(a, options.exposure_stops);
  const Plane pb = ssim_display_plane(b, options.exposure_stops);
  d.ssim = mean_ssim(pa, pb);
  d.ssim_windows = std::isnan(d.ssim) ? 0
                                      : static_cast<long long>(a.width - ssim_window + 1) *
                                            static_cast<long long>(a.height - ssim_window + 1);
  return d;
}

double pixel_error(const Rgb& a, const Rgb& b, ErrorMetric metric, double epsilon) {
  double e = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double diff = std::abs(a[c] - b[c]);
    // absolute: |a - b|; relative: |a - b| / sqrt(b^2 + eps), the root of the relative MSE's term.
    e = std::max(e, metric == ErrorMetric::absolute ? diff : diff / std::sqrt(b[c] * b[c] + epsilon));
  }
  return e;
}

Rgb heat_ramp(double t) {
  if (!(t > 0.0)) t = 0.0;  // also NaN
  t = std::min(t, 1.0);
  // Cubehelix, Green 2011 (Bull. Astr. Soc. India 39, 289): phi = 2 pi (s / 3 + r lambda),
  // a = h lambda^gamma (1 - lambda^gamma) / 2, with s = 0.25, r = 0.45, h = 2.2, gamma = 1.
  constexpr double start = 0.25;
  constexpr double rotations = 0.45;
  constexpr double hue = 2.2;
  const double phi = 2.0 * std::numbers::pi * (start / 3.0 + rotations * t);
  const double amp = hue * t * (1.0 - t) / 2.0;
  const double cp = std::cos(phi);
  const double sp = std::sin(phi);
  // Green 2011: the deviation from grey is perpendicular to the luma direction (0.30, 0.59, 0.11).
  const double encoded[3] = {t + amp * (-0.14861 * cp + 1.78277 * sp), t + amp * (-0.29227 * cp - 0.90649 * sp),
                             t + amp * (1.97294 * cp)};
  Rgb out;
  for (int c = 0; c < 3; ++c) out[c] = srgb_to_linear(std::clamp(encoded[c], 0.0, 1.0));
  return out;
}

Result<Heatmap> error_heatmap(const Image& a, const Image& b, const CompareOptions& options) {
  if (auto ok = check_comparable(a, b, options); !ok) return ok.error();
  if (!(options.heatmap_scale >= 0.0) || !std::isfinite(options.heatmap_scale)) {
    return make_error("compare: the heat-map scale " + number_text(options.heatmap_scale) +
                      " must be finite and >= 0 (0: automatic)");
  }
  if (!(options.relative_mse_epsilon > 0.0) || !std::isfinite(options.relative_mse_epsilon)) {
    return make_error("compare: the relative MSE's epsilon " + number_text(options.relative_mse_epsilon) +
                      " must be finite and > 0");
  }
  std::vector<double> errors(a.pixel_count());
  Heatmap h;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const double e = pixel_error(a.at(x, y), b.at(x, y), options.heatmap_metric, options.relative_mse_epsilon);
      errors[static_cast<std::size_t>(y) * static_cast<std::size_t>(a.width) + static_cast<std::size_t>(x)] = e;
      h.max_error = std::max(h.max_error, e);
    }
  }
  if (options.heatmap_scale > 0.0) {
    h.scale = options.heatmap_scale;
  } else {
    // Automatic: the 99th percentile (the value of rank floor(0.99 (N - 1)) in increasing order), so that a
    // few fireflies or a specular highlight do not turn the rest black; the maximum when that is 0, and 1
    // when every error is 0.
    std::vector<double> sorted = errors;
    const auto rank = static_cast<std::size_t>(heatmap_auto_percentile * static_cast<double>(sorted.size() - 1));
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(rank), sorted.end());
    h.percentile_error = sorted[rank];
    h.scale = h.percentile_error > 0.0 ? h.percentile_error : (h.max_error > 0.0 ? h.max_error : 1.0);
  }
  h.image = Image(a.width, a.height);
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const double e = errors[static_cast<std::size_t>(y) * static_cast<std::size_t>(a.width) + static_cast<std::size_t>(x)];
      h.image.set(x, y, heat_ramp(e / h.scale));
    }
  }
  return h;
}

Result<Image> side_by_side(const Image& a, const Image& b, const Image& heatmap, const CompareOptions& options) {
  if (auto ok = check_comparable(a, b, options); !ok) return ok.error();
  CompareOptions heat_names = options;
  heat_names.name_b = "the heat map";
  if (auto ok = check_comparable(a, heatmap, heat_names); !ok) return ok.error();
  if (!std::isfinite(options.exposure_stops)) return make_error("compare: the exposure must be finite");
  const double gain = std::exp2(options.exposure_stops);
  const int w = a.width;
  Image out(3 * w + 2 * side_by_side_gap, a.height);
  const Rgb gap = Rgb::gray(0.18);  // mid grey (18% reflectance), visible against black and white
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < out.width; ++x) out.set(x, y, gap);
    for (int x = 0; x < w; ++x) {
      out.set(x, y, a.at(x, y) * gain);
      out.set(x + w + side_by_side_gap, y, b.at(x, y) * gain);
      out.set(x + 2 * (w + side_by_side_gap), y, heatmap.at(x, y));
    }
  }
  return out;
}

}  // namespace shadelab
