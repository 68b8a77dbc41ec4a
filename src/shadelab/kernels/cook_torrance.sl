// cook-torrance: a microfacet specular lobe over a Lambertian base, f_r = kd/pi + ks F D G / (c (N.L)(N.V)).
//   form microfacet: c = 4 and D normalized (Walter et al., "Microfacet Models for Refraction", EGSR 2007, eq. 20)
//   form 1981:       c = pi and the paper's D without the 1/pi (Cook & Torrance 1981 eq. 4), i.e. 4x microfacet
// d: beckmann (m) | blinn-phong (n) | ggx (alpha = m); g: cook-torrance | kelemen | smith (height-correlated,
// for Beckmann's D or, with d = ggx, for GGX's: Heitz 2014 eq. 99);
// f: dielectric (ior) | conductor (ior, k) | schlick (f0) | none. F is evaluated at L.H.

const int COOK_TORRANCE_D_BECKMANN = 0;
const int COOK_TORRANCE_D_BLINN_PHONG = 1;
const int COOK_TORRANCE_D_GGX = 2;
const int COOK_TORRANCE_G_COOK_TORRANCE = 0;
const int COOK_TORRANCE_G_KELEMEN = 1;
const int COOK_TORRANCE_G_SMITH = 2;
const int COOK_TORRANCE_F_DIELECTRIC = 0;
const int COOK_TORRANCE_F_CONDUCTOR = 1;
const int COOK_TORRANCE_F_SCHLICK = 2;
const int COOK_TORRANCE_F_NONE = 3;
const int COOK_TORRANCE_FORM_MICROFACET = 0;
const int COOK_TORRANCE_FORM_1981 = 1;

struct CookTorranceParams {
  rgb kd;
  rgb ks;
  real m;  // Beckmann RMS slope (d beckmann; and the Smith term), or GGX alpha (d ggx)
  real n;  // Blinn-Phong exponent (d blinn-phong), n = 2/m^2 - 2
  int d;   // COOK_TORRANCE_D_*
  int g;   // COOK_TORRANCE_G_*
  int f;   // COOK_TORRANCE_F_*
  rgb ior;
  rgb k;
  rgb f0;
  int form;  // COOK_TORRANCE_FORM_*
};

struct CookTorranceState {
  rgb diffuse;  // kd / pi
  CookTorranceParams p;
};

inline CookTorranceState cook_torrance_prepare(CookTorranceParams p) {
  CookTorranceState s;
  s.diffuse = p.kd * SL_INV_PI;
  s.p = p;
  return s;
}

inline rgb cook_torrance_fresnel(CookTorranceParams p, real cos_i) {
  if (p.f == COOK_TORRANCE_F_DIELECTRIC) return F_dielectric_rgb(cos_i, p.ior);
  if (p.f == COOK_TORRANCE_F_CONDUCTOR) return F_conductor_rgb(cos_i, p.ior, p.k);
  if (p.f == COOK_TORRANCE_F_SCHLICK) return F_schlick_rgb(cos_i, p.f0);
  return rgb(1.0);
}

inline real cook_torrance_distribution(CookTorranceParams p, real cos_h) {
  if (p.d == COOK_TORRANCE_D_GGX) return D_ggx(cos_h, p.m);
  return p.d == COOK_TORRANCE_D_BECKMANN ? D_beckmann(cos_h, p.m) : D_blinn_phong(cos_h, p.n);
}

inline rgb cook_torrance_eval(CookTorranceState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  vec3 h = half_vector(wi, wo);
  real nl = wi.z;
  real nv = wo.z;
  real nh = h.z;
  // L.H == V.H for a reflection pair in exact arithmetic; their mean keeps f(wi, wo) == f(wo, wi) exactly.
  real lh = 0.5 * (dot(wi, h) + dot(wo, h));
  if (nh <= 0.0 || lh <= 0.0) return s.diffuse;
  real d = cook_torrance_distribution(s.p, nh);
  if (d == 0.0) return s.diffuse;
  // Visibility V = G / (4 N.L N.V), the microfacet form's denominator folded in.
  real v = 0.0;
  if (s.p.g == COOK_TORRANCE_G_COOK_TORRANCE) {
    v = G_cook_torrance(nh, nv, nl, lh) / (4.0 * nl * nv);
  } else if (s.p.g == COOK_TORRANCE_G_KELEMEN) {
    v = V_kelemen(lh);
  } else if (s.p.d == COOK_TORRANCE_D_GGX) {
    v = G2_ggx_correlated(wi, wo, s.p.m, s.p.m) / (4.0 * nl * nv);
  } else {
    v = G_smith_beckmann(nl, nv, s.p.m) / (4.0 * nl * nv);
  }
  // The 1981 form: F (pi D) G / (pi N.L N.V) = 4 F D G / (4 N.L N.V).
  real form_scale = s.p.form == COOK_TORRANCE_FORM_1981 ? 4.0 : 1.0;
  return s.diffuse + s.p.ks * cook_torrance_fresnel(s.p, lh) * (d * v * form_scale);
}
