#include "shadelab/brdf/utia.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>

#include "shadelab/color/rgb.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

static_assert(std::endian::native == std::endian::little, "UTIA files are little-endian; this reader assumes the host is");

namespace {

constexpr double deg = pi / 180.0;

// Direction at elevation cos theta = z and azimuth phi.
Vec3 direction_z(double z, double phi) { return spherical_direction(std::sqrt(std::max(0.0, 1.0 - z * z)), z, phi); }

// One axis of the interpolation: the two neighbouring samples and the weight of the upper one.
struct Axis {
  int k0 = 0, k1 = 0;
  double t = 0.0;
};
// theta in sample units (theta / 15 degrees), held at the last sample beyond it.
Axis theta_axis(double x) {
  x = std::clamp(x, 0.0, static_cast<double>(UtiaTable::n_theta - 1));
  Axis a;
  a.k0 = std::min(static_cast<int>(x), UtiaTable::n_theta - 2);
  a.k1 = a.k0 + 1;
  a.t = x - a.k0;
  return a;
}
// phi in sample units (phi / 7.5 degrees), periodic.
Axis phi_axis(double x) {
  const double f = std::floor(x);
  Axis a;
  a.t = x - f;
  const int n = UtiaTable::n_phi;
  const double m = std::fmod(f, static_cast<double>(n));
  a.k0 = (static_cast<int>(m) + n) % n;
  a.k1 = (a.k0 + 1) % n;
  return a;
}

// The loader's angles of a direction: theta = acos z, phi = atan2(y, x) in [0, 2 pi).
void angles(const Vec3& w, double& theta, double& phi) {
  theta = std::acos(std::clamp(w.z, -1.0, 1.0));
  phi = std::atan2(w.y, w.x);
  if (phi < 0.0) phi += two_pi;
}

}  // namespace

Vec3 utia_direction(int theta_k, int phi_k) {
  const double t = theta_k * UtiaTable::theta_step_deg * deg, p = phi_k * UtiaTable::phi_step_deg * deg;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

Result<UtiaTable> parse_utia(std::span<const char> bytes, const std::string& name) {
  if (bytes.size() != UtiaTable::file_bytes) {
    return make_error(name + ": " + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(UtiaTable::file_bytes) +
                      " (3 planes of 6 x 48 x 6 x 48 float64, theta_i x phi_i x theta_v x phi_v)" +
                      (bytes.size() < UtiaTable::file_bytes ? ": truncated" : ": trailing bytes"));
  }
  UtiaTable t;
  std::memcpy(t.values.data(), bytes.data(), UtiaTable::file_bytes);
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    if (!std::isfinite(t.values[i])) {
      const std::size_t k = i % UtiaTable::plane;
      const std::size_t pv = k % 48, tv = (k / 48) % 6, pi_ = (k / 288) % 48, ti = k / 13824;
      const auto phi = [](std::size_t j) { return std::to_string(j * 15 / 2) + (j % 2 ? ".5" : ""); };  // 7.5 k degrees
      return make_error(name + ": value of channel " + "RGB"[i / UtiaTable::plane] + " at theta_i " + std::to_string(15 * ti) +
                        ", phi_i " + phi(pi_) + ", theta_v " + std::to_string(15 * tv) + ", phi_v " + phi(pv) + " degrees is not finite");
    }
  }
  return t;
}

Result<UtiaTable> read_utia(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(path.string() + ": cannot read (" + ec.message() + ")");
  if (size != UtiaTable::file_bytes) {
    return make_error(path.string() + ": " + std::to_string(size) + " bytes, expected " + std::to_string(UtiaTable::file_bytes) +
                      " (3 planes of 6 x 48 x 6 x 48 float64, theta_i x phi_i x theta_v x phi_v)" +
                      (size < UtiaTable::file_bytes ? ": truncated" : ": trailing bytes"));
  }
  std::vector<char> bytes(UtiaTable::file_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in.seekg(0) || !in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    return make_error(path.string() + ": cannot read " + std::to_string(bytes.size()) + " bytes");
  }
  return parse_utia(bytes, path.string());
}

std::vector<char> encode_utia(const UtiaTable& table) {
  std::vector<char> bytes(UtiaTable::file_bytes);
  std::memcpy(bytes.data(), table.values.data(), UtiaTable::file_bytes);
  return bytes;
}

UtiaTable measure_utia(const Brdf& brdf) {
  UtiaTable t;
  for (int ti = 0; ti < UtiaTable::n_theta; ++ti) {
    for (int pi_ = 0; pi_ < UtiaTable::n_phi; ++pi_) {
      for (int tv = 0; tv < UtiaTable::n_theta; ++tv) {
        for (int pv = 0; pv < UtiaTable::n_phi; ++pv) {
          const Rgb f = brdf.eval(utia_direction(ti, pi_), utia_direction(tv, pv));
          const std::size_t idx = UtiaTable::index(ti, pi_, tv, pv);
          t.values[idx] = f.r;
          t.values[UtiaTable::plane + idx] = f.g;
          t.values[2 * UtiaTable::plane + idx] = f.b;
        }
      }
    }
  }
  return t;
}

UtiaBrdf::UtiaBrdf(std::shared_ptr<const UtiaTable> table) : m_table(std::move(table)) {
  m_views.reserve(static_cast<std::size_t>(UtiaTable::n_theta) * UtiaTable::n_phi);
  std::vector<double> mass(static_cast<std::size_t>(phi_cells) * z_cells);
  for (int tv = 0; tv < UtiaTable::n_theta; ++tv) {
    for (int pv = 0; pv < UtiaTable::n_phi; ++pv) {
      const Vec3 wo = utia_direction(tv, pv);
      for (int j = 0; j < z_cells; ++j) {
        const double z = (j + 0.5) / z_cells;
        for (int i = 0; i < phi_cells; ++i) {
          const double phi = (i + 0.5) / phi_cells * two_pi;
          mass[static_cast<std::size_t>(j) * phi_cells + static_cast<std::size_t>(i)] = std::max(0.0, luminance(eval(direction_z(z, phi), wo))) * z;
        }
      }
      // Finite and non-negative by construction; an all-zero view is uniform.
      m_views.push_back(std::move(*Distribution2D::create(mass, phi_cells, z_cells)));
    }
  }
}

std::size_t UtiaBrdf::view_index(const Vec3& wo) const {
  double theta = 0.0, phi = 0.0;
  angles(wo, theta, phi);
  const int tv = std::min(static_cast<int>(std::lround(theta / (UtiaTable::theta_step_deg * deg))), UtiaTable::n_theta - 1);
  const int pv = static_cast<int>(std::lround(phi / (UtiaTable::phi_step_deg * deg))) % UtiaTable::n_phi;
  return static_cast<std::size_t>(tv) * UtiaTable::n_phi + static_cast<std::size_t>(pv);
}

Rgb UtiaBrdf::eval(const Vec3& wi, const Vec3& wo) const {
  if (!(wi.z > 0.0 && wo.z > 0.0)) return {};
  double ti = 0.0, pi_ = 0.0, tv = 0.0, pv = 0.0;
  angles(wi, ti, pi_);
  angles(wo, tv, pv);
  // Sample units: theta / 15 degrees, phi / 7.5 degrees.
  const Axis a[4] = {theta_axis(ti / (UtiaTable::theta_step_deg * deg)), phi_axis(pi_ / (UtiaTable::phi_step_deg * deg)),
                     theta_axis(tv / (UtiaTable::theta_step_deg * deg)), phi_axis(pv / (UtiaTable::phi_step_deg * deg))};
  double sum[3] = {0.0, 0.0, 0.0};
  // Multilinear interpolation: each of the 16 corners weighted by the product of its axes' linear weights.
  for (int corner = 0; corner < 16; ++corner) {
    int k[4];
    double w = 1.0;
    for (int d = 0; d < 4; ++d) {
      const bool up = (corner >> d) & 1;
      k[d] = up ? a[d].k1 : a[d].k0;
      w *= up ? a[d].t : 1.0 - a[d].t;
    }
    if (w == 0.0) continue;
    const std::size_t idx = UtiaTable::index(k[0], k[1], k[2], k[3]);
    for (int c = 0; c < 3; ++c) sum[c] += w * std::max(0.0, m_table->value(c, idx));
  }
  return {sum[0], sum[1], sum[2]};
}

double UtiaBrdf::pdf(const Vec3& wi, const Vec3& wo) const {
  if (!(wo.z > 0.0) || !(wi.z > 0.0)) return 0.0;
  double phi = std::atan2(wi.y, wi.x);
  if (phi < 0.0) phi += two_pi;
  const double x = std::min(phi / two_pi, std::nextafter(1.0, 0.0));
  const double y = std::min(wi.z, std::nextafter(1.0, 0.0));
  // d(omega) = d(cos theta) d(phi) = 2 pi dx dy.
  const double table = m_views[view_index(wo)].pdf({x, y}) / two_pi;
  return cosine_share * wi.z * inv_pi + (1.0 - cosine_share) * table;
}

BrdfSample UtiaBrdf::sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  BrdfSample s;
  if (!(wo.z > 0.0)) return s;
  if (u_lobe < cosine_share) {
    s.wi = sample_cosine_hemisphere(u);
  } else {
    const auto t = m_views[view_index(wo)].sample(u);
    s.wi = direction_z(t.p.y, two_pi * t.p.x);
  }
  s.pdf = pdf(s.wi, wo);
  if (s.pdf > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
  return s;
}

Result<BrdfPtr> read_utia_brdf(const std::filesystem::path& path) {
  auto t = read_utia(path);
  if (!t) return t.error();
  return BrdfPtr(std::make_unique<UtiaBrdf>(std::make_shared<const UtiaTable>(std::move(*t))));
}

}  // namespace shadelab
