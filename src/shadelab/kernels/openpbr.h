// shadelab kernels: the openpbr kernel (openpbr.sl) compiled as C++ with its dielectric albedo table's texel fetches.
// openpbr.sl is not in kernels.h's list: the shader exporter does not embed it (the model has no shader, see
// docs/models/openpbr.md: its 48 x 32 x 32 table is larger than a GLSL ES uniform block), and kernels.h's
// dependants do not recompile for it. It reads kernels.h's kernels (fresnel, microfacet, ggx_energy).
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "shadelab/kernels/kernels.h"

namespace shadelab::kernel {

// E_d(mu, alpha, e) of the GGX reflection lobe with the exact dielectric Fresnel (openpbr.sl): texel (k, j, i) at
// [(k * 32 + j) * 32 + i], k the slice (e_k = k / (S - 1)), j the ggx_energy row, i its column; averages at
// [k * 32 + j]. Computed at first use (openpbr_tables.cpp).
const double* dielectric_energy_texels();
const double* dielectric_energy_average_texels();
inline real dielectric_energy_texel(int k, int row, int col) {
  static std::atomic<const double*> cache{nullptr};
  return ggx_energy_cached(cache, dielectric_energy_texels)[(k * 32 + row) * 32 + col];
}
inline real dielectric_energy_average_texel(int k, int row) {
  static std::atomic<const double*> cache{nullptr};
  return ggx_energy_cached(cache, dielectric_energy_average_texels)[k * 32 + row];
}

// clang-format off
#include "shadelab/kernels/openpbr.sl"
// clang-format on

// The table, for tests and for `bake lut`-like tools (its quadrature's error: dielectric_directional_albedo's
// estimate, and kernels/openpbr_test.cpp).
struct DielectricEnergyTable {
  int slices = 0;
  int rows = 0;
  int cols = 0;
  std::vector<double> e;        // slices * rows * cols (row 0 unused: the exact Fresnel)
  std::vector<double> e_avg;    // slices * rows
  double seconds = 0.0;         // wall time of the computation
};
const DielectricEnergyTable& dielectric_energy_table();

// E_d(mu, alpha, e) by the table's own quadrature at any point, with n x n Gauss-Legendre nodes over the visible
// normals (n = the table's 64 when 0); [0] the value, [1] the difference to the rule of n/2 (an error estimate).
std::pair<double, double> dielectric_directional_albedo(double mu, double alpha, double e, int n = 0);

}  // namespace shadelab::kernel
