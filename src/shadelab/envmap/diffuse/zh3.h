// ZH3: linear SH plus one quadratic zonal harmonic (Roughton, Sloan, Silvennoinen, Iwanicki & Shirley, "ZH3:
// Quadratic Zonal Harmonics", i3D 2024 / PACMCGIT 7(1)): 4 + 1 coefficients per RGB channel.
//
// The band-1 part of channel c is c_1,-1 Y_1,-1 + c_10 Y_10 + c_11 Y_11 = sqrt(3/(4 pi)) v_c . w with
// v_c = (-c_11, -c_1-1, c_10) (the signs of sh.h's Condon-Shortley basis), so v_c points where L1 is largest.
// The zonal axis is shared by the channels: a = normalize(sum_c lum_c v_c), lum = Rec. 709 luminance weights
// (the paper's luminance axis, section 3.3). The reconstruction is
//   L(w) ~ c_00 Y_00 + sum_m c_1m Y_1m(w) + z_c Y_20(a . w),  Y_20(t) = sqrt(5/(16 pi)) (3 t^2 - 1),
// and irradiance multiplies the three terms by A_0, A_1, A_2 = pi, 2 pi/3, pi/4 (sh_bands.h).
//   stored:       z_c = integral L_c(w) Y_20(a . w) dw = sqrt(4 pi/5) sum_m c_2m Y_2m(a) (addition theorem): the
//                 projection onto the one unit-norm band-2 function along a, the least-squares best zonal
//                 coefficient for that axis (so for a function symmetric about a it is L2 exactly).
//   hallucinated: z_c = c_00 (0.08 r_c + 0.6 r_c^2), r_c = |v_c . a| / c_00 (the paper's curve fit, section 3.4.3),
//                 from the linear SH alone: no extra storage. r lies in [0, sqrt(3)] for radiance >= 0 (a
//                 directional light gives sqrt(3) and an exact z/c_00 of sqrt(5), where the fit gives 1.939).
#pragma once

#include <array>

#include "shadelab/color/rgb.h"
#include "shadelab/core/vec.h"
#include "shadelab/envmap/diffuse/sh_bands.h"

namespace shadelab {

enum class Zh3Mode { stored, hallucinated };

struct Zh3 {
  std::array<Rgb, 4> linear{};  // c_00, c_1-1, c_10, c_11 (radiance)
  Vec3 axis{0, 0, 1};           // unit
  Rgb zonal;                    // z_c (radiance)
  Zh3Mode mode = Zh3Mode::stored;
};

// The luminance-weighted L1 direction; +z when the L1 band is zero.
Vec3 zh3_axis(const std::array<Rgb, 4>& linear);
// The hallucinated zonal coefficient (the paper's fit) of linear SH along axis a.
Rgb zh3_hallucinated_zonal(const std::array<Rgb, 4>& linear, const Vec3& axis);
// From SH of at least 2 bands (stored needs 3).
Zh3 zh3_from_sh(const ShBands& sh, Zh3Mode mode);
// sum of the three terms with band factors f0, f1, f2 (1, 1, 1: radiance; A_l: E; A_l/pi: E/pi).
Rgb zh3_evaluate(const Zh3& z, const Vec3& n, double f0 = 1.0, double f1 = 1.0, double f2 = 1.0);
inline Rgb zh3_irradiance(const Zh3& z, const Vec3& n) {
  return zh3_evaluate(z, n, sh_cosine_band_factor(0), sh_cosine_band_factor(1), sh_cosine_band_factor(2));
}

}  // namespace shadelab
