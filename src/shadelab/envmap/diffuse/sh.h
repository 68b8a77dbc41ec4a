// shadelab spherical harmonics, order 3 (bands l = 0, 1, 2: nine coefficients per RGB channel).
//
// Basis (real SH with the Condon-Shortley phase, z as the polar axis, in the order of Sloan, "Stupid
// Spherical Harmonics (SH) Tricks", GDC 2008, and of the PI-or-not article's code):
//   Y0 = 1/(2 sqrt(pi))                      = 0.282095
//   Y1 = -sqrt(3/(4pi)) y, Y2 = sqrt(3/(4pi)) z, Y3 = -sqrt(3/(4pi)) x           (0.488603)
//   Y4 = sqrt(15/(4pi)) xy, Y5 = -sqrt(15/(4pi)) yz, Y7 = -sqrt(15/(4pi)) xz       (1.092548)
//   Y6 = sqrt(5/(16pi)) (3z^2 - 1)                                                (0.315392)
//   Y8 = sqrt(15/(16pi)) (x^2 - y^2)                                              (0.546274)
// x, y, z are world coordinates (the renderer's +Y up does not matter: SH convolution is rotation-covariant).
//
// Projection: c_i = sum over texels of L(w) Y_i(w) dOmega with the exact texel solid angles.
// Cosine-lobe convolution (Ramamoorthi & Hanrahan, "An Efficient Representation for Irradiance Environment
// Maps", SIGGRAPH 2001): E(n) = sum_l A_l sum_m c_lm Y_lm(n), A = (pi, 2pi/3, pi/4). Divided by pi
// (1, 2/3, 1/4) it gives the exit radiance of a white Lambert surface: the game convention E/pi.
// Wrapped diffuse (Hill, "Righting Wrap", 2011; PI-or-not article): (1, (2 - w)/3, (1 - w)^2/4), already
// divided by pi; they are the bands of the kernel max(0, cos + w) / (pi (1 + w)^2), the wrapped-diffuse BRDF
// times the cosine, and are applied per surface at evaluation, as the article's comments recommend.
#pragma once

#include <array>
#include <functional>

#include "shadelab/color/rgb.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/mat3.h"
#include "shadelab/core/vec.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/image/image.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

// The basis constants, written once in kernels/sh9.sl (the shaders read the same text); sh_test.cpp checks them
// against their closed forms 1/(2 sqrt(pi)), sqrt(3/(4 pi)), sqrt(15/(4 pi)), sqrt(5/(16 pi)), sqrt(15/(16 pi)).
inline const double sh_c0 = kernel::SH9_C0;
inline const double sh_c1 = kernel::SH9_C1;
inline const double sh_c2 = kernel::SH9_C2;
inline const double sh_c3 = kernel::SH9_C3;
inline const double sh_c4 = kernel::SH9_C4;

using ShBasis = std::array<double, 9>;
ShBasis sh9_basis(const Vec3& n);  // n unit
constexpr int sh_band(int i) { return i == 0 ? 0 : (i < 4 ? 1 : 2); }

struct Sh9 {
  std::array<Rgb, 9> c{};
  Sh9& operator+=(const Sh9& o) {
    for (std::size_t i = 0; i < 9; ++i) c[i] += o.c[i];
    return *this;
  }
};

using BandFactors = std::array<double, 3>;
inline constexpr BandFactors cosine_band_factors = {pi, 2.0 * pi / 3.0, pi / 4.0};
inline constexpr BandFactors cosine_band_factors_over_pi = {1.0, 2.0 / 3.0, 1.0 / 4.0};
constexpr BandFactors wrapped_band_factors_over_pi(double w) {
  return {1.0, (2.0 - w) / 3.0, (1.0 - w) * (1.0 - w) / 4.0};
}

// Windows that damp bands 1 and 2 to reduce ringing (Sloan 2008, section "Windowing"), applied as extra band
// factors: hanning (1 + cos(pi l / 5)) / 2 = (1, 0.905, 0.655); lanczos sinc(pi l / 4) = (1, 0.900, 0.637).
// For a single directional light the order-3 irradiance dips to -3.96% of the facing value's 16/17 scale
// (min over directions of 1/4 + t/2 + 5/16 P_2(t)); either window halves the dip (-1.89%, -1.92%) and
// lowers the peak from 1.0625 to 0.907 (hanning) or 0.899 (lanczos): a blur, documented in docs/envmap.md.
enum class ShWindow { none, hanning, lanczos };
BandFactors sh_window_factors(ShWindow window);

// Projections. The cube-map one uses precomputed per-texel tables and a deterministic parallel reduction.
Sh9 project_sh9(const CubeMap& cube);
namespace detail {
// project_sh9(cube) with its kernel limited to `widest` (0: baseline x86-64, 1: AVX2 + FMA, 2: AVX-512F;
// each where the CPU has it), so that tests reach every wrapper on any machine.
Sh9 project_sh9_simd(const CubeMap& cube, int widest);
}  // namespace detail
Sh9 project_sh9(const Image& latlong);
// Of a function of direction, with an N x N cube of exact solid angles (for tests and analytic inputs).
Sh9 project_sh9(const std::function<Rgb(const Vec3&)>& f, int size);

// sum_i factor_l(i) c_i Y_i(n). With unit factors: the SH reconstruction of the projected function.
Rgb sh9_evaluate(const Sh9& sh, const Vec3& n, const BandFactors& factors = {1.0, 1.0, 1.0});
// Irradiance in the two conventions: radiometric E (W/m^2) and game E/pi (the exit radiance of a white
// Lambert surface). kd x the game value is the diffuse exit radiance.
inline Rgb sh9_irradiance(const Sh9& sh, const Vec3& n) { return sh9_evaluate(sh, n, cosine_band_factors); }
inline Rgb sh9_irradiance_game(const Sh9& sh, const Vec3& n) {
  return sh9_evaluate(sh, n, cosine_band_factors_over_pi);
}
Sh9 sh9_scale_bands(const Sh9& sh, const BandFactors& factors);

// A directional light of game colour c toward direction `to_light`, projected as the delta pi c delta(w - d)
// (the x pi of the game unit, Lagarde 2012). With d3dx_normalize the result is scaled by 16/17 so that the
// SH-evaluated game irradiance facing the light is exactly c, the D3DXSHEvalDirectionalLight semantics
// ("the exit radiance of a point directly under the light on a diffuse object with an albedo of 1 would be
// 1.0"): the order-3 truncation of the delta gives 1 + 1/2... = 17/16 there.
Sh9 sh9_directional_light(const Vec3& to_light, const Rgb& colour_game, bool d3dx_normalize = true);

// The coefficients of the rotated function g(w) = f(R^-1 w).
Sh9 sh9_rotate(const Sh9& sh, const Mat3& rotation);

// A rigorous bound on the order-2 truncation: for every n, |E(n) - sh9_irradiance(sh, n)| <= K sqrt(R) per
// channel, where R = integral of L^2 - sum of the nine squared coefficients (Parseval: the energy SH9 leaves
// out) and K = sqrt(sum over even l >= 4 of A_l^2 (2l + 1)/(4 pi)) = 0.1279158 (A_l of Ramamoorthi & Hanrahan
// 2001, eq. 8; odd l >= 3 have A_l = 0); Cauchy-Schwarz over m (addition theorem), then over l.
// Divide by pi for the game convention. `sh` must be project_sh9(env).
inline constexpr double sh9_truncation_constant = 0.12791583849327710;
Rgb sh9_irradiance_error_bound(const CubeMap& env, const Sh9& sh);

}  // namespace shadelab
