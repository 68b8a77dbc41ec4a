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

// GGX (Trowbridge-Reitz), anisotropic: D(h) = 1 / (pi ax ay (hx^2/ax^2 + hy^2/ay^2 + hz^2)^2) for h.z > 0
// (Trowbridge & Reitz 1975; Walter et al. 2007 eq. 33 for ax = ay; Heitz 2014, "Understanding the
// Masking-Shadowing Function", eq. 85). h is the unit half vector in the local frame (tangent +X).
inline real D_ggx_aniso(vec3 h, real ax, real ay) {
  if (h.z <= 0.0) return 0.0;
  real x = h.x / ax;
  real y = h.y / ay;
  real s = x * x + y * y + h.z * h.z;
  return 1.0 / (SL_PI * ax * ay * s * s);
}

// Perceptual roughness r to the GGX roughness alpha: alpha = r^2 (Burley 2012, "Physically-Based Shading at
// Disney", section 5.4; Karis 2013). The one conversion: the kernels, the C++ (brdf/microfacet.h) and the
// shaders all call it.
inline real alpha_from_roughness(real r) {
  return r * r;
}
// Its inverse, r = sqrt(alpha): the perceptual roughness the split sum's chain and tables are read at.
inline real roughness_from_alpha(real alpha) {
  return sqrt(alpha);
}

// GGX, isotropic: alpha^2 / (pi ((alpha^2 - 1) cos^2(theta_h) + 1)^2) (Walter et al. 2007 eq. 33, written
// as in Filament's documentation, "Specular D": D_GGX).
inline real D_ggx(real cos_h, real alpha) {
  if (cos_h <= 0.0) return 0.0;
  real a2 = alpha * alpha;
  real d = (a2 - 1.0) * cos_h * cos_h + 1.0;
  return a2 / (SL_PI * d * d);
}

// Smith's Lambda for GGX: (-1 + sqrt(1 + a^-2)) / 2 with a^-2 = (ax^2 wx^2 + ay^2 wy^2) / wz^2 (Heitz 2014
// eq. 86 and, for the anisotropic roughness projected on w's azimuth, eq. 80). Written t / (2 (1 + sqrt(1 + t)))
// (the same number without the cancellation of sqrt(1 + t) - 1 for small t). For w.z > 0.
inline real lambda_ggx(vec3 w, real ax, real ay) {
  real t = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / (w.z * w.z);
  return 0.5 * t / (1.0 + sqrt(1.0 + t));
}

// Smith masking G1(w) = 1 / (1 + Lambda(w)) (Heitz 2014 eq. 43).
inline real G1_ggx(vec3 w, real ax, real ay) {
  return 1.0 / (1.0 + lambda_ggx(w, ax, ay));
}

// Height-correlated Smith masking-shadowing for reflection: 1 / (1 + Lambda(wi) + Lambda(wo)) (Heitz 2014
// eq. 99). The sum is formed first, so G2(wi, wo) == G2(wo, wi) exactly.
inline real G2_ggx_correlated(vec3 wi, vec3 wo, real ax, real ay) {
  return 1.0 / (1.0 + (lambda_ggx(wi, ax, ay) + lambda_ggx(wo, ax, ay)));
}

// Separable Smith masking-shadowing: G1(wi) G1(wo) (Heitz 2014 eq. 98; Walter et al. 2007 eq. 23).
inline real G2_ggx_separable(vec3 wi, vec3 wo, real ax, real ay) {
  return G1_ggx(wi, ax, ay) * G1_ggx(wo, ax, ay);
}

// The height-correlated Smith-GGX visibility V = G2 / (4 N.L N.V) in the form Filament's documentation
// gives ("Geometric shadowing", V_SmithGGXCorrelated): 0.5 / (N.L sqrt(N.V^2 (1 - a^2) + a^2) +
// N.V sqrt(N.L^2 (1 - a^2) + a^2)); isotropic, nl and nv > 0. Tested equal to G2_ggx_correlated / (4 nl nv).
inline real V_smith_ggx_correlated(real nv, real nl, real alpha) {
  real a2 = alpha * alpha;
  real lv = nl * sqrt(nv * nv * (1.0 - a2) + a2);
  real ll = nv * sqrt(nl * nl * (1.0 - a2) + a2);
  return 0.5 / (lv + ll);
}
