#include "shadelab/brdf/merl.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <system_error>

#include "shadelab/core/constants.h"

namespace shadelab {

static_assert(std::endian::native == std::endian::little, "MERL files are little-endian; this reader assumes the host is");

namespace {

// Rotation about the y axis by angle a (right-handed): (x cos a + z sin a, y, -x sin a + z cos a).
Vec3 rotate_y(const Vec3& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {v.x * c + v.z * s, v.y, -v.x * s + v.z * c};
}
// Rotation about the z axis by angle a.
Vec3 rotate_z(const Vec3& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {v.x * c - v.y * s, v.x * s + v.y * c, v.z};
}

int clamp_index(double x, int n) {
  if (!(x > 0.0)) return 0;
  return std::min(static_cast<int>(x), n - 1);
}

}  // namespace

// Rusinkiewicz 1998, section 3: h = (wi + wo) / |wi + wo|, d = wi rotated by -phi_h about n, then -theta_h about b.
HalfDiffAngles half_diff_angles(const Vec3& wi, const Vec3& wo) {
  const Vec3 h = normalize(wi + wo);
  HalfDiffAngles a;
  a.theta_h = std::acos(std::clamp(h.z, -1.0, 1.0));
  a.phi_h = std::atan2(h.y, h.x);
  const Vec3 d = rotate_y(rotate_z(wi, -a.phi_h), -a.theta_h);
  a.theta_d = std::acos(std::clamp(d.z, -1.0, 1.0));
  a.phi_d = std::atan2(d.y, d.x);
  return a;
}

std::pair<Vec3, Vec3> half_diff_directions(const HalfDiffAngles& a) {
  const double st = std::sin(a.theta_d);
  const Vec3 d{st * std::cos(a.phi_d), st * std::sin(a.phi_d), std::cos(a.theta_d)};
  const Vec3 wi = rotate_z(rotate_y(d, a.theta_h), a.phi_h);
  const Vec3 h = rotate_z(Vec3{std::sin(a.theta_h), 0.0, std::cos(a.theta_h)}, a.phi_h);
  const Vec3 wo = h * (2.0 * dot(wi, h)) - wi;  // the mirror of wi about h
  return {wi, wo};
}

// BRDFRead.cpp's theta_half_index, theta_diff_index and phi_diff_index.
MerlBin merl_bin(const HalfDiffAngles& a) {
  MerlBin b;
  b.theta_h = a.theta_h <= 0.0 ? 0 : clamp_index(std::sqrt(a.theta_h / (0.5 * pi)) * MerlTable::n_theta_h, MerlTable::n_theta_h);
  b.theta_d = clamp_index(a.theta_d / (0.5 * pi) * MerlTable::n_theta_d, MerlTable::n_theta_d);
  const double phi = a.phi_d < 0.0 ? a.phi_d + pi : a.phi_d;
  b.phi_d = clamp_index(phi / pi * MerlTable::n_phi_d, MerlTable::n_phi_d);
  return b;
}

HalfDiffAngles merl_bin_centre(int theta_h_i, int theta_d_i, int phi_d_i) {
  HalfDiffAngles a;
  const double s = (theta_h_i + 0.5) / MerlTable::n_theta_h;
  a.theta_h = s * s * 0.5 * pi;
  a.theta_d = (theta_d_i + 0.5) / MerlTable::n_theta_d * 0.5 * pi;
  a.phi_d = (phi_d_i + 0.5) / MerlTable::n_phi_d * pi;
  return a;
}

Result<MerlTable> parse_merl(std::span<const char> bytes, const std::string& name) {
  if (bytes.size() < 12) {
    return make_error(name + ": truncated: " + std::to_string(bytes.size()) + " bytes, a MERL file has a 12-byte header");
  }
  std::int32_t dims[3];
  std::memcpy(dims, bytes.data(), sizeof(dims));
  if (dims[0] != MerlTable::n_theta_h || dims[1] != MerlTable::n_theta_d || dims[2] != MerlTable::n_phi_d) {
    return make_error(name + ": header dims " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
                      std::to_string(dims[2]) + ", expected MERL's 90 x 90 x 180 (theta_h, theta_d, phi_d)");
  }
  if (bytes.size() != MerlTable::file_bytes) {
    return make_error(name + ": " + std::to_string(bytes.size()) + " bytes, expected " +
                      std::to_string(MerlTable::file_bytes) + " (a 12-byte header and three planes of 90 x 90 x 180 float64)" +
                      (bytes.size() < MerlTable::file_bytes ? ": truncated" : ": trailing bytes"));
  }
  MerlTable t;
  std::memcpy(t.stored.data(), bytes.data() + 12, 3 * MerlTable::count * sizeof(double));
  for (std::size_t i = 0; i < t.stored.size(); ++i) {
    if (!std::isfinite(t.stored[i])) {
      const std::size_t bin = i % MerlTable::count;
      const std::size_t th = bin / (MerlTable::n_theta_d * MerlTable::n_phi_d);
      const std::size_t td = (bin / MerlTable::n_phi_d) % MerlTable::n_theta_d;
      const std::size_t pd = bin % MerlTable::n_phi_d;
      return make_error(name + ": value of channel " + "RGB"[i / MerlTable::count] + " at bin (theta_h " +
                        std::to_string(th) + ", theta_d " + std::to_string(td) + ", phi_d " + std::to_string(pd) +
                        ") is not finite");
    }
  }
  return t;
}

Result<MerlTable> read_merl(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(path.string() + ": cannot read (" + ec.message() + ")");
  if (size != MerlTable::file_bytes) {
    // Read the header only, so that the message says what the file is.
    std::vector<char> head(static_cast<std::size_t>(std::min<std::uintmax_t>(size, 12)));
    std::ifstream f(path, std::ios::binary);
    f.read(head.data(), static_cast<std::streamsize>(head.size()));
    if (head.size() == 12) {
      auto r = parse_merl(head, path.string());  // refuses the dims, or else the size below
      if (!r) {
        const std::string& m = r.error().message;
        if (m.find("header dims") != std::string::npos) return r;
      }
    }
    return make_error(path.string() + ": " + std::to_string(size) + " bytes, expected " +
                      std::to_string(MerlTable::file_bytes) + " (a 12-byte header and three planes of 90 x 90 x 180 float64)" +
                      (size < MerlTable::file_bytes ? ": truncated" : ": trailing bytes"));
  }
  std::vector<char> bytes(MerlTable::file_bytes);
  std::ifstream f(path, std::ios::binary);
  if (!f.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    return make_error(path.string() + ": cannot read " + std::to_string(bytes.size()) + " bytes");
  }
  return parse_merl(bytes, path.string());
}

std::vector<char> encode_merl(const MerlTable& table) {
  std::vector<char> bytes(MerlTable::file_bytes);
  const std::int32_t dims[3] = {MerlTable::n_theta_h, MerlTable::n_theta_d, MerlTable::n_phi_d};
  std::memcpy(bytes.data(), dims, sizeof(dims));
  std::memcpy(bytes.data() + 12, table.stored.data(), 3 * MerlTable::count * sizeof(double));
  return bytes;
}

MerlTable measure_merl(const Brdf& brdf) {
  MerlTable t;
  for (int i = 0; i < MerlTable::n_theta_h; ++i) {
    for (int j = 0; j < MerlTable::n_theta_d; ++j) {
      for (int k = 0; k < MerlTable::n_phi_d; ++k) {
        const auto [wi, wo] = half_diff_directions(merl_bin_centre(i, j, k));
        const std::size_t idx = MerlTable::index(i, j, k);
        if (!(wi.z > 0.0 && wo.z > 0.0)) continue;  // stays -1: not measured
        const Rgb f = brdf.eval(normalize(wi), normalize(wo));
        t.stored[idx] = f.r / MerlTable::scale[0];
        t.stored[MerlTable::count + idx] = f.g / MerlTable::scale[1];
        t.stored[2 * MerlTable::count + idx] = f.b / MerlTable::scale[2];
      }
    }
  }
  return t;
}

}  // namespace shadelab
