// shadelab kernel tables: the numbers behind the kernels' texel fetches (kernels.h), computed once, at first
// use (thread-safe), by the library's own deterministic quadrature (numeric/quadrature.h); no table is
// hard-coded. The accessors give the exporter what it embeds in a shader: dimensions, the mapping from the
// kernel's arguments to texels (documented in the .sl file that reads the table) and the values.
#pragma once

#include <string>
#include <vector>

namespace shadelab::kernel {

// E(mu, alpha) and E_avg(alpha) of the GGX single-scattering lobe with F = 1 (ggx_energy.sl), for one Smith
// masking-shadowing form g (GGX_ENERGY_G_SEPARABLE or GGX_ENERGY_G_CORRELATED).
struct GgxEnergyTable {
  int g = 0;
  int rows = 0;                // alpha nodes
  int cols = 0;                // mu nodes per row
  std::vector<double> alpha;   // rows: alpha_j
  std::vector<double> mu;      // rows * cols: mu of each texel, row-major
  std::vector<double> e;       // rows * cols: E at (mu, alpha_j), row-major (the texels)
  std::vector<double> e_avg;   // rows: the exact integral 2 int E_row_j(mu) mu d(mu) of row j's interpolant
  std::vector<double> e_error; // rows * cols: the quadrature's estimated absolute error of each texel
  std::string mapping;         // one paragraph: how (mu, alpha) maps to texels (ggx_energy.sl)
};

const GgxEnergyTable& ggx_energy_table(int g);

}  // namespace shadelab::kernel
