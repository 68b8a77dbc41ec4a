#include "shadelab/brdf/fresnel.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace shadelab {

double F_dielectric(double cos_i, double eta) {
  if (eta == 1.0) return 0.0;  // no interface (index-matched); avoids 0/0 and a spurious TIR at grazing
  cos_i = std::clamp(cos_i, -1.0, 1.0);
  if (cos_i < 0.0) {  // arriving from the transmitted side: swap the media
    eta = 1.0 / eta;
    cos_i = -cos_i;
  }
  const double sin2_i = std::max(0.0, 1.0 - cos_i * cos_i);
  const double sin2_t = sin2_i / (eta * eta);  // Snell: sin_t = sin_i / eta
  if (sin2_t >= 1.0) return 1.0;               // total internal reflection
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (r_s * r_s + r_p * r_p);
}

double F_conductor(double cos_i, double n, double k) {
  using C = std::complex<double>;
  if (n == 1.0 && k == 0.0) return 0.0;  // no interface (index-matched); avoids 0/0 at grazing
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const C eta(n, k);
  const double sin2_i = 1.0 - cos_i * cos_i;
  const C cos_t = std::sqrt(C(1.0) - sin2_i / (eta * eta));  // complex Snell's law
  const C r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const C r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (std::norm(r_s) + std::norm(r_p));
}

Rgb F_conductor(double cos_i, const Rgb& n, const Rgb& k) {
  return {F_conductor(cos_i, n.r, k.r), F_conductor(cos_i, n.g, k.g), F_conductor(cos_i, n.b, k.b)};
}

}  // namespace shadelab
