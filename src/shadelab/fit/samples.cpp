#include "shadelab/fit/samples.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace shadelab {

namespace {

constexpr double pi = std::numbers::pi;

Vec3 rotate_about_z(const Vec3& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x - s * v.y, s * v.x + c * v.y, v.z};
}

// Visits the grid's kept configurations: fn(theta_h_i, theta_d_i, phi_d_i, wi, wo, weight).
template <typename Fn>
void for_each_configuration(const FitGridOptions& o, int n_phi_h, Fn&& fn) {
  const int sd = std::max(1, o.theta_d_stride), sp = std::max(1, o.phi_d_stride), nh = std::max(1, n_phi_h);
  const double cos_max = std::cos(o.max_theta_deg * pi / 180.0);
  const double n2 = static_cast<double>(MerlTable::n_theta_h) * MerlTable::n_theta_h;
  const double d_theta_d = sd * 0.5 * pi / MerlTable::n_theta_d;
  const double d_phi_d = 2.0 * sp * pi / MerlTable::n_phi_d;  // both halves of phi_d: [0, pi) stands for [0, 2pi)
  const double d_phi_h = 2.0 * pi / nh;
  for (int i = 0; i < MerlTable::n_theta_h; ++i) {
    const double d_theta_h = 0.5 * pi * (2.0 * i + 1.0) / n2;  // ((i+1)^2 - i^2)/90^2 of pi/2
    for (int j = sd / 2; j < MerlTable::n_theta_d; j += sd) {
      for (int k = sp / 2; k < MerlTable::n_phi_d; k += sp) {
        const HalfDiffAngles a = merl_bin_centre(i, j, k);
        const auto [wi0, wo0] = half_diff_directions(a);
        // dw_i dw_o = 4 cos(theta_d) sin(theta_h) sin(theta_d) dtheta_h dphi_h dtheta_d dphi_d (Rusinkiewicz 1998)
        const double w = 4.0 * std::cos(a.theta_d) * std::sin(a.theta_h) * std::sin(a.theta_d) * d_theta_h *
                         d_phi_h * d_theta_d * d_phi_d;
        if (!(wi0.z > cos_max && wo0.z > cos_max)) continue;
        for (int m = 0; m < nh; ++m) {
          const double phi_h = 2.0 * pi * m / nh;
          fn(i, j, k, normalize(rotate_about_z(wi0, phi_h)), normalize(rotate_about_z(wo0, phi_h)), w);
        }
      }
    }
  }
}

}  // namespace

FitData fit_grid(const FitGridOptions& options) {
  FitData d;
  for_each_configuration(options, options.n_phi_h, [&](int, int, int, const Vec3& wi, const Vec3& wo, double w) {
    d.wi.push_back(wi);
    d.wo.push_back(wo);
    d.weight.push_back(w);
  });
  return d;
}

FitData fit_data_from_brdf(const Brdf& data, const FitGridOptions& options) {
  FitData d = fit_grid(options);
  d.value.resize(d.wi.size());
  data.eval_batch(d.wi.data(), d.wo.data(), d.value.data(), d.wi.size());
  return d;
}

FitData fit_data_from_merl(const MerlTable& table, const FitGridOptions& options) {
  FitData d;
  for_each_configuration(options, 1, [&](int i, int j, int k, const Vec3& wi, const Vec3& wo, double w) {
    const std::size_t idx = MerlTable::index(i, j, k);
    const Rgb f{table.value(0, idx), table.value(1, idx), table.value(2, idx)};
    if (f.r < 0.0 || f.g < 0.0 || f.b < 0.0) return;  // not measured
    d.wi.push_back(wi);
    d.wo.push_back(wo);
    d.weight.push_back(w);
    d.value.push_back(f);
  });
  return d;
}

bool fit_data_is_grey(const FitData& data) {
  for (const Rgb& v : data.value) {
    const double m = std::max(std::abs(v.r), std::max(std::abs(v.g), std::abs(v.b)));
    if (std::abs(v.r - v.g) > 1e-12 * m || std::abs(v.r - v.b) > 1e-12 * m) return false;
  }
  return true;
}

bool looks_isotropic(const Brdf& f) {
  // 64 pairs on a fixed lattice of the upper hemisphere (theta up to 75 degrees), each rotated by three angles.
  for (int n = 0; n < 64; ++n) {
    const double ti = (0.1 + 1.2 * ((n * 37) % 64) / 64.0), to = (0.05 + 1.2 * ((n * 11) % 64) / 64.0);
    const double pi_ = 2.0 * pi * ((n * 23) % 64) / 64.0, po = 2.0 * pi * ((n * 53) % 64) / 64.0;
    const Vec3 wi{std::sin(ti) * std::cos(pi_), std::sin(ti) * std::sin(pi_), std::cos(ti)};
    const Vec3 wo{std::sin(to) * std::cos(po), std::sin(to) * std::sin(po), std::cos(to)};
    const Rgb f0 = f.eval(wi, wo);
    for (double a : {0.7, 1.9, 3.3}) {
      const Rgb f1 = f.eval(normalize(rotate_about_z(wi, a)), normalize(rotate_about_z(wo, a)));
      for (int c = 0; c < 3; ++c) {
        if (std::abs(f1[c] - f0[c]) > 1e-9 * std::max(std::abs(f0[c]), 1e-300) + 1e-300) return false;
      }
    }
  }
  return true;
}

}  // namespace shadelab
