// shadelab spherical harmonics of any number of bands B = 1 .. 5 (l = 0 .. B - 1: L0 .. L4, B^2 coefficients
// per RGB channel). Sh9 (sh.h) stays the order-3 model that shaders use; this is its generalisation, with the
// same basis convention, so the first nine functions of ShBands are sh9_basis (tested to rounding).
//
// Basis (real SH, Condon-Shortley phase, z polar axis, Sloan's order: index l^2 + l + m, m = -l .. l):
//   Y_l0 = K_l0 P_l(z),  Y_lm = sqrt(2) K_lm P_l^m(z) cos(m phi) (m > 0),  Y_l-m = sqrt(2) K_lm P_l^m(z) sin(m phi),
//   K_lm = sqrt((2l + 1)/(4 pi) (l - m)!/(l + m)!), P_l^m with the (-1)^m phase (Sloan, "Stupid Spherical
//   Harmonics (SH) Tricks", GDC 2008, eq. 6). Evaluated as polynomials in (x, y, z): sin^m(theta) cos(m phi)
//   and sin^m(theta) sin(m phi) are the real and imaginary parts of (x + i y)^m, and P_l^m / sin^m(theta) obeys
//   the standard three-term recurrence in l (Press et al., Numerical Recipes 3rd ed., eq. 6.7.9):
//   Q_mm = (-1)^m (2m - 1)!!, Q_m+1,m = (2m + 1) z Q_mm, (l - m) Q_lm = (2l - 1) z Q_l-1,m - (l + m - 1) Q_l-2,m.
//
// Cosine-lobe band factors (Ramamoorthi & Hanrahan, "An Efficient Representation for Irradiance Environment
// Maps", SIGGRAPH 2001, eq. 8), the Funk-Hecke coefficients 2 pi integral_0^1 t P_l(t) dt of max(0, cos):
//   A_0 = pi, A_1 = 2 pi/3, A_l = 0 for odd l > 1, A_l = 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) l!/(2^l ((l/2)!)^2)
//   for even l: A_2 = pi/4, A_3 = 0, A_4 = -pi/24.
//
// Windows (Sloan 2008, "Windowing"), factors w_l applied on top of the band factors, generalised from the
// order-3 widths of sh.h (hanning 5, lanczos 4) so that the window is the same function of l / L (L = B - 1):
//   hanning w_l = (1 + cos(pi l / (2L + 1))) / 2,   lanczos w_l = sinc(pi l / (2L)) = sin(pi l/(2L)) / (pi l/(2L)).
// At B = 3 they are exactly sh_window_factors (hanning 1, 0.905, 0.655; lanczos 1, 0.900, 0.637).
//
// Projection with exact solid angles: bands 0..2 are project_sh9 itself (bit for bit: the moment sums of
// sh.cpp, exact per texel for a lat-long map), bands 3 and 4 the sum over texel centres of L Y_lm dOmega with
// the exact texel solid angle (cube: CubeTexelTable; lat-long: the ring's exact 2 pi/W (cos theta0 - cos theta1)).
#pragma once

#include <functional>
#include <vector>

#include "shadelab/color/rgb.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/image/image.h"

namespace shadelab {

inline constexpr int sh_max_bands = 5;
constexpr int sh_index(int l, int m) { return l * l + l + m; }

// The B^2 basis values at unit direction n (B in 1 .. sh_max_bands).
std::vector<double> sh_basis(const Vec3& n, int bands);

// A_l of the clamped cosine (radiometric; divide by pi for E/pi), for any l >= 0.
double sh_cosine_band_factor(int l);
// The B window factors (ShWindow::none gives ones).
std::vector<double> sh_window_factors(ShWindow window, int bands);

struct ShBands {
  int bands = 0;
  std::vector<Rgb> c;  // bands^2 coefficients, Sloan's order
  explicit ShBands(int b = 3) : bands(b), c(static_cast<std::size_t>(b * b)) {}
  ShBands& operator+=(const ShBands& o);
};

ShBands project_sh_bands(const CubeMap& cube, int bands);
ShBands project_sh_bands(const Image& latlong, int bands);
// Of a function of direction, over an N x N cube of exact solid angles (for tests and analytic inputs).
ShBands project_sh_bands(const std::function<Rgb(const Vec3&)>& f, int size, int bands);

// sum_lm factor_l c_lm Y_lm(n); `factors` has one entry per band (empty: ones).
Rgb sh_bands_evaluate(const ShBands& sh, const Vec3& n, const std::vector<double>& factors = {});
ShBands sh_bands_scale(const ShBands& sh, const std::vector<double>& factors);
// The cosine band factors of bands 0 .. B-1, radiometric or divided by pi (game), times a window.
std::vector<double> sh_irradiance_factors(int bands, bool game_units, ShWindow window = ShWindow::none);

// A directional light of game colour c toward `to_light`: the delta pi c delta(w - d) projected, Y_lm(d) pi c.
// With d3dx_normalize it is divided by the truncated game irradiance facing the light, sum_l A_l (2l + 1)/(4 pi)
// (3/4 for B = 2, 17/16 for B = 3 and 4, 31/32 for B = 5), so the light gives exactly c facing it (sh.h).
ShBands sh_bands_directional_light(const Vec3& to_light, const Rgb& colour_game, int bands, bool d3dx_normalize = true);
double sh_directional_peak(int bands);  // sum_{l < B} A_l (2l + 1)/(4 pi)

}  // namespace shadelab
