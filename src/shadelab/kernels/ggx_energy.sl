// ggx_energy: the directional albedo E(mu, alpha) of the GGX single-scattering lobe with F = 1,
//   E(mu_o, alpha) = integral over the upper hemisphere of D(h) G2(wi, wo) / (4 mu_i mu_o) mu_i d(wi),
// and its cosine-weighted average E_avg(alpha) = 2 integral_0^1 E(mu, alpha) mu d(mu), read from tables
// (shading dialect, sl.h). Kulla & Conty 2017 (slides 16-19) need both for the multiple-scattering lobe;
// Filament's energy compensation needs E (its dfg.y). The tables are computed by the library's own
// quadrature (kernels/tables.cpp); the texel fetches ggx_energy_texel and ggx_energy_average_texel are the
// only language-specific piece: C++ reads the computed tables, a shader a const array of the same numbers.
//
// Layout: GGX_ENERGY_ROWS rows of roughness, alpha_j = c ((1 + amax/c)^(j/(R-1)) - 1) with c = 0.02 (uniform
// in log(alpha + c): dense at small alpha, where E changes fastest near grazing), row 0 at alpha = 0 (E = 1).
// Row j holds GGX_ENERGY_COLS values at mu_i = kappa_j ((1 + 1/kappa_j)^(x_i^2) - 1), x_i = i/(C-1),
// kappa_j = alpha_j: uniform in x = sqrt(log(1 + mu/kappa)/log(1 + 1/kappa)), which resolves the fall of E
// near mu ~ alpha and its square-root-like rise at grazing (node x = 0 holds E at mu = 1e-7).
// Interpolation: Catmull-Rom in x along a row (the end cells use linearly extrapolated ghost values) and in
// log(alpha + c) across rows (linear in the first cell, next to alpha = 0). Every weight applies to E and
// E_avg alike and E_avg_j is the exact integral of row j's interpolant, so 2 integral E mu d(mu) == E_avg
// holds for the interpolated values too (what makes the Kulla-Conty lobe restore the lost energy exactly);
// the interpolation error against E itself is below 3e-4 for alpha in [0.01, 1] and theta in [0, 89] deg
// (tested, ggx_energy_test.cpp). alpha is clamped to [0, 1].

const int GGX_ENERGY_G_SEPARABLE = 0;   // the table of G2 = G1 G1
const int GGX_ENERGY_G_CORRELATED = 1;  // the table of the height-correlated G2
const int GGX_ENERGY_ROWS = 32;
const int GGX_ENERGY_COLS = 32;
const real GGX_ENERGY_C = 0.02;
const real GGX_ENERGY_ALPHA_MAX = 1.2;  // the last row, beyond 1 so that alpha <= 1 has four rows around it
const real GGX_ENERGY_MU_MIN = 1e-7;    // node x = 0

inline real ggx_energy_row_alpha(int j) {
  real y = real(j) / real(GGX_ENERGY_ROWS - 1);
  return GGX_ENERGY_C * (exp(y * log(1.0 + GGX_ENERGY_ALPHA_MAX / GGX_ENERGY_C)) - 1.0);
}

// Texel i of row j with linearly extrapolated ghosts at i = -1 and i = C.
inline real ggx_energy_texel_ghost(int g, int j, int i) {
  if (i < 0) return 2.0 * ggx_energy_texel(g, j, 0) - ggx_energy_texel(g, j, 1);
  if (i > GGX_ENERGY_COLS - 1) {
    return 2.0 * ggx_energy_texel(g, j, GGX_ENERGY_COLS - 1) - ggx_energy_texel(g, j, GGX_ENERGY_COLS - 2);
  }
  return ggx_energy_texel(g, j, i);
}

// E of row j at mu: Catmull-Rom in the row's column coordinate x (C - 1), x = sqrt(log(1 + mu/kappa) *
// inv_log), kappa = alpha_j, inv_log = 1 / log(1 + 1/kappa). Row 0 (alpha = 0) is 1.
inline real ggx_energy_row_mapped(int g, int j, real kappa, real inv_log, real mu) {
  if (j == 0) return 1.0;
  real m = clamp(mu, 0.0, 1.0);
  real x = sqrt(log(1.0 + m / kappa) * inv_log) * real(GGX_ENERGY_COLS - 1);
  int i = int(min(floor(x), real(GGX_ENERGY_COLS - 2)));
  real s = x - real(i);
  real e = 0.0;
  for (int k = 0; k < 4; ++k) e = e + catmull_rom_weight(k, s) * ggx_energy_texel_ghost(g, j, i - 1 + k);
  return e;
}

inline real ggx_energy_row(int g, int j, real mu) {
  if (j == 0) return 1.0;
  real kappa = ggx_energy_row_alpha(j);
  return ggx_energy_row_mapped(g, j, kappa, 1.0 / log(1.0 + 1.0 / kappa), mu);
}

// The continuous row coordinate of alpha.
inline real ggx_energy_row_position(real alpha) {
  real a = clamp(alpha, 0.0, 1.0);
  return log(1.0 + a / GGX_ENERGY_C) / log(1.0 + GGX_ENERGY_ALPHA_MAX / GGX_ENERGY_C) *
         real(GGX_ENERGY_ROWS - 1);
}

// Weight of row j - 1 + k (k = 0..3) for alpha in the cell of row j at t: Catmull-Rom, linear in cell 0.
inline real ggx_energy_row_weight(int j, int k, real t) {
  if (j == 0) return k == 1 ? 1.0 - t : (k == 2 ? t : 0.0);
  return catmull_rom_weight(k, t);
}

// Everything about the four rows around one alpha that does not depend on mu: a model prepares it once,
// so that each lookup costs four logarithms and sixteen texel fetches.
struct GgxEnergyRows {
  int g;
  int j;  // rows j - 1 .. j + 2
  real w0;
  real w1;
  real w2;
  real w3;
  real kappa0;
  real kappa1;
  real kappa2;
  real kappa3;
  real inv_log0;
  real inv_log1;
  real inv_log2;
  real inv_log3;
};

inline real ggx_energy_inv_log(int row) {
  return row > 0 ? 1.0 / log(1.0 + 1.0 / ggx_energy_row_alpha(row)) : 0.0;
}

inline GgxEnergyRows ggx_energy_rows(int g, real alpha) {
  GgxEnergyRows r;
  r.g = g;
  real p = ggx_energy_row_position(alpha);
  r.j = int(min(floor(p), real(GGX_ENERGY_ROWS - 3)));
  real t = p - real(r.j);
  r.w0 = ggx_energy_row_weight(r.j, 0, t);
  r.w1 = ggx_energy_row_weight(r.j, 1, t);
  r.w2 = ggx_energy_row_weight(r.j, 2, t);
  r.w3 = ggx_energy_row_weight(r.j, 3, t);
  r.kappa0 = r.j > 1 ? ggx_energy_row_alpha(r.j - 1) : 0.0;
  r.kappa1 = r.j > 0 ? ggx_energy_row_alpha(r.j) : 0.0;
  r.kappa2 = ggx_energy_row_alpha(r.j + 1);
  r.kappa3 = ggx_energy_row_alpha(r.j + 2);
  r.inv_log0 = r.j > 1 ? ggx_energy_inv_log(r.j - 1) : 0.0;
  r.inv_log1 = ggx_energy_inv_log(r.j);
  r.inv_log2 = ggx_energy_inv_log(r.j + 1);
  r.inv_log3 = ggx_energy_inv_log(r.j + 2);
  return r;
}

// E(mu, alpha) for the prepared alpha.
inline real ggx_energy_at(GgxEnergyRows r, real mu) {
  real e = r.w1 * ggx_energy_row_mapped(r.g, r.j, r.kappa1, r.inv_log1, mu) +
           r.w2 * ggx_energy_row_mapped(r.g, r.j + 1, r.kappa2, r.inv_log2, mu);
  if (r.j > 0) {
    e = e + r.w0 * ggx_energy_row_mapped(r.g, r.j - 1, r.kappa0, r.inv_log0, mu) +
        r.w3 * ggx_energy_row_mapped(r.g, r.j + 2, r.kappa3, r.inv_log3, mu);
  }
  return e;
}

// E_avg(alpha) for the prepared alpha: the same weights over the rows' averages.
inline real ggx_energy_average_at(GgxEnergyRows r) {
  real e = r.w1 * ggx_energy_average_texel(r.g, r.j) + r.w2 * ggx_energy_average_texel(r.g, r.j + 1);
  if (r.j > 0) {
    e = e + r.w0 * ggx_energy_average_texel(r.g, r.j - 1) + r.w3 * ggx_energy_average_texel(r.g, r.j + 2);
  }
  return e;
}

inline real ggx_energy(int g, real mu, real alpha) {
  return ggx_energy_at(ggx_energy_rows(g, alpha), mu);
}

inline real ggx_energy_average(int g, real alpha) {
  return ggx_energy_average_at(ggx_energy_rows(g, alpha));
}
