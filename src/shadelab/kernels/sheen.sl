// sheen: the sheen lobe of glTF's KHR_materials_sheen (shading dialect, sl.h), and the table of its directional
// albedo that the albedo scaling of the layers below reads.
//   f_sheen = sheen_color D_charlie(h) V(wi, wo)
// D_charlie = (2 + 1/a) sin(theta_h)^(1/a) / (2 pi), a = sheen_roughness^2 (Estevez & Kulla 2017, "Production
//   Friendly Microfacet Sheen BRDF", eq. 2; KHR_materials_sheen, "Sheen BRDF"). Normalized over projected area:
//   integral of D cos(theta_h) d(omega_h) = (2 + 1/a) integral sin^(1/a + 1) cos d(theta) = 1 (tested).
// V = charlie: 1 / ((1 + Lambda(wo) + Lambda(wi)) 4 N.L N.V), Lambda the fitted Smith Lambda of Estevez & Kulla
//   (eq. 3 and table 1): Lambda(mu) = exp(L(mu)) for mu < 0.5, exp(2 L(0.5) - L(1 - mu)) above, L(x) = a0 / (1 +
//   a1 x^a2) + a3 x + a4, the five coefficients interpolated between their a = 0 and a = 1 fits with (1 - a)^2.
//   (The paper's "terminator softening" of Lambda is not in glTF's lobe and not here.)
// V = ashikhmin: 1 / (4 (N.L + N.V - N.L N.V)) (Ashikhmin & Premoze 2007 via Neubelt & Pettineo 2013, "Crafting a
//   Next-Gen Material Pipeline for The Order: 1886"; KHR_materials_sheen's alternative).
// sheen_roughness is clamped to [SHEEN_ROUGHNESS_MIN, 1] (0.07, as several engines clamp it): below it the lobe's
// albedo near grazing grows without bound and no table of 1e-4 accuracy is small enough for a shader.
//
// Neither visibility is a true Smith term of D_charlie, and the lobe's directional albedo E(mu, r) exceeds 1 near
// grazing at low roughness (charlie: 1.9 at r = 0.077, theta = 89 deg; ashikhmin: 3.3; computed, not fitted:
// docs/models/gltf.md), so glTF's albedo scaling 1 - max(sheen_color) E goes negative there: gltf.sl clamps it.
//
// The table (kernels/tables.cpp, by the library's quadrature): SHEEN_ENERGY_ROWS rows of roughness, r_j = r_min +
// c ((1 + (1 - r_min)/c)^(j/(R-1)) - 1), c = SHEEN_ENERGY_ROW_C (dense at low roughness, where E changes fastest);
// row j holds SHEEN_ENERGY_COLS values at mu_i = mu_min + k_j ((1 + (1 - mu_min)/k_j)^(x_i^2) - 1), x_i = i/(C-1),
// k_j = 2 r_j (dense near grazing, where E rises over a width about the roughness), mu_min = cos(89 deg). Two
// tables: visibility charlie (SHEEN_VISIBILITY_CHARLIE) then ashikhmin. Interpolation: Catmull-Rom in x along a row
// and in the row coordinate across rows, with quadratically extrapolated ghost values at every edge. The error of
// the interpolated E against the converged integral is below 1e-4 for r in [0.07, 1] and theta in [0, 85] deg (the
// range of the furnace claims), and below 3e-4 up to 89 deg, where E rises steepest at low roughness (tested,
// kernels/sheen_test.cpp); mu below mu_min reads mu_min.

const int SHEEN_VISIBILITY_CHARLIE = 0;
const int SHEEN_VISIBILITY_ASHIKHMIN = 1;
const int SHEEN_ENERGY_ROWS = 64;
const int SHEEN_ENERGY_COLS = 32;
const real SHEEN_ROUGHNESS_MIN = 0.07;
const real SHEEN_ENERGY_ROW_C = 0.1;
const real SHEEN_ENERGY_MU_MIN = 0.017452406437283512;  // cos(89 deg)

inline real sheen_alpha(real sheen_roughness) {
  real r = clamp(sheen_roughness, SHEEN_ROUGHNESS_MIN, 1.0);
  return r * r;
}

// D_charlie = (2 + 1/a) sin(theta_h)^(1/a) / (2 pi) (Estevez & Kulla 2017, eq. 2), from sin^2(theta_h) = s2 (for a
// unit half vector h.x^2 + h.y^2, which keeps the digits that 1 - cos^2 loses near the normal).
inline real D_charlie_sin2(real s2, real alpha) {
  if (s2 <= 0.0) return 0.0;  // pow(0, y) is undefined in GLSL; the limit is 0 (1/(2a) > 0)
  return (2.0 + 1.0 / alpha) * pow(min(s2, 1.0), 0.5 / alpha) * SL_INV_TWO_PI;
}
inline real D_charlie(real cos_h, real alpha) {
  if (cos_h <= 0.0) return 0.0;
  return D_charlie_sin2(1.0 - cos_h * cos_h, alpha);
}

// Estevez & Kulla's L(x): a0 / (1 + a1 x^a2) + a3 x + a4 with (a0..a4) = mix(fit at a = 1, fit at a = 0, (1 - a)^2)
// (their table 1: a = 0: 25.3245, 3.32435, 0.16801, -1.27393, -4.85967; a = 1: 21.5473, 3.82987, 0.19823, -1.97760,
// -4.32054). x in (0, 1].
inline real sheen_lambda_l(real x, real alpha) {
  real t = (1.0 - alpha) * (1.0 - alpha);
  real a0 = mix(21.5473, 25.3245, t);
  real a1 = mix(3.82987, 3.32435, t);
  real a2 = mix(0.19823, 0.16801, t);
  real a3 = mix(-1.97760, -1.27393, t);
  real a4 = mix(-4.32054, -4.85967, t);
  real xp = x > 0.0 ? pow(x, a2) : 0.0;  // pow(0, y) is undefined in GLSL; the limit is 0 (a2 > 0)
  return a0 / (1.0 + a1 * xp) + a3 * x + a4;
}

// Their fitted Smith Lambda of D_charlie (eq. 3): exp(L(mu)) below mu = 0.5, exp(2 L(0.5) - L(1 - mu)) above.
inline real sheen_lambda(real mu, real alpha) {
  real m = clamp(mu, 0.0, 1.0);
  if (m < 0.5) return exp(sheen_lambda_l(m, alpha));
  return exp(2.0 * sheen_lambda_l(0.5, alpha) - sheen_lambda_l(1.0 - m, alpha));
}

// The two visibility terms V = G / (4 N.L N.V); nl, nv > 0.
inline real V_sheen_charlie(real nl, real nv, real alpha) {
  return 1.0 / ((1.0 + (sheen_lambda(nv, alpha) + sheen_lambda(nl, alpha))) * 4.0 * nl * nv);
}
inline real V_sheen_ashikhmin(real nl, real nv) {
  return 1.0 / (4.0 * (nl + nv - nl * nv));
}

// D V of the sheen lobe (without sheen_color) for unit wi, wo above the horizon; 0 below.
inline real sheen_dv(int visibility, vec3 wi, vec3 wo, real alpha) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
  vec3 h = half_vector(wi, wo);
  real v = visibility == SHEEN_VISIBILITY_ASHIKHMIN ? V_sheen_ashikhmin(wi.z, wo.z) : V_sheen_charlie(wi.z, wo.z, alpha);
  if (h.z <= 0.0) return 0.0;
  return D_charlie_sin2(h.x * h.x + h.y * h.y, alpha) * v;
}

// ---- The directional albedo table E(mu, r) = integral of D V cos(theta_i) d(omega_i).

inline real sheen_energy_row_roughness(int j) {
  real y = real(j) / real(SHEEN_ENERGY_ROWS - 1);
  return SHEEN_ROUGHNESS_MIN +
         SHEEN_ENERGY_ROW_C * (exp(y * log(1.0 + (1.0 - SHEEN_ROUGHNESS_MIN) / SHEEN_ENERGY_ROW_C)) - 1.0);
}

// The continuous row coordinate of a roughness (clamped to the table's range).
inline real sheen_energy_row_position(real sheen_roughness) {
  real r = clamp(sheen_roughness, SHEEN_ROUGHNESS_MIN, 1.0);
  return log1p_accurate((r - SHEEN_ROUGHNESS_MIN) / SHEEN_ENERGY_ROW_C) /
         log(1.0 + (1.0 - SHEEN_ROUGHNESS_MIN) / SHEEN_ENERGY_ROW_C) * real(SHEEN_ENERGY_ROWS - 1);
}

// Texel i of row j with quadratically extrapolated ghosts at i = -1 and i = C.
inline real sheen_energy_texel_ghost(int v, int j, int i) {
  if (i < 0) {
    return 3.0 * sheen_energy_texel(v, j, 0) - 3.0 * sheen_energy_texel(v, j, 1) + sheen_energy_texel(v, j, 2);
  }
  if (i > SHEEN_ENERGY_COLS - 1) {
    int c = SHEEN_ENERGY_COLS - 1;
    return 3.0 * sheen_energy_texel(v, j, c) - 3.0 * sheen_energy_texel(v, j, c - 1) + sheen_energy_texel(v, j, c - 2);
  }
  return sheen_energy_texel(v, j, i);
}

// E of row j at mu: Catmull-Rom in the row's column coordinate x (C - 1), x = sqrt(log(1 + (mu - mu_min)/k) /
// log(1 + (1 - mu_min)/k)), k = 2 r_j.
inline real sheen_energy_row(int v, int j, real mu) {
  real k = 2.0 * sheen_energy_row_roughness(j);
  real m = clamp(mu, SHEEN_ENERGY_MU_MIN, 1.0);
  real x = sqrt(log1p_accurate((m - SHEEN_ENERGY_MU_MIN) / k) / log(1.0 + (1.0 - SHEEN_ENERGY_MU_MIN) / k)) *
           real(SHEEN_ENERGY_COLS - 1);
  int i = int(min(floor(x), real(SHEEN_ENERGY_COLS - 2)));
  real s = x - real(i);
  real e = 0.0;
  for (int q = 0; q < 4; ++q) e = e + catmull_rom_weight(q, s) * sheen_energy_texel_ghost(v, j, i - 1 + q);
  return e;
}

// The four rows around one roughness and their weights: prepared once per material.
struct SheenEnergyRows {
  int v;
  int j;  // rows j - 1 .. j + 2 (quadratic ghosts beyond the first and last row)
  real t;
};

inline SheenEnergyRows sheen_energy_rows(int visibility, real sheen_roughness) {
  SheenEnergyRows r;
  r.v = visibility;
  real p = sheen_energy_row_position(sheen_roughness);
  r.j = int(min(floor(p), real(SHEEN_ENERGY_ROWS - 2)));
  r.t = p - real(r.j);
  return r;
}

// Row jj's E at mu, with the quadratic ghosts beyond the table's rows.
inline real sheen_energy_row_ghost(int v, int jj, real mu) {
  if (jj < 0) return 3.0 * sheen_energy_row(v, 0, mu) - 3.0 * sheen_energy_row(v, 1, mu) + sheen_energy_row(v, 2, mu);
  if (jj > SHEEN_ENERGY_ROWS - 1) {
    int l = SHEEN_ENERGY_ROWS - 1;
    return 3.0 * sheen_energy_row(v, l, mu) - 3.0 * sheen_energy_row(v, l - 1, mu) + sheen_energy_row(v, l - 2, mu);
  }
  return sheen_energy_row(v, jj, mu);
}

// E(mu) for the prepared roughness.
inline real sheen_energy_at(SheenEnergyRows r, real mu) {
  real e = 0.0;
  for (int q = 0; q < 4; ++q) e = e + catmull_rom_weight(q, r.t) * sheen_energy_row_ghost(r.v, r.j - 1 + q, mu);
  return e;
}

inline real sheen_energy(int visibility, real mu, real sheen_roughness) {
  return sheen_energy_at(sheen_energy_rows(visibility, sheen_roughness), mu);
}
