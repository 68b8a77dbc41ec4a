#include "shadelab/envmap/diffuse/sh_bands.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/base/latlong.h"

namespace shadelab {

namespace {

void check_bands(int bands) {
  if (bands < 1 || bands > sh_max_bands) {
    throw std::invalid_argument("bands: " + std::to_string(bands) + " is out of range [1, " + std::to_string(sh_max_bands) + "]");
  }
}

// Writes the B^2 basis values into out (header: the recurrence for Q_lm = P_l^m / sin^m and (x + iy)^m).
void basis_into(const Vec3& n, int bands, double* out) {
  const double x = n.x, y = n.y, z = n.z;
  double re = 1.0, im = 0.0;  // (x + i y)^m
  double qmm = 1.0;           // Q_mm = (-1)^m (2m - 1)!!
  for (int m = 0; m < bands; ++m) {
    if (m > 0) {
      const double r = re * x - im * y;
      im = re * y + im * x;
      re = r;
      qmm *= -(2.0 * m - 1.0);
    }
    double q_prev = 0.0, q = qmm;  // Q_{l-1,m}, Q_lm, starting at l = m
    for (int l = m; l < bands; ++l) {
      if (l == m + 1) {
        q_prev = q;
        q = (2.0 * m + 1.0) * z * qmm;
      } else if (l > m + 1) {
        const double next = ((2.0 * l - 1.0) * z * q - (l + m - 1.0) * q_prev) / (l - m);
        q_prev = q;
        q = next;
      }
      // K_lm = sqrt((2l + 1)/(4 pi) (l - m)!/(l + m)!)
      const double k = std::sqrt((2.0 * l + 1.0) / (4.0 * pi) * std::exp(std::lgamma(l - m + 1.0) - std::lgamma(l + m + 1.0)));
      if (m == 0) {
        out[sh_index(l, 0)] = k * q;
      } else {
        out[sh_index(l, m)] = std::sqrt(2.0) * k * q * re;
        out[sh_index(l, -m)] = std::sqrt(2.0) * k * q * im;
      }
    }
  }
}

}  // namespace

std::vector<double> sh_basis(const Vec3& n, int bands) {
  check_bands(bands);
  std::vector<double> out(static_cast<std::size_t>(bands * bands));
  basis_into(n, bands, out.data());
  return out;
}

double sh_cosine_band_factor(int l) {
  if (l < 0) throw std::invalid_argument("band " + std::to_string(l) + " < 0");
  if (l == 0) return pi;
  if (l == 1) return 2.0 * pi / 3.0;
  if (l % 2 == 1) return 0.0;
  // 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * l! / (2^l ((l/2)!)^2)   (Ramamoorthi & Hanrahan 2001, eq. 8)
  const double ratio = std::exp(std::lgamma(l + 1.0) - l * std::log(2.0) - 2.0 * std::lgamma(l / 2.0 + 1.0));
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return sign * two_pi / ((l + 2.0) * (l - 1.0)) * ratio;
}

std::vector<double> sh_window_factors(ShWindow window, int bands) {
  check_bands(bands);
  std::vector<double> w(static_cast<std::size_t>(bands), 1.0);
  const double top = bands - 1.0;  // L
  for (int l = 1; l < bands; ++l) {
    const auto i = static_cast<std::size_t>(l);
    if (window == ShWindow::hanning) {
      w[i] = 0.5 * (1.0 + std::cos(pi * l / (2.0 * top + 1.0)));  // Sloan 2008, width 2L + 1
    } else if (window == ShWindow::lanczos) {
      const double a = pi * l / (2.0 * top);  // Sloan 2008, width 2L
      w[i] = std::sin(a) / a;
    }
  }
  return w;
}

ShBands& ShBands::operator+=(const ShBands& o) {
  if (o.bands != bands) throw std::invalid_argument("ShBands: adding " + std::to_string(o.bands) + " bands to " + std::to_string(bands));
  for (std::size_t i = 0; i < c.size(); ++i) c[i] += o.c[i];
  return *this;
}

namespace {

// Bands 0..2 from the Sh9 projection, the rest (if any) from sums over (direction, solid angle, radiance).
ShBands combine(const Sh9& low, int bands) {
  ShBands out(bands);
  for (std::size_t i = 0; i < std::min<std::size_t>(9, out.c.size()); ++i) out.c[i] = low.c[i];
  return out;
}

// Adds sum_k L_k dOmega_k Y_i(d_k) for i >= 9 over rows computed by `row(r, acc)` in parallel, summed in row
// order (the same for any thread count).
template <class RowFn>
void add_high_bands(ShBands& sh, int rows, RowFn row) {
  if (sh.bands <= 3) return;
  const std::size_t n = sh.c.size();
  std::vector<std::vector<Rgb>> partial(static_cast<std::size_t>(rows), std::vector<Rgb>(n));
  tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
    for (int r = range.begin(); r != range.end(); ++r) row(r, partial[static_cast<std::size_t>(r)]);
  });
  for (const auto& p : partial)
    for (std::size_t i = 9; i < n; ++i) sh.c[i] += p[i];
}

}  // namespace

ShBands project_sh_bands(const CubeMap& cube, int bands) {
  check_bands(bands);
  ShBands sh = combine(project_sh9(cube), bands);
  const int n = cube.size;
  const CubeTexelTable& t = CubeTexelTable::get(n);
  add_high_bands(sh, 6 * n, [&](int r, std::vector<Rgb>& acc) {
    const int f = r / n, y = r % n;
    double b[sh_max_bands * sh_max_bands];
    for (int x = 0; x < n; ++x) {
      const std::size_t k = (static_cast<std::size_t>(f) * n + y) * n + x;
      basis_into(t.direction[k], bands, b);
      const Rgb l = cube.texel(f, x, y) * t.solid_angle[k];
      for (std::size_t i = 9; i < acc.size(); ++i) acc[i] += l * b[i];
    }
  });
  return sh;
}

ShBands project_sh_bands(const Image& latlong, int bands) {
  check_bands(bands);
  ShBands sh = combine(project_sh9(latlong), bands);
  const int w = latlong.width, h = latlong.height;
  add_high_bands(sh, h, [&](int y, std::vector<Rgb>& acc) {
    const double d_omega = latlong_texel_solid_angle(y, w, h);
    double b[sh_max_bands * sh_max_bands];
    for (int x = 0; x < w; ++x) {
      basis_into(latlong_direction((x + 0.5) / w, (y + 0.5) / h), bands, b);
      const Rgb l = latlong.at(x, y) * d_omega;
      for (std::size_t i = 9; i < acc.size(); ++i) acc[i] += l * b[i];
    }
  });
  return sh;
}

ShBands project_sh_bands(const std::function<Rgb(const Vec3&)>& f, int size, int bands) {
  check_bands(bands);
  const CubeTexelTable& t = CubeTexelTable::get(size);
  ShBands sh(bands);
  double b[sh_max_bands * sh_max_bands];
  for (std::size_t k = 0; k < t.direction.size(); ++k) {
    basis_into(t.direction[k], bands, b);
    const Rgb l = f(t.direction[k]) * t.solid_angle[k];
    for (std::size_t i = 0; i < sh.c.size(); ++i) sh.c[i] += l * b[i];
  }
  return sh;
}

Rgb sh_bands_evaluate(const ShBands& sh, const Vec3& n, const std::vector<double>& factors) {
  double b[sh_max_bands * sh_max_bands];
  basis_into(n, sh.bands, b);
  Rgb out;
  for (int l = 0; l < sh.bands; ++l) {
    const double f = factors.empty() ? 1.0 : factors.at(static_cast<std::size_t>(l));
    Rgb band;
    for (int m = -l; m <= l; ++m) band += sh.c[static_cast<std::size_t>(sh_index(l, m))] * b[sh_index(l, m)];
    out += band * f;
  }
  return out;
}

ShBands sh_bands_scale(const ShBands& sh, const std::vector<double>& factors) {
  ShBands out = sh;
  for (int l = 0; l < sh.bands; ++l)
    for (int m = -l; m <= l; ++m) out.c[static_cast<std::size_t>(sh_index(l, m))] *= factors.at(static_cast<std::size_t>(l));
  return out;
}

std::vector<double> sh_irradiance_factors(int bands, bool game_units, ShWindow window) {
  std::vector<double> f = sh_window_factors(window, bands);
  for (int l = 0; l < bands; ++l) f[static_cast<std::size_t>(l)] *= sh_cosine_band_factor(l) / (game_units ? pi : 1.0);
  return f;
}

double sh_directional_peak(int bands) {
  double s = 0.0;
  for (int l = 0; l < bands; ++l) s += sh_cosine_band_factor(l) * (2.0 * l + 1.0) / (4.0 * pi);  // addition theorem at t = 1
  return s;
}

ShBands sh_bands_directional_light(const Vec3& to_light, const Rgb& colour_game, int bands, bool d3dx_normalize) {
  const std::vector<double> b = sh_basis(normalize(to_light), bands);
  const double scale = pi / (d3dx_normalize ? sh_directional_peak(bands) : 1.0);
  ShBands sh(bands);
  for (std::size_t i = 0; i < b.size(); ++i) sh.c[i] = colour_game * (scale * b[i]);
  return sh;
}

}  // namespace shadelab
