// shadelab LDR-FLIP (flip.h; sources there).
#include "shadelab/image/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace shadelab {

namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;
using Vec3d = std::array<double, 3>;

// Constants of Andersson et al. 2020 (sections 4-6).
constexpr double q_c = 0.7;    // colour error exponent
constexpr double p_c = 0.4;    // colour error's knee, as a share of c_max
constexpr double p_t = 0.95;   // the error at the knee
constexpr double q_f = 0.5;    // feature error exponent
constexpr double feature_width = 0.082;  // w, degrees: the feature detectors' sigma is w / 2
// Contrast sensitivity, per channel: up to two Gaussians (a, b) (section 4.1, Table 1).
struct CsfTerm {
  double a, b;
};
constexpr std::array<CsfTerm, 2> csf_y{{{1.0, 0.0047}, {0.0, 1e-5}}};
constexpr std::array<CsfTerm, 2> csf_cx{{{1.0, 0.0053}, {0.0, 1e-5}}};
constexpr std::array<CsfTerm, 2> csf_cz{{{34.1, 0.04}, {13.5, 0.025}}};
constexpr double csf_b_max = 0.04;

Vec3d mul(const Mat3& m, const Vec3d& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

Mat3 inverse(const Mat3& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  Mat3 r{};
  r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
  r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return r;
}

// Linear Rec.709 RGB -> CIE XYZ from the primaries' and D65's chromaticities (ITU-R BT.709-6 item 1.3-1.4;
// SMPTE RP 177-1993 section 3.3: columns are the primaries' xyz scaled so that RGB (1, 1, 1) is the white).
struct ColourSpace {
  Mat3 rgb_to_xyz{};
  Mat3 xyz_to_rgb{};
  Vec3d white{};  // Xn, Yn = 1, Zn
};

const ColourSpace& space() {
  static const ColourSpace s = [] {
    const double xs[3] = {0.64, 0.30, 0.15}, ys[3] = {0.33, 0.60, 0.06};
    const double wx = 0.3127, wy = 0.3290;
    Mat3 p{};
    for (int c = 0; c < 3; ++c) {
      p[0][c] = xs[c] / ys[c];
      p[1][c] = 1.0;
      p[2][c] = (1.0 - xs[c] - ys[c]) / ys[c];
    }
    ColourSpace out;
    out.white = {wx / wy, 1.0, (1.0 - wx - wy) / wy};
    const Vec3d scale = mul(inverse(p), out.white);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out.rgb_to_xyz[r][c] = p[r][c] * scale[c];
    out.xyz_to_rgb = inverse(out.rgb_to_xyz);
    return out;
  }();
  return s;
}

// XYZ -> YCxCz (Zhang & Wandell 1997, "A spatial extension of CIELAB for digital color-image reproduction",
// J. SID 5(1): L*a*b* with the cube root left out).
Vec3d xyz_to_ycxcz(const Vec3d& xyz) {
  const Vec3d& w = space().white;
  const double x = xyz[0] / w[0], y = xyz[1] / w[1], z = xyz[2] / w[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3d ycxcz_to_xyz(const Vec3d& v) {
  const Vec3d& w = space().white;
  const double y = (v[0] + 16.0) / 116.0;
  return {(y + v[1] / 500.0) * w[0], y * w[1], (y - v[2] / 200.0) * w[2]};
}

// CIE 1976 L*a*b* (CIE 15:2004, 8.2.1), D65 white.
Vec3d xyz_to_lab(const Vec3d& xyz) {
  const Vec3d& w = space().white;
  constexpr double delta = 6.0 / 29.0;
  const auto f = [](double t) {
    return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
  };
  const double fx = f(xyz[0] / w[0]), fy = f(xyz[1] / w[1]), fz = f(xyz[2] / w[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

// Hunt effect (section 4.2): chroma scaled by 0.01 L.
Vec3d hunt(const Vec3d& lab) { return {lab[0], 0.01 * lab[0] * lab[1], 0.01 * lab[0] * lab[2]}; }

// HyAB (Abasi, Amani Tehran, Fairchild 2020, Color Res. Appl. 45(2); FLIP eq. 3).
double hyab(const Vec3d& p, const Vec3d& q) {
  return std::abs(p[0] - q[0]) + std::sqrt((p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

Vec3d clamp01(const Vec3d& v) {
  return {std::clamp(v[0], 0.0, 1.0), std::clamp(v[1], 0.0, 1.0), std::clamp(v[2], 0.0, 1.0)};
}

// Filtered YCxCz -> linear RGB clamped to [0, 1] -> Hunt-adjusted L*a*b* (section 4.2).
Vec3d perceptual(const Vec3d& ycxcz) {
  const ColourSpace& s = space();
  return hunt(xyz_to_lab(mul(s.rgb_to_xyz, clamp01(mul(s.xyz_to_rgb, ycxcz_to_xyz(ycxcz))))));
}

double c_max() { return std::pow(flip_max_hyab(), q_c); }

// HyAB^q_c mapped to [0, 1] (section 4.3).
double colour_error(const Vec3d& test_lab, const Vec3d& ref_lab) {
  const double cmax = c_max();
  const double knee = p_c * cmax;
  const double e = std::pow(hyab(test_lab, ref_lab), q_c);
  return e < knee ? e * p_t / knee : p_t + (e - knee) / (cmax - knee) * (1.0 - p_t);
}

// One-dimensional weights of the sum of Gaussians S (flip.h) at pixel offsets -r..r, per term: the 2D filter
// is sum_i g_i(x) g_i(y) with g_i(x) = sqrt(a_i sqrt(pi / b_i)) exp(-pi^2 x^2 / b_i), and every weight is
// divided by sqrt(sum_i (sum_x g_i(x))^2) so that the 2D filter sums to 1.
std::array<std::vector<double>, 2> csf_weights(const std::array<CsfTerm, 2>& terms, int r, double ppd) {
  std::array<std::vector<double>, 2> g;
  double total = 0.0;
  for (std::size_t i = 0; i < 2; ++i) {
    g[i].resize(static_cast<std::size_t>(2 * r + 1));
    double sum = 0.0;
    for (int k = -r; k <= r; ++k) {
      const double x = k / ppd;
      const double v = std::sqrt(terms[i].a * std::sqrt(std::numbers::pi / terms[i].b)) *
                       std::exp(-std::numbers::pi * std::numbers::pi * x * x / terms[i].b);
      g[i][static_cast<std::size_t>(k + r)] = v;
      sum += v;
    }
    total += sum * sum;
  }
  const double norm = 1.0 / std::sqrt(total);
  for (auto& w : g)
    for (double& v : w) v *= norm;
  return g;
}

// Separable convolution with clamped edges: rows by wx, then columns by wy.
std::vector<double> convolve(const std::vector<double>& src, int w, int h, const std::vector<double>& wx,
                             const std::vector<double>& wy) {
  const int rx = static_cast<int>(wx.size() / 2), ry = static_cast<int>(wy.size() / 2);
  std::vector<double> tmp(src.size()), out(src.size());
  const auto at = [w](int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x); };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int k = -rx; k <= rx; ++k) s += wx[static_cast<std::size_t>(k + rx)] * src[at(std::clamp(x + k, 0, w - 1), y)];
      tmp[at(x, y)] = s;
    }
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double s = 0.0;
      for (int k = -ry; k <= ry; ++k) s += wy[static_cast<std::size_t>(k + ry)] * tmp[at(x, std::clamp(y + k, 0, h - 1))];
      out[at(x, y)] = s;
    }
  }
  return out;
}

// The feature detectors' 1D kernels (section 5): Gaussian g (sum 1), first derivative -x g and second
// derivative (x^2 / sigma^2 - 1) g, each derivative's positive weights summing to 1 and negative to -1.
struct FeatureKernels {
  std::vector<double> g, d1, d2;
};

FeatureKernels feature_kernels(double ppd) {
  const double sigma = 0.5 * feature_width * ppd;
  const int r = static_cast<int>(std::ceil(3.0 * sigma));
  FeatureKernels k;
  double gs = 0.0, d1p = 0.0, d1n = 0.0, d2p = 0.0, d2n = 0.0;
  for (int x = -r; x <= r; ++x) {
    const double g = std::exp(-static_cast<double>(x * x) / (2.0 * sigma * sigma));
    const double d1 = -x * g, d2 = (x * x / (sigma * sigma) - 1.0) * g;
    k.g.push_back(g);
    k.d1.push_back(d1);
    k.d2.push_back(d2);
    gs += g;
    (d1 > 0.0 ? d1p : d1n) += std::abs(d1);
    (d2 > 0.0 ? d2p : d2n) += std::abs(d2);
  }
  for (double& v : k.g) v /= gs;
  for (double& v : k.d1) v /= v > 0.0 ? d1p : d1n;
  for (double& v : k.d2) v /= v > 0.0 ? d2p : d2n;
  return k;
}

}  // namespace

double flip_max_hyab() {
  const ColourSpace& s = space();
  const Vec3d green = hunt(xyz_to_lab(mul(s.rgb_to_xyz, {0.0, 1.0, 0.0})));
  const Vec3d blue = hunt(xyz_to_lab(mul(s.rgb_to_xyz, {0.0, 0.0, 1.0})));
  return hyab(green, blue);
}

double flip_flat_color_error(const Rgb& test, const Rgb& reference) {
  const ColourSpace& s = space();
  const auto lab = [&s](const Rgb& c) { return perceptual(xyz_to_ycxcz(mul(s.rgb_to_xyz, clamp01({c.r, c.g, c.b})))); };
  return colour_error(lab(test), lab(reference));
}

Result<FlipResult> flip(const Image& test, const Image& reference, const FlipOptions& options) {
  CompareOptions co;
  co.name_a = options.name_test;
  co.name_b = options.name_reference;
  if (auto ok = check_comparable(test, reference, co); !ok) return ok.error();
  const double ppd = options.pixels_per_degree;
  if (!(ppd > 0.0) || !std::isfinite(ppd) || ppd > 1000.0) {
    return make_error("flip: pixels per degree " + std::to_string(ppd) + " is out of range (0, 1000]");
  }
  const int w = test.width, h = test.height;
  const std::size_t n = test.pixel_count();
  const ColourSpace& s = space();
  // YCxCz planes of both images.
  std::array<std::array<std::vector<double>, 3>, 2> planes;
  const Image* images[2] = {&test, &reference};
  for (int i = 0; i < 2; ++i) {
    for (auto& p : planes[static_cast<std::size_t>(i)]) p.resize(n);
    for (std::size_t p = 0; p < n; ++p) {
      const float* d = images[i]->data.data() + 3 * p;
      const Vec3d v = xyz_to_ycxcz(mul(s.rgb_to_xyz, clamp01({static_cast<double>(d[0]), static_cast<double>(d[1]),
                                                              static_cast<double>(d[2])})));
      for (std::size_t c = 0; c < 3; ++c) planes[static_cast<std::size_t>(i)][c][p] = v[c];
    }
  }
  // Colour pipeline.
  const int r = static_cast<int>(std::ceil(3.0 * std::sqrt(csf_b_max / (2.0 * std::numbers::pi * std::numbers::pi)) * ppd));
  const std::array<const std::array<CsfTerm, 2>*, 3> csf{&csf_y, &csf_cx, &csf_cz};
  std::array<std::array<std::vector<double>, 3>, 2> filtered;
  for (std::size_t c = 0; c < 3; ++c) {
    const auto g = csf_weights(*csf[c], r, ppd);
    for (std::size_t i = 0; i < 2; ++i) {
      std::vector<double> sum(n, 0.0);
      for (std::size_t t = 0; t < 2; ++t) {
        if ((*csf[c])[t].a == 0.0) continue;
        const std::vector<double> part = convolve(planes[i][c], w, h, g[t], g[t]);
        for (std::size_t p = 0; p < n; ++p) sum[p] += part[p];
      }
      filtered[i][c] = std::move(sum);
    }
  }
  // Feature pipeline on y = (Y + 16) / 116.
  const FeatureKernels fk = feature_kernels(ppd);
  std::array<std::array<std::vector<double>, 4>, 2> features;  // dx, dy, ddx, ddy
  for (std::size_t i = 0; i < 2; ++i) {
    std::vector<double> y(n);
    for (std::size_t p = 0; p < n; ++p) y[p] = (planes[i][0][p] + 16.0) / 116.0;
    features[i] = {convolve(y, w, h, fk.d1, fk.g), convolve(y, w, h, fk.g, fk.d1), convolve(y, w, h, fk.d2, fk.g),
                   convolve(y, w, h, fk.g, fk.d2)};
  }
  FlipResult out;
  out.map.width = w;
  out.map.height = h;
  out.map.values.resize(n);
  double sum = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    const Vec3d lt = perceptual({filtered[0][0][p], filtered[0][1][p], filtered[0][2][p]});
    const Vec3d lr = perceptual({filtered[1][0][p], filtered[1][1][p], filtered[1][2][p]});
    const double ec = colour_error(lt, lr);
    const auto& ft = features[0];
    const auto& fr = features[1];
    const double edge = std::abs(std::hypot(ft[0][p], ft[1][p]) - std::hypot(fr[0][p], fr[1][p]));
    const double point = std::abs(std::hypot(ft[2][p], ft[3][p]) - std::hypot(fr[2][p], fr[3][p]));
    const double ef = std::pow(std::max(edge, point) / std::numbers::sqrt2, q_f);
    const double e = std::pow(ec, 1.0 - ef);
    out.map.values[p] = e;
    sum += e;
  }
  out.mean = sum / static_cast<double>(n);
  return out;
}

}  // namespace shadelab
