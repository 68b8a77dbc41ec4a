// measured: a BRDF that evaluates a measured table (a MERL 100 file, brdf/merl.h).
//
// eval: trilinear interpolation in the table's own binning, between bin centres, in the continuous coordinates
//   x_h = 90 sqrt(theta_h / (pi/2)) - 1/2,  x_d = 90 theta_d / (pi/2) - 1/2,  x_p = 180 phi_d / pi - 1/2
// (bin i's centre at x = i; phi_d folded into [0, pi), brdf/merl.h). At the edges: theta_h and theta_d are
// clamped to the first and last centres (constant beyond them); phi_d is periodic with period pi, so x_p wraps
// (bin 179 is next to bin 0). A neighbour that was not measured (negative) drops out and the others' weights are
// renormalized; when all eight are missing (a grazing pair whose neighbouring centres are all below the horizon),
// the nearest lower theta_d row with a measured corner is used, constant in theta_d from there (and f = 0 if
// there is none). At or below the horizon f = 0 (the contract). The lookup is a
// function of the half/difference angles, which swapping wi and wo leaves alone up to phi_d -> phi_d + pi, so
// the model is reciprocal.
//
// sample / pdf: a one-sample mixture with an exact pdf: with probability 0.1 the cosine lobe; else, for the
// view's elevation bin (32 bins uniform in theta_o), a piecewise-constant density over the upper hemisphere in
// (phi_i - phi_o, cos theta_i) on 128 x 64 cells (equal solid angle), each cell's mass proportional to the
// luminance of f cos theta_i at its centre with wo at the bin's centre. The cosine share keeps the density
// positive wherever f can be.
//
// The registry's model `measured` (parameter `file`) builds it through load_measured_brdf, the one entry for
// measured data files, which keeps what it read by canonical path, modification time and size: a second BRDF of
// the same unchanged file shares the table and the samplers' tables of the first (no second read of 35 MB, no
// second sampler construction).
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "shadelab/brdf/brdf.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/sampling/distribution.h"

namespace shadelab {

class MeasuredBrdf final : public Brdf {
 public:
  static constexpr int view_bins = 32;
  static constexpr int phi_cells = 128;
  static constexpr int z_cells = 64;
  static constexpr double cosine_share = 0.1;

  explicit MeasuredBrdf(std::shared_ptr<const MerlTable> table);
  // Copies share the table and the samplers' tables (cheap).
  MeasuredBrdf(const MeasuredBrdf&) = default;

  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override;
  bool is_tabulated() const override { return true; }
  const MerlTable& table() const { return *m_table; }

 private:
  int view_bin(const Vec3& wo) const;
  std::shared_ptr<const MerlTable> m_table;
  // One per view bin, over (x = (phi_i - phi_o) / 2pi, y = cos theta_i); shared by copies.
  std::shared_ptr<const std::vector<Distribution2D>> m_views;
};

// Reads a measured BRDF file and builds its BRDF: today every file is read as MERL 100 (brdf/merl.h: its size
// and header are checked first); other measured formats are dispatched from here. Errors are one line naming the
// file. Loads are cached by (canonical path, modification time, size): while a BRDF of the file lives, or for the
// last four files loaded, another load of the unchanged file copies it without reading. Thread-safe.
Result<BrdfPtr> load_measured_brdf(const std::filesystem::path& path);
// How many times load_measured_brdf has read and parsed a file (not counting cache hits): for tests.
std::size_t measured_file_reads();

}  // namespace shadelab
