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

// E(mu, r) of the sheen lobe D_charlie V (sheen.sl), for both visibilities: texel (v, j, i) at e[(v * rows + j) *
// cols + i], v = SHEEN_VISIBILITY_CHARLIE or _ASHIKHMIN. Computed at first use (about 2 CPU-s: 2048 nested
// quadratures, shared by the two visibilities, on up to 8 threads, deterministic whatever their number).
struct SheenEnergyTable {
  int rows = 0;                   // roughness nodes
  int cols = 0;                   // mu nodes per row
  std::vector<double> roughness;  // rows: r_j (sheen roughness; alpha = r^2)
  std::vector<double> mu;         // rows * cols: mu of each texel, row-major
  std::vector<double> e;          // 2 * rows * cols: E at (mu, r_j) for charlie, then ashikhmin
  std::vector<double> e_error;    // 2 * rows * cols: the quadrature's estimated absolute error of each texel
  std::string mapping;            // one paragraph: how (mu, r) maps to texels (sheen.sl)
};

const SheenEnergyTable& sheen_energy_table();

// The directional albedo of the sheen lobe (D V cos integrated over the hemisphere of wi) at (mu, r) for both
// visibilities, by the table's own quadrature (outer adaptive Gauss-Kronrod over theta_i, inner 48-point
// Gauss-Legendre over the azimuth); [0] charlie, [1] ashikhmin. Exposed for `shadelab bake lut` at other resolutions.
struct SheenAlbedo {
  double e[2] = {0.0, 0.0};
  double error[2] = {0.0, 0.0};
};
SheenAlbedo sheen_directional_albedo(double mu, double sheen_roughness);

}  // namespace shadelab::kernel
