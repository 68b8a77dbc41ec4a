// minimalist-cook-torrance: f_r = kd/pi + ks (n + 1)(N.H)^n / (8 pi (L.H)^3) (Schüler, "An Efficient and
// Physically Plausible Real-Time Shading Model", ShaderX7 2.5, 2009; the zoo article's "Minimalist
// Cook-Torrance"): kd/pi + ks D F V with D = (n+1)/(2pi) (N.H)^n and the combined FV = 1/(4 (L.H)^3).

struct MinimalistCookTorranceParams {
  rgb kd;
  rgb ks;
  real n;
};

struct MinimalistCookTorranceState {
  rgb diffuse;  // kd / pi
  rgb ks;
  real n;
};

inline MinimalistCookTorranceState minimalist_cook_torrance_prepare(MinimalistCookTorranceParams p) {
  MinimalistCookTorranceState s;
  s.diffuse = p.kd * SL_INV_PI;
  s.ks = p.ks;
  s.n = p.n;
  return s;
}

inline rgb minimalist_cook_torrance_eval(MinimalistCookTorranceState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  vec3 h = half_vector(wi, wo);
  // L.H = V.H in exact arithmetic; their mean keeps f(wi, wo) == f(wo, wi) bit for bit.
  real lh = safe_divisor(0.5 * (dot(wi, h) + dot(wo, h)));
  // D F V = (n+1)/(2pi) (N.H)^n * 1/(4 (L.H)^3)   (ShaderX7, zoo article)
  return s.diffuse + s.ks * (D_blinn_phong_ndf(h.z, s.n) / (4.0 * lh * lh * lh));
}
