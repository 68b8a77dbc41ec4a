// microfacet: normal distributions D and masking-shadowing G / visibility V terms, named after their
// equations (shading dialect, sl.h). cos_h is N.H (H the unit half vector). Distributions D are normalized
// over projected area, integral of D(h) cos(theta_h) d(omega_h) = 1, except D_blinn_phong_ndf, which is the
// zoo's NDF row (integral of D d(omega_h) = 1).

// Beckmann: exp(-tan^2(a)/m^2) / (pi m^2 cos^4(a)) (Cook & Torrance 1981 eq. 5 with the 1/pi of
// Walter et al. 2007 eq. 25). m is the RMS slope.
inline real D_beckmann(real cos_h, real m) {
  if (cos_h <= 0.0) return 0.0;
  real c2 = cos_h * cos_h;
  real tan2 = (1.0 - c2) / c2;
  return exp(-tan2 / (m * m)) / (SL_PI * m * m * c2 * c2);
}

// Blinn-Phong, heightfield normalization: (n + 2)/(2 pi) cos^n (the zoo's "Blinn-Phong (heightfield)" row).
inline real D_blinn_phong(real cos_h, real n) {
  return cos_h > 0.0 ? (n + 2.0) * SL_INV_TWO_PI * pow(cos_h, n) : 0.0;
}

// Blinn-Phong, NDF normalization: (n + 1)/(2 pi) cos^n (the zoo's "Blinn-Phong (NDF)" row).
inline real D_blinn_phong_ndf(real cos_h, real n) {
  return cos_h > 0.0 ? (n + 1.0) * SL_INV_TWO_PI * pow(cos_h, n) : 0.0;
}

// Cook-Torrance masking-shadowing: min(1, 2 NH NV / VH, 2 NH NL / VH) (Cook & Torrance 1981 eq. 6;
// the lecture's slide, where VH = LH).
inline real G_cook_torrance(real nh, real nv, real nl, real vh) {
  return min(1.0, min(2.0 * nh * nv / vh, 2.0 * nh * nl / vh));
}

// Kelemen & Szirmay-Kalos 2001: G / (4 NL NV) ~= 1 / (4 (L.H)^2), a visibility term V.
inline real V_kelemen(real lh) {
  return 0.25 / (lh * lh);
}

// Smith's Lambda for the Beckmann distribution: (erf(a) - 1)/2 + exp(-a^2)/(2 a sqrt(pi)),
// a = 1/(m tan(theta)) (Walter et al. 2007 eq. 27; Heitz 2014 eq. 80).
inline real lambda_beckmann(real cos_theta, real m) {
  if (cos_theta >= 1.0) return 0.0;
  real tan_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta)) / cos_theta;
  real a = 1.0 / (m * tan_theta);
  return 0.5 * (erf(a) - 1.0) + exp(-a * a) / (2.0 * a * sqrt(SL_PI));
}

// Height-correlated Smith masking-shadowing for Beckmann: 1 / (1 + Lambda(wi) + Lambda(wo)) (Heitz 2014,
// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 99).
inline real G_smith_beckmann(real cos_i, real cos_o, real m) {
  return 1.0 / (1.0 + lambda_beckmann(cos_i, m) + lambda_beckmann(cos_o, m));
}
