// shadelab MERL 100 BRDF files (Matusik, Pfister, Brand & McMillan 2003, "A Data-Driven Reflectance Model", ACM
// TOG 22(3); the layout the database's BRDFRead.cpp reads):
//
//   int32 dims[3] = {90, 90, 180}   (theta_h, theta_d, phi_d bins), little-endian
//   float64 R[90*90*180], G[...], B[...]   index = phi_d_i + 180 (theta_d_i + 90 theta_h_i)
//   f_r = stored x scale, scale = 1/1500 (R), 1.15/1500 (G), 1.66/1500 (B); a negative stored value: not measured
//
// Binning in Rusinkiewicz's half/difference angles (Rusinkiewicz 1998, "A New Change of Variables for Efficient
// BRDF Representation"; half_diff_angles below):
//   theta_h_i = floor(90 sqrt(theta_h / (pi/2)))   (dense near the specular peak)
//   theta_d_i = floor(90 theta_d / (pi/2))
//   phi_d_i   = floor(180 phi_d / pi), phi_d folded into [0, pi) by phi_d + pi (the same configuration for an
//               isotropic reciprocal BRDF: swapping wi and wo turns phi_d by pi)
// each clamped to its range. The files are 34,992,012 bytes; anything else is refused, naming the file and what
// is wrong, before anything beyond the file's own bytes is allocated.
//
// measure_merl is a virtual gonioreflectometer: any BRDF evaluated at each bin's centre (below), so that data of
// known parameters can be written in the format and fitted back.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "shadelab/brdf/brdf.h"
#include "shadelab/core/error.h"
#include "shadelab/core/vec.h"

namespace shadelab {

struct MerlTable {
  static constexpr int n_theta_h = 90;
  static constexpr int n_theta_d = 90;
  static constexpr int n_phi_d = 180;
  static constexpr std::size_t count = static_cast<std::size_t>(n_theta_h) * n_theta_d * n_phi_d;
  static constexpr std::size_t file_bytes = 12 + 3 * count * 8;
  static constexpr std::array<double, 3> scale = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

  // The file's values as stored (unscaled): the R plane, then G, then B; 3 x count.
  std::vector<double> stored = std::vector<double>(3 * count, -1.0);

  // f_r of channel c (0 R, 1 G, 2 B) in bin `index`, in 1/sr; negative: not measured.
  double value(int c, std::size_t index) const {
    const double s = stored[static_cast<std::size_t>(c) * count + index];
    return s < 0.0 ? -1.0 : s * scale[static_cast<std::size_t>(c)];
  }
  static std::size_t index(int theta_h_i, int theta_d_i, int phi_d_i) {
    return static_cast<std::size_t>(phi_d_i) +
           static_cast<std::size_t>(n_phi_d) * (static_cast<std::size_t>(theta_d_i) +
                                                static_cast<std::size_t>(n_theta_d) * static_cast<std::size_t>(theta_h_i));
  }
};

// Rusinkiewicz's coordinates of a pair: h = normalize(wi + wo) at (theta_h, phi_h); the difference vector
// d = R_y(-theta_h) R_z(-phi_h) wi at (theta_d, phi_d), phi_d in (-pi, pi] as atan2 gives it (not folded).
struct HalfDiffAngles {
  double theta_h = 0.0, phi_h = 0.0, theta_d = 0.0, phi_d = 0.0;
};
HalfDiffAngles half_diff_angles(const Vec3& wi, const Vec3& wo);
// The inverse: wi = R_z(phi_h) R_y(theta_h) d, wo = 2 (wi.h) h - wi.
std::pair<Vec3, Vec3> half_diff_directions(const HalfDiffAngles& a);

// The bin of a configuration (the formulas above; phi_d folded here).
struct MerlBin {
  int theta_h = 0, theta_d = 0, phi_d = 0;
};
MerlBin merl_bin(const HalfDiffAngles& a);
// The centre of a bin: theta_h = ((i + 0.5) / 90)^2 pi/2, theta_d = (j + 0.5) / 90 pi/2, phi_d = (k + 0.5) / 180 pi,
// phi_h = 0.
HalfDiffAngles merl_bin_centre(int theta_h_i, int theta_d_i, int phi_d_i);

// Parses a file's bytes; `name` names it in errors. Refused: a size other than file_bytes, dims other than
// {90, 90, 180}, a NaN or infinite value (the first one's channel and bin named).
Result<MerlTable> parse_merl(std::span<const char> bytes, const std::string& name);
// Reads and parses a file (its size is checked before it is read).
Result<MerlTable> read_merl(const std::filesystem::path& path);
// The bytes of a file (write them with image_io's write_file_atomically).
std::vector<char> encode_merl(const MerlTable& table);

// The virtual gonioreflectometer: stored = f_r(wi, wo) / scale at each bin's centre (half_diff_directions of
// merl_bin_centre), and -1 (not measured) where the centre puts wi or wo at or below the horizon, as a
// gonioreflectometer cannot measure there. A non-reciprocal model is measured as wi = light, wo = viewer.
MerlTable measure_merl(const Brdf& brdf);

}  // namespace shadelab
