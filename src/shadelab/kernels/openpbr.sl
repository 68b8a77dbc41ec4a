// openpbr: the reflection of OpenPBR Surface 1.1 (opaque, non-thin-walled) as its specification writes the layers and
// their albedo-scaled combination (shading dialect, sl.h). Source: "OpenPBR Surface", Academy Software Foundation,
// version 1.1 (academysoftwarefoundation.github.io/OpenPBR, sections "Microfacet model", "Base substrate", "Metal",
// "Glossy-diffuse", "Coat" with "Darkening", "View-dependent absorption", "Roughening", "Total internal reflection",
// and "Fuzz"). Transmission, subsurface, thin film, emission and the thin-walled mode are not modelled.
//
//   f = F_w f_fuzz + S_fuzz f_coated                                         (Fuzz, eq. fuzz-layering-approx)
//   f_coated = C f_coat + lerp(1, T S_coat, C) lerp(1, Delta, C delta) f_base        (Coat, coat_layering_formula
//       _with_albedo_scaling, Darkening: modulated_darkening_factor)
//   f_base = M f_metal + (1 - M) (f_dielectric + S_diel f_diffuse)          (Base substrate, Glossy-diffuse)
// with the scalings S of the layers below by the albedo E of the layer above, in two forms (OPENPBR_LAYERING_*):
//   view (the specification's equations):  S_diel = 1 - E_d(mu_o),  S_coat = 1 - E_c(mu_o),  S_fuzz = 1 - F_w E_f(mu_o)
//   reciprocal:  S_diel = (1 - E_d(mu_i)) (1 - E_d(mu_o)) / (1 - E_d_avg)   (Glossy-diffuse, the Kelemen form the
//       specification gives, with N = 1/(1 - E_avg): exact for the Lambertian base), S_coat = (1 - E_c(mu_i)) (1 -
//       E_c(mu_o)), S_fuzz = (1 - F_w E_f(mu_i)) (1 - F_w E_f(mu_o)) (symmetric attenuation, as adobe/openpbr-bsdf's
//       OPENPBR_RECIPROCAL_COAT_AND_FUZZ = 1; energy conserving, not preserving), and the darkening's K_s = (F(mu_i) +
//       F(mu_o)) / 2 in place of F(mu_o). The fuzz lobe itself (an LTC fit as a function of mu_o) stays non-reciprocal.
// The lobes, each with its source:
//   f_dielectric = specular_color F(V.H, eta_s') D G2 / (4 mu_i mu_o): anisotropic GGX, height-correlated Smith
//       (Microfacet model); eta_s' = (1 + e)/(1 - e), e = sqrt(clamp(specular_weight F_s, 0, 1)), F_s = ((eta_s -
//       1)/(eta_s + 1))^2 (Dielectric base, eq. modulated_ior), eta_s = lerp(n_b, n_b/n_c or n_c/n_b (TIR fix), C)
//       (Coat, eq. specular_ior_ratio and specular_ior_ratio_with_tir_fix); F the exact dielectric Fresnel.
//   f_metal = specular_weight F82(V.H) D G2 / (4 mu_i mu_o) + f_ms: F82 = F_schlick - mu (1 - mu)^6 / (mu_bar (1 -
//       mu_bar)^6) (F_schlick(mu_bar) - specular_color F_schlick(mu_bar)), mu_bar = 1/7, F0 = base_weight base_color
//       (Metal, Kutz et al. 2021); f_ms the Kulla-Conty multiple-scattering lobe (Kulla & Conty 2017, slides 16-19;
//       the specification's "Microfacet model" asks for such a compensation).
//   f_diffuse = w_d (rho/pi) A (1 + sigma s/t) + w_d (rho_ms/pi) (1 - E_FON(mu_i)) (1 - E_FON(mu_o)) / (1 - E_FON_avg):
//       EON (Portsmouth, Kutz, Hill 2024, "EON: A practical energy-preserving rough diffuse BRDF", eqs. for f_FON,
//       E_FON exact, E_FON_avg and rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg))), rho = base_color, w_d = base_weight,
//       sigma = base_diffuse_roughness.
//   f_coat = F(V.H, eta_c) D G2 / (4 mu_i mu_o), isotropic GGX, alpha_c = coat_roughness^2 (Coat).
//   T = coat_color^((1/mu_i^t + 1/mu_o^t)/2), mu^t = sqrt(1 - (1 - mu^2)/eta_c^2) (View-dependent absorption).
//   Delta = (1 - K)/(1 - E_b K), K = lerp(K_s, K_r, r_b), K_r = 1 - (1 - E_F(eta_c))/eta_c^2, r_b = lerp(lerp(1, r,
//       clamp(xi_s F_s)), r, M) (Darkening, eqs. general_darkening_formula .. base_roughness_estimate).
//   base roughness under the coat r' = lerp(r, min(1, r^4 + 2 r_c^4)^(1/4), C) (Roughening); alpha_t = r'^2 sqrt(2/(1
//       + (1 - a)^2)), alpha_b = (1 - a) alpha_t (Microfacet model, eq. openpbr-anisotropy-formula).
//   mu_i f_fuzz = fuzz_color E_f(mu_o, r_f) D_LTC(wi | mu_o, r_f): Zeltner, Burley, Chiang 2022, "Practical
//       Multiple-Scattering Sheen Using Linearly Transformed Cosines", the published fits of E_f (a Gaussian in mu)
//       and of the LTC matrix (a^-1, b^-1 rational in mu and r) (github.com/tizian/ltc-sheen, as MaterialX ships them).
// E_d, E_c: the directional albedo of the GGX reflection lobe with the exact dielectric Fresnel, from the table
// below (computed by openpbr_tables.cpp with the library's quadrature); E of the metal's Kulla-Conty lobe from
// ggx_energy.sl. Tables are read at the isotropic alpha = r'^2 (= sqrt((alpha_t^2 + alpha_b^2)/2)): exact without
// anisotropy, an approximation with it.

const int OPENPBR_LAYERING_VIEW = 0;
const int OPENPBR_LAYERING_RECIPROCAL = 1;
const real OPENPBR_ALPHA_MIN = 1e-4;  // the floor of the GGX alphas (roughness 0 is a mirror; f is a function)

// ---- The dielectric albedo table E_d(mu, alpha, e): e = (eta - 1)/(eta + 1) = sqrt(F0) in [0, 1] (eta in [1, inf]).
// Slices k = 0..S-1 at e_k = (k/(S-1))^2: uniform in sqrt(e), since at grazing E rises like sqrt(e) (F ~ 1 for
// V.H below ~2 sqrt(e)) and at normal incidence like e^2 = (sqrt(e))^4. In each slice the rows of ggx_energy.sl
// (32 alpha rows, alpha_j as there) and 32 mu columns per row at mu_i = kappa_j ((1 + 1/kappa_j)^(x_i^2) - 1), x_i =
// i/31, kappa_j = max(alpha_j, 0.1): ggx_energy's warp, with kappa held at 0.1 for sharp rows so that the Fresnel
// curve of the whole mu range keeps columns (the F = 1 table needs none there). Row 0 (alpha = 0) is the exact
// F(mu, eta_k) rather than texels. Catmull-Rom in x (quadratic ghosts), across rows (ggx_energy's weights) and across
// slices in sqrt(e) with quadratic ghost slices at both ends. The average table E_avg(e_k, alpha_j) = 2 integral
// E_row(mu) mu d(mu) of each row's interpolant (row 0: the hemispherical Fresnel average E_F(eta_k)), read with the
// same weights. Interpolation error against the converged integral: measured in kernels/openpbr_test.cpp and stated
// in docs/models/openpbr.md.
const int OPENPBR_DE_SLICES = 48;
const real OPENPBR_DE_KAPPA_MIN = 0.1;  // the columns' warp parameter floor

inline real openpbr_eta_from_e(real e) {
  return (1.0 + e) / (1.0 - e);
}

// F(mu, eta(e)) with its two ends: e = 0 no interface, e = 1 (eta = inf) a perfect mirror.
inline real openpbr_fresnel_e(real mu, real e) {
  if (e <= 0.0) return 0.0;
  if (e >= 1.0) return 1.0;
  return F_dielectric(mu, openpbr_eta_from_e(e));
}

inline real openpbr_de_texel_ghost(int k, int j, int i) {
  // Quadratic ghosts (3 p0 - 3 p1 + p2): the warp makes E(x) curve fast in the end cells, which a linear ghost bends.
  if (i < 0) {
    return 3.0 * dielectric_energy_texel(k, j, 0) - 3.0 * dielectric_energy_texel(k, j, 1) + dielectric_energy_texel(k, j, 2);
  }
  if (i > GGX_ENERGY_COLS - 1) {
    int n = GGX_ENERGY_COLS - 1;
    return 3.0 * dielectric_energy_texel(k, j, n) - 3.0 * dielectric_energy_texel(k, j, n - 1) +
           dielectric_energy_texel(k, j, n - 2);
  }
  return dielectric_energy_texel(k, j, i);
}

// The column coordinate of mu in the row of alpha_j (kappa = max(alpha_j, 0.1)), in units of columns; row 0 has none.
inline real openpbr_de_column(real alpha_j, real mu) {
  if (alpha_j <= 0.0) return 0.0;
  real kappa = max(alpha_j, OPENPBR_DE_KAPPA_MIN);
  real m = clamp(mu, 0.0, 1.0);
  return sqrt(log(1.0 + m / kappa) / log(1.0 + 1.0 / kappa)) * real(GGX_ENERGY_COLS - 1);
}

// The slice's e: e_k = (k/(S-1))^2.
inline real openpbr_de_slice_e(int k) {
  real q = real(k) / real(OPENPBR_DE_SLICES - 1);
  return q * q;
}

// E of slice k, row j at the column coordinate x (row 0: the exact Fresnel of the slice at mu).
inline real openpbr_de_row(int k, int j, real x, real mu) {
  if (j == 0) return openpbr_fresnel_e(mu, openpbr_de_slice_e(k));
  int i = int(min(floor(x), real(GGX_ENERGY_COLS - 2)));
  real s = x - real(i);
  real e = 0.0;
  for (int c = 0; c < 4; ++c) e = e + catmull_rom_weight(c, s) * openpbr_de_texel_ghost(k, j, i - 1 + c);
  return e;
}

// What a lookup at one (alpha, e) needs beyond mu: the ggx_energy rows (weights, kappas) and the slice weights.
struct OpenpbrDielectricRows {
  GgxEnergyRows r;
  int k;  // slices k - 1 .. k + 2
  real w0;
  real w1;
  real w2;
  real w3;
};

inline OpenpbrDielectricRows openpbr_dielectric_rows(real alpha, real e) {
  OpenpbrDielectricRows d;
  d.r = ggx_energy_rows(GGX_ENERGY_G_CORRELATED, alpha);
  real p = sqrt(clamp(e, 0.0, 1.0)) * real(OPENPBR_DE_SLICES - 1);
  d.k = int(min(floor(p), real(OPENPBR_DE_SLICES - 2)));
  real t = p - real(d.k);
  d.w0 = catmull_rom_weight(0, t);
  d.w1 = catmull_rom_weight(1, t);
  d.w2 = catmull_rom_weight(2, t);
  d.w3 = catmull_rom_weight(3, t);
  return d;
}

// E of slice k at mu for the prepared rows (columns x0..x3 of rows j-1..j+2).
inline real openpbr_de_slice(OpenpbrDielectricRows d, int k, real mu, real x0, real x1, real x2, real x3) {
  GgxEnergyRows r = d.r;
  real e = r.w1 * openpbr_de_row(k, r.j, x1, mu) + r.w2 * openpbr_de_row(k, r.j + 1, x2, mu);
  if (r.j > 0) e = e + r.w0 * openpbr_de_row(k, r.j - 1, x0, mu) + r.w3 * openpbr_de_row(k, r.j + 2, x3, mu);
  return e;
}

// Slice k with the quadratic ghosts at k = -1 and k = S.
inline real openpbr_de_slice_ghost(OpenpbrDielectricRows d, int k, real mu, real x0, real x1, real x2, real x3) {
  if (k < 0) {
    return 3.0 * openpbr_de_slice(d, 0, mu, x0, x1, x2, x3) - 3.0 * openpbr_de_slice(d, 1, mu, x0, x1, x2, x3) +
           openpbr_de_slice(d, 2, mu, x0, x1, x2, x3);
  }
  if (k > OPENPBR_DE_SLICES - 1) {
    int n = OPENPBR_DE_SLICES - 1;
    return 3.0 * openpbr_de_slice(d, n, mu, x0, x1, x2, x3) - 3.0 * openpbr_de_slice(d, n - 1, mu, x0, x1, x2, x3) +
           openpbr_de_slice(d, n - 2, mu, x0, x1, x2, x3);
  }
  return openpbr_de_slice(d, k, mu, x0, x1, x2, x3);
}

// E_d(mu) for the prepared (alpha, e).
inline real openpbr_dielectric_energy_at(OpenpbrDielectricRows d, real mu) {
  GgxEnergyRows r = d.r;
  real x0 = openpbr_de_column(r.kappa0, mu);  // kappa_n of GgxEnergyRows is alpha of row n (0 for row 0)
  real x1 = openpbr_de_column(r.kappa1, mu);
  real x2 = openpbr_de_column(r.kappa2, mu);
  real x3 = openpbr_de_column(r.kappa3, mu);
  real e = d.w0 * openpbr_de_slice_ghost(d, d.k - 1, mu, x0, x1, x2, x3) +
           d.w1 * openpbr_de_slice_ghost(d, d.k, mu, x0, x1, x2, x3) +
           d.w2 * openpbr_de_slice_ghost(d, d.k + 1, mu, x0, x1, x2, x3) +
           d.w3 * openpbr_de_slice_ghost(d, d.k + 2, mu, x0, x1, x2, x3);
  return clamp(e, 0.0, 1.0);
}

inline real openpbr_de_average_slice(OpenpbrDielectricRows d, int k) {
  GgxEnergyRows r = d.r;
  real e = r.w1 * dielectric_energy_average_texel(k, r.j) + r.w2 * dielectric_energy_average_texel(k, r.j + 1);
  if (r.j > 0) {
    e = e + r.w0 * dielectric_energy_average_texel(k, r.j - 1) + r.w3 * dielectric_energy_average_texel(k, r.j + 2);
  }
  return e;
}

inline real openpbr_de_average_ghost(OpenpbrDielectricRows d, int k) {
  if (k < 0) {
    return 3.0 * openpbr_de_average_slice(d, 0) - 3.0 * openpbr_de_average_slice(d, 1) + openpbr_de_average_slice(d, 2);
  }
  if (k > OPENPBR_DE_SLICES - 1) {
    int n = OPENPBR_DE_SLICES - 1;
    return 3.0 * openpbr_de_average_slice(d, n) - 3.0 * openpbr_de_average_slice(d, n - 1) +
           openpbr_de_average_slice(d, n - 2);
  }
  return openpbr_de_average_slice(d, k);
}

// E_d_avg = 2 integral E_d(mu) mu d(mu) for the prepared (alpha, e); at alpha = 0 the hemispherical Fresnel average.
inline real openpbr_dielectric_energy_average_at(OpenpbrDielectricRows d) {
  real e = d.w0 * openpbr_de_average_ghost(d, d.k - 1) + d.w1 * openpbr_de_average_ghost(d, d.k) +
           d.w2 * openpbr_de_average_ghost(d, d.k + 1) + d.w3 * openpbr_de_average_ghost(d, d.k + 2);
  return clamp(e, 0.0, 1.0);
}

// ---- EON (Portsmouth, Kutz, Hill 2024).
const real OPENPBR_FON_C1 = 0.5 - 2.0 / (3.0 * SL_PI);       // A = 1/(1 + c1 sigma) (EON eq. 4, "constant1_FON")
const real OPENPBR_FON_C2 = 2.0 / 3.0 - 28.0 / (15.0 * SL_PI);  // E_avg = A (1 + c2 sigma) (EON, "constant2_FON")

// E_FON(mu) exact: A + (B/pi) G(mu), G = S (acos(mu) - S mu) + (2/3)((S/mu)(1 - S^3) - S), S = sqrt(1 - mu^2) (EON,
// "E_FON_exact"); mu clamped to >= 1e-7 (G ~ S/mu (2/3)(1 - S^3) stays finite: 1 - S^3 ~ 1.5 mu^2).
inline real openpbr_eon_albedo(real mu, real a, real b) {
  real m = clamp(mu, 1e-7, 1.0);
  real s = sqrt(max(0.0, 1.0 - m * m));
  real g = s * (acos(m) - s * m) + (2.0 / 3.0) * ((s / m) * (1.0 - s * s * s) - s);
  return a + (b * SL_INV_PI) * g;
}

// ---- Fuzz (Zeltner et al. 2022), roughness r clamped to [0.01, 1] as the fits were made.
// E_f(mu, r): a Gaussian in mu with an offset, clamped to [0, 1] (ltc-sheen's "dir_albedo" fit).
inline real openpbr_fuzz_albedo(real mu, real r) {
  real x = clamp(mu, 0.0, 1.0);
  real y = clamp(r, 0.01, 1.0);
  real s = y * (0.0206607 + 1.58491 * y) / (0.0379424 + y * (1.32227 + y));
  real m = y * (-0.193854 + y * (-1.14885 + y * (1.7932 - 0.95943 * y * y))) / (0.046391 + y);
  real o = y * (0.000654023 + (-0.0207818 + 0.119681 * y) * y) / (1.26264 + y * (-1.92021 + y));
  real q = (x - m) / s;
  return clamp(exp(-0.5 * q * q) / (s * sqrt(2.0 * SL_PI)) + o, 0.0, 1.0);
}

// The LTC's inverse matrix [[a, 0, b], [0, a, 0], [0, 0, 1]] in the frame of wo (x toward wo's azimuth).
inline real openpbr_fuzz_ltc_a(real mu, real r) {
  real x = clamp(mu, 0.0, 1.0);
  real y = clamp(r, 0.01, 1.0);
  return (2.58126 * x + 0.813703 * y) * y / (1.0 + 0.310327 * x * x + 2.60994 * x * y);
}
inline real openpbr_fuzz_ltc_b(real mu, real r) {
  real x = clamp(mu, 0.0, 1.0);
  real y = clamp(r, 0.01, 1.0);
  return sqrt(1.0 - x) * (y - 1.0) * y * y * y / (0.0000254053 + 1.71228 * x - 1.71506 * x * y + 1.34174 * y * y);
}

// w in wo's azimuthal frame: x along wo's projection on the surface (any frame when wo is the normal).
inline vec3 openpbr_fuzz_frame(vec3 wo, vec3 w) {
  real l = sqrt(wo.x * wo.x + wo.y * wo.y);
  real cx = 1.0;
  real cy = 0.0;
  if (l > 0.0) {
    cx = wo.x / l;
    cy = wo.y / l;
  }
  return vec3(cx * w.x + cy * w.y, -cy * w.x + cx * w.y, w.z);
}

// D_LTC(w) = D_o(w'/|w'|) |M^-1| / |w'|^3 = w'.z a^2 / (pi |w'|^4), w' = M^-1 w (Heitz et al. 2016, eq. 2 with
// D_o = cos/pi), for w in wo's frame; 0 below the horizon (M^-1 keeps z, so the lobe stays in the hemisphere).
inline real openpbr_fuzz_ltc(real a, real b, vec3 w) {
  if (w.z <= 0.0) return 0.0;
  vec3 v = vec3(a * w.x + b * w.z, a * w.y, w.z);
  real l2 = dot(v, v);
  return v.z * SL_INV_PI * (a / l2) * (a / l2);
}

// ---- The model.
// Each rgb field starts a 16-byte row.
struct OpenpbrParams {
  rgb base_color;
  real base_weight;
  rgb specular_color;
  real base_metalness;
  rgb coat_color;
  real base_diffuse_roughness;
  rgb fuzz_color;
  real specular_weight;
  real specular_roughness;
  real specular_roughness_anisotropy;
  real specular_ior;
  real coat_weight;
  real coat_roughness;
  real coat_ior;
  real coat_darkening;
  real fuzz_weight;
  real fuzz_roughness;
  int layering;  // OPENPBR_LAYERING_*
};

struct OpenpbrState {
  int layering;
  real metalness;
  // Diffuse (EON): w_d rho A / pi, the compensation's w_d rho_ms / (pi (1 - E_avg)), A, B.
  rgb diffuse_ss;
  rgb diffuse_ms;
  real fon_a;
  real fon_b;
  real sigma;
  // Specular (dielectric and metal): anisotropic alphas; the dielectric's e; the metal's F0, F82 factor, weight.
  real alpha_t;
  real alpha_b;
  real spec_e;
  rgb specular_color;
  rgb metal_f0;
  rgb metal_a;  // (1 - specular_color) F_schlick(1/7) / (mu_bar (1 - mu_bar)^6)
  real specular_weight;
  rgb metal_ms_scale;  // specular_weight F_ms / (pi (1 - E_avg)), Kulla-Conty
  OpenpbrDielectricRows diel_rows;
  real diel_avg;  // E_d_avg (the reciprocal form's normalization)
  // Coat.
  real coat_weight;
  real coat_alpha;
  real coat_eta;
  real coat_e;
  rgb coat_color;
  OpenpbrDielectricRows coat_rows;
  real coat_k_r;      // K_r = 1 - (1 - E_F)/eta_c^2
  real coat_r_b;      // the base roughness estimate r_b
  rgb coat_e_b;       // the base's normal-incidence albedo E_b
  real coat_dark;     // C delta
  // Fuzz.
  real fuzz_weight;
  rgb fuzz_color;
  real fuzz_roughness;
};

// The metal's F82-tint Fresnel times specular_weight at V.H = c (Metal, F_metal = xi F82; fresnel.sl's F_schlick_f82,
// checked there against the specification's form).
inline rgb openpbr_f82(OpenpbrState s, real c) {
  return F_schlick_f82_rgb(c, s.metal_f0, s.specular_color) * s.specular_weight;
}

inline OpenpbrState openpbr_prepare(OpenpbrParams p) {
  OpenpbrState s;
  s.layering = p.layering;
  s.metalness = p.base_metalness;
  real c = p.coat_weight;
  // EON: A = 1/(1 + c1 sigma), B = sigma A, E_avg = A (1 + c2 sigma), rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg)).
  s.sigma = p.base_diffuse_roughness;
  s.fon_a = 1.0 / (1.0 + OPENPBR_FON_C1 * s.sigma);
  s.fon_b = s.sigma * s.fon_a;
  real e_avg = s.fon_a * (1.0 + OPENPBR_FON_C2 * s.sigma);
  rgb rho = p.base_color;
  s.diffuse_ss = rho * (p.base_weight * s.fon_a * SL_INV_PI);
  s.diffuse_ms = rgb(0.0);
  if (s.sigma > 0.0) {  // sigma = 0: E_FON = 1, no compensation (and 1 - E_avg = 0)
    rgb rho_ms = rho * rho * e_avg / (rgb(1.0) - rho * (1.0 - e_avg));
    s.diffuse_ms = rho_ms * (p.base_weight * SL_INV_PI / (1.0 - e_avg));
  }
  // Roughening under the coat, then OpenPBR's anisotropy mapping.
  real r = p.specular_roughness;
  real rc = p.coat_roughness;
  real r_coated = mix(r, pow(min(1.0, r * r * r * r + 2.0 * rc * rc * rc * rc), 0.25), c);
  real alpha = r_coated * r_coated;
  real an = 1.0 - p.specular_roughness_anisotropy;
  real at = alpha * sqrt(2.0 / (1.0 + an * an));
  s.alpha_t = max(at, OPENPBR_ALPHA_MIN);
  s.alpha_b = max(an * at, OPENPBR_ALPHA_MIN);
  real alpha_table = max(alpha, OPENPBR_ALPHA_MIN);
  // The dielectric's relative ior under the coat (TIR fix: n_c/n_b where n_c > n_b), then specular_weight's e.
  real nb = p.specular_ior;
  real nc = p.coat_ior;
  real eta_bc = nc > nb ? nc / nb : nb / nc;
  real eta_s = mix(nb, eta_bc, c);
  real q = (eta_s - 1.0) / (eta_s + 1.0);
  real f_s = q * q;
  real xi_fs = clamp(p.specular_weight * f_s, 0.0, 1.0);
  s.spec_e = sqrt(xi_fs);
  s.specular_color = p.specular_color;
  s.specular_weight = p.specular_weight;
  s.diel_rows = openpbr_dielectric_rows(alpha_table, s.spec_e);
  s.diel_avg = openpbr_dielectric_energy_average_at(s.diel_rows);
  // Metal: F0 = base_weight base_color; F82's factor; Kulla-Conty with F_avg = xi (F0 + (1 - F0)/21 - a/126).
  s.metal_f0 = p.base_color * p.base_weight;
  real mu_bar = 1.0 / 7.0;
  real mb = 1.0 - mu_bar;
  real mb5 = mb * mb * mb * mb * mb;
  rgb schlick_bar = s.metal_f0 + (rgb(1.0) - s.metal_f0) * mb5;
  s.metal_a = (rgb(1.0) - p.specular_color) * schlick_bar / (mu_bar * mb5 * mb);
  rgb f_avg = (s.metal_f0 + (rgb(1.0) - s.metal_f0) / 21.0 - s.metal_a / 126.0) * p.specular_weight;
  real e_ms_avg = ggx_energy_average_at(s.diel_rows.r);
  s.metal_ms_scale = rgb(0.0);
  if (e_ms_avg < 1.0) {  // 1 - E_avg vanishes only as alpha -> 0, where 1 - E(mu) vanishes too
    rgb f_ms = f_avg * f_avg * e_ms_avg / (rgb(1.0) - f_avg * (1.0 - e_ms_avg));
    s.metal_ms_scale = f_ms * (SL_INV_PI / (1.0 - e_ms_avg));
  }
  // Coat.
  s.coat_weight = c;
  s.coat_alpha = max(rc * rc, OPENPBR_ALPHA_MIN);
  s.coat_eta = nc;
  s.coat_e = (nc - 1.0) / (nc + 1.0);
  s.coat_color = p.coat_color;
  s.coat_rows = openpbr_dielectric_rows(s.coat_alpha, s.coat_e);
  OpenpbrDielectricRows mirror = openpbr_dielectric_rows(0.0, s.coat_e);
  s.coat_k_r = 1.0 - (1.0 - openpbr_dielectric_energy_average_at(mirror)) / (nc * nc);
  real r_d = mix(1.0, r, xi_fs);
  s.coat_r_b = mix(r_d, r, p.base_metalness);
  // E_b: the base's normal-incidence albedo, the slabs' albedos mixed by metalness: the glossy-diffuse slab
  // specular_color E_d(1) + (1 - E_d(1)) w_d rho (exact for the Lambertian base), the metal xi F0.
  real ed1 = openpbr_dielectric_energy_at(s.diel_rows, 1.0);
  rgb e_gd = p.specular_color * ed1 + rho * (p.base_weight * (1.0 - ed1));
  s.coat_e_b = mix(e_gd, s.metal_f0 * p.specular_weight, p.base_metalness);
  s.coat_dark = c * p.coat_darkening;
  // Fuzz.
  s.fuzz_weight = p.fuzz_weight;
  s.fuzz_color = p.fuzz_color;
  s.fuzz_roughness = p.fuzz_roughness;
  return s;
}

// The GGX single-scattering factor D G2 / (4 mu_i mu_o) of the base's anisotropic lobe.
inline real openpbr_base_dg(OpenpbrState s, vec3 wi, vec3 wo, vec3 h) {
  return D_ggx_aniso(h, s.alpha_t, s.alpha_b) * G2_ggx_correlated(wi, wo, s.alpha_t, s.alpha_b) /
         (4.0 * (wi.z * wo.z));
}

// The diffuse lobe f_diffuse (EON): s/t = s / max(mu_i, mu_o) where s = wi.wo - mu_i mu_o > 0, else s.
inline rgb openpbr_diffuse(OpenpbrState s, vec3 wi, vec3 wo) {
  real sv = dot(wi, wo) - wi.z * wo.z;
  real st = sv > 0.0 ? sv / max(wi.z, wo.z) : sv;
  rgb f = s.diffuse_ss * (1.0 + s.sigma * st);
  if (s.sigma > 0.0) {
    real ei = max(0.0, 1.0 - openpbr_eon_albedo(wi.z, s.fon_a, s.fon_b));
    real eo = max(0.0, 1.0 - openpbr_eon_albedo(wo.z, s.fon_a, s.fon_b));
    f = f + s.diffuse_ms * (ei * eo);
  }
  return f;
}

// The base substrate f_base = M f_metal + (1 - M) (f_dielectric + S_diel f_diffuse).
inline rgb openpbr_base(OpenpbrState s, vec3 wi, vec3 wo, vec3 h) {
  real dg = openpbr_base_dg(s, wi, wo, h);
  real vh = dot(wo, h);
  rgb f = rgb(0.0);
  if (s.metalness > 0.0) {
    rgb metal = openpbr_f82(s, vh) * dg;
    real ei = max(0.0, 1.0 - ggx_energy_at(s.diel_rows.r, wi.z));
    real eo = max(0.0, 1.0 - ggx_energy_at(s.diel_rows.r, wo.z));
    metal = metal + s.metal_ms_scale * (ei * eo);
    f = f + metal * s.metalness;
  }
  if (s.metalness < 1.0) {
    rgb diel = s.specular_color * (openpbr_fresnel_e(vh, s.spec_e) * dg);
    real eo = openpbr_dielectric_energy_at(s.diel_rows, wo.z);
    real scale = 1.0 - eo;
    if (s.layering == OPENPBR_LAYERING_RECIPROCAL) {
      real ei = openpbr_dielectric_energy_at(s.diel_rows, wi.z);
      scale = s.diel_avg < 1.0 ? (1.0 - ei) * (1.0 - eo) / (1.0 - s.diel_avg) : 0.0;
    }
    f = f + (diel + openpbr_diffuse(s, wi, wo) * scale) * (1.0 - s.metalness);
  }
  return f;
}

// The coat's transmittance along the refracted directions: coat_color^((1/mu_i^t + 1/mu_o^t)/2).
inline rgb openpbr_coat_transmittance(OpenpbrState s, real mu_i, real mu_o) {
  real e2 = s.coat_eta * s.coat_eta;
  real ti = sqrt(1.0 - (1.0 - mu_i * mu_i) / e2);
  real to = sqrt(1.0 - (1.0 - mu_o * mu_o) / e2);
  real x = 0.5 * (1.0 / ti + 1.0 / to);
  return rgb(pow(s.coat_color.r, x), pow(s.coat_color.g, x), pow(s.coat_color.b, x));
}

inline rgb openpbr_eval(OpenpbrState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  vec3 h = half_vector(wi, wo);
  rgb f = openpbr_base(s, wi, wo, h);
  bool reciprocal = s.layering == OPENPBR_LAYERING_RECIPROCAL;
  if (s.coat_weight > 0.0) {
    real fo = openpbr_fresnel_e(wo.z, s.coat_e);
    real k_s = reciprocal ? 0.5 * (openpbr_fresnel_e(wi.z, s.coat_e) + fo) : fo;
    real k = mix(k_s, s.coat_k_r, s.coat_r_b);
    rgb delta = rgb(1.0 - k) / (rgb(1.0) - s.coat_e_b * k);
    real eo = openpbr_dielectric_energy_at(s.coat_rows, wo.z);
    real scale = 1.0 - eo;
    if (reciprocal) scale = scale * (1.0 - openpbr_dielectric_energy_at(s.coat_rows, wi.z));
    rgb below = mix(rgb(1.0), openpbr_coat_transmittance(s, wi.z, wo.z) * scale, s.coat_weight) *
                mix(rgb(1.0), delta, s.coat_dark);
    // D from h's components (D_ggx_aniso with equal alphas), as gltf.sl's clearcoat.
    real coat = openpbr_fresnel_e(dot(wo, h), s.coat_e) * D_ggx_aniso(h, s.coat_alpha, s.coat_alpha) *
                V_smith_ggx_correlated(wo.z, wi.z, s.coat_alpha);
    f = f * below + rgb(s.coat_weight * coat);
  }
  if (s.fuzz_weight > 0.0) {
    real eo = s.fuzz_weight * openpbr_fuzz_albedo(wo.z, s.fuzz_roughness);
    real scale = 1.0 - eo;
    if (reciprocal) scale = scale * (1.0 - s.fuzz_weight * openpbr_fuzz_albedo(wi.z, s.fuzz_roughness));
    real a = openpbr_fuzz_ltc_a(wo.z, s.fuzz_roughness);
    real b = openpbr_fuzz_ltc_b(wo.z, s.fuzz_roughness);
    real d = openpbr_fuzz_ltc(a, b, openpbr_fuzz_frame(wo, wi));
    f = f * scale + s.fuzz_color * (eo * d / wi.z);
  }
  return f;
}
