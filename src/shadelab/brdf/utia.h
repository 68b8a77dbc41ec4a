// shadelab UTIA BRDF database `.bin` files (Filip & Vavra 2014, "Template-Based Sampling of Anisotropic BRDFs",
// Computer Graphics Forum 33(7); the 150 materials at btf.utia.cas.cz; the layout their reader, and the readers
// derived from it, use):
//
//   no header; float64 little-endian values, 3 planes (R, G, B), each of 6 x 48 x 6 x 48 values:
//   index = plane * 82944 + 13824 theta_i_k + 288 phi_i_k + 48 theta_v_k + phi_v_k
//   theta_i = 15 theta_i_k degrees (0 .. 75), phi_i = 7.5 phi_i_k degrees (0 .. 352.5), the same for the view.
// The files are 3 x 82944 x 8 = 1,990,656 bytes; any other size is refused (there is no magic number or header to
// check, so the size and finite values are all that identifies one). i is the light (shadelab's wi), v the viewer
// (wo). The values are read as linear RGB f_r in 1/sr, as the database's own reader does (no sRGB decoding).
//
// Evaluation: multilinear interpolation in (theta_i, phi_i, theta_v, phi_v) between the 16 measured neighbours
// (the database reader's weights, linear in each angle); phi periodic (352.5 degrees next to 0); theta beyond the last
// measured 75 degrees is held at 75 (constant up to the horizon; the database reader extrapolates linearly there,
// which goes negative for falling data); negative stored values (present in the published files) and the
// interpolated result are clamped at 0; on or below the horizon f = 0.
//
// sample / pdf: a one-sample mixture with an exact pdf: with probability 0.1 the cosine lobe; else, for the nearest
// measured view (6 x 48 of them), a piecewise-constant density over the light's (phi_i, cos theta_i) in 96 x 32
// cells, each cell's mass the luminance of f cos theta_i at its centre.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "shadelab/brdf/brdf.h"
#include "shadelab/core/error.h"
#include "shadelab/sampling/distribution.h"

namespace shadelab {

struct UtiaTable {
  static constexpr int n_theta = 6;     // 0, 15, ..., 75 degrees
  static constexpr int n_phi = 48;      // 0, 7.5, ..., 352.5 degrees
  static constexpr double theta_step_deg = 15.0;
  static constexpr double phi_step_deg = 7.5;
  static constexpr std::size_t plane = static_cast<std::size_t>(n_theta) * n_phi * n_theta * n_phi;  // 82944
  static constexpr std::size_t file_bytes = 3 * plane * 8;

  std::vector<double> values = std::vector<double>(3 * plane, 0.0);  // as stored

  static std::size_t index(int theta_i, int phi_i, int theta_v, int phi_v) {
    return static_cast<std::size_t>(phi_v) +
           static_cast<std::size_t>(n_phi) * (static_cast<std::size_t>(theta_v) +
           static_cast<std::size_t>(n_theta) * (static_cast<std::size_t>(phi_i) + static_cast<std::size_t>(n_phi) * static_cast<std::size_t>(theta_i)));
  }
  double value(int c, std::size_t idx) const { return values[static_cast<std::size_t>(c) * plane + idx]; }
};

// The direction at a measured (theta_k, phi_k).
Vec3 utia_direction(int theta_k, int phi_k);

// Refused: a size other than file_bytes (truncated or trailing), a NaN or infinite value (its channel and the four
// angles named).
Result<UtiaTable> parse_utia(std::span<const char> bytes, const std::string& name);
Result<UtiaTable> read_utia(const std::filesystem::path& path);
std::vector<char> encode_utia(const UtiaTable& table);
// Any BRDF evaluated at the measured directions (a virtual gonioreflectometer, for tests and seeds).
UtiaTable measure_utia(const Brdf& brdf);

class UtiaBrdf final : public Brdf {
 public:
  static constexpr double cosine_share = 0.1;
  static constexpr int phi_cells = 96;
  static constexpr int z_cells = 32;
  explicit UtiaBrdf(std::shared_ptr<const UtiaTable> table);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override;
  bool is_reciprocal() const override { return false; }
  bool is_tabulated() const override { return true; }  // interpolated between measured directions (brdf.h)
  const UtiaTable& table() const { return *m_table; }

 private:
  std::size_t view_index(const Vec3& wo) const;
  std::shared_ptr<const UtiaTable> m_table;
  std::vector<Distribution2D> m_views;  // per measured view (uniform where f is 0 for every light)
};

Result<BrdfPtr> read_utia_brdf(const std::filesystem::path& path);

}  // namespace shadelab
