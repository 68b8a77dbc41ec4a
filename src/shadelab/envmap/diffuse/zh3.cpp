#include "shadelab/envmap/diffuse/zh3.h"

#include <cmath>
#include <stdexcept>

#include "shadelab/color/rgb.h"
#include "shadelab/core/constants.h"
#include "shadelab/envmap/diffuse/sh.h"

namespace shadelab {

namespace {

double channel(const Rgb& c, int i) { return i == 0 ? c.r : (i == 1 ? c.g : c.b); }
void set_channel(Rgb& c, int i, double v) { (i == 0 ? c.r : (i == 1 ? c.g : c.b)) = v; }

// v_c = (-c_11, -c_1-1, c_10): the direction in which the band-1 part of channel c is largest (zh3.h).
Vec3 l1_vector(const std::array<Rgb, 4>& linear, int ch) {
  return {-channel(linear[3], ch), -channel(linear[1], ch), channel(linear[2], ch)};
}

}  // namespace

Vec3 zh3_axis(const std::array<Rgb, 4>& linear) {
  // a = normalize(sum_c lum_c v_c): the L1 vector of the luminance (ZH3 paper, section 3.3)
  const Vec3 v{-luminance(linear[3]), -luminance(linear[1]), luminance(linear[2])};
  const double len = std::sqrt(dot(v, v));
  if (!(len > 0.0) || !std::isfinite(len)) return {0, 0, 1};
  return v * (1.0 / len);
}

Rgb zh3_hallucinated_zonal(const std::array<Rgb, 4>& linear, const Vec3& axis) {
  Rgb z;
  for (int ch = 0; ch < 3; ++ch) {
    const double c0 = channel(linear[0], ch);
    if (!(c0 > 0.0)) continue;  // no light in this channel: no zonal term
    const double r = std::abs(dot(l1_vector(linear, ch), axis)) / c0;
    set_channel(z, ch, c0 * (0.08 * r + 0.6 * r * r));  // ZH3 paper, section 3.4.3 (curve fit)
  }
  return z;
}

Zh3 zh3_from_sh(const ShBands& sh, Zh3Mode mode) {
  if (sh.bands < 2 || (mode == Zh3Mode::stored && sh.bands < 3)) {
    throw std::invalid_argument("zh3: needs " + std::string(mode == Zh3Mode::stored ? "3" : "2") + " bands");
  }
  Zh3 z;
  z.mode = mode;
  for (std::size_t i = 0; i < 4; ++i) z.linear[i] = sh.c[i];
  z.axis = zh3_axis(z.linear);
  if (mode == Zh3Mode::hallucinated) {
    z.zonal = zh3_hallucinated_zonal(z.linear, z.axis);
  } else {
    // z = sqrt(4 pi / 5) sum_m c_2m Y_2m(a): the addition theorem Y_20(a . w) = sqrt(4 pi/5) sum_m Y_2m(a) Y_2m(w)
    const std::vector<double> y = sh_basis(z.axis, 3);
    for (int m = -2; m <= 2; ++m) z.zonal += sh.c[static_cast<std::size_t>(sh_index(2, m))] * y[static_cast<std::size_t>(sh_index(2, m))];
    z.zonal *= std::sqrt(4.0 * pi / 5.0);
  }
  return z;
}

Rgb zh3_evaluate(const Zh3& z, const Vec3& n, double f0, double f1, double f2) {
  const std::vector<double> y = sh_basis(n, 2);
  const double t = dot(z.axis, n);
  const double y20 = sh_c3 * (3.0 * t * t - 1.0);  // Y_20(a . n) = sqrt(5/(16 pi)) (3 t^2 - 1)
  Rgb l1;
  for (std::size_t i = 1; i < 4; ++i) l1 += z.linear[i] * y[i];
  return z.linear[0] * (f0 * y[0]) + l1 * f1 + z.zonal * (f2 * y20);
}

}  // namespace shadelab
