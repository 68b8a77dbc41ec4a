// burley: the Disney diffuse of Burley 2012 ("Physically-Based Shading at Disney", SIGGRAPH course notes,
// section 5.3, eq. for f_d):
//   f_d = kd/pi (1 + (F_D90 - 1)(1 - cos(theta_l))^5) (1 + (F_D90 - 1)(1 - cos(theta_v))^5),
//   F_D90 = 0.5 + 2 roughness cos^2(theta_d), theta_d the angle between the light and the half vector.
// roughness is the artist's parameter in [0, 1] (Burley's; the specular alpha is its square). The form is
// symmetric in l and v (cos(theta_d) = L.H = V.H), so it is reciprocal; it is not energy conserving by
// design (the retro-reflection raises the albedo above kd at grazing for roughness 1, the Schlick-like
// darkening lowers it for roughness 0; docs/models/burley.md gives the measured figures).

struct BurleyParams {
  rgb kd;
  real roughness;
};

struct BurleyState {
  rgb diffuse;  // kd / pi
  real roughness;
};

inline BurleyState burley_prepare(BurleyParams p) {
  BurleyState s;
  s.diffuse = p.kd * SL_INV_PI;
  s.roughness = p.roughness;
  return s;
}

// Burley's factor (1 + (F_D90 - 1)(1 - N.L)^5)(1 + (F_D90 - 1)(1 - N.V)^5), without the 1/pi; lh = L.H.
// Filament's Fd_Burley is this factor over pi (Filament documentation, "Diffuse BRDF").
inline real burley_factor(real nl, real nv, real lh, real roughness) {
  real f90 = 0.5 + 2.0 * roughness * lh * lh;
  real ml = 1.0 - nl;
  real mv = 1.0 - nv;
  real light_scatter = 1.0 + (f90 - 1.0) * (ml * ml * ml * ml * ml);
  real view_scatter = 1.0 + (f90 - 1.0) * (mv * mv * mv * mv * mv);
  return light_scatter * view_scatter;
}

inline rgb burley_eval(BurleyState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  vec3 h = half_vector(wi, wo);
  real lh = 0.5 * (dot(wi, h) + dot(wo, h));
  // The product of the light and view factors is formed the same way for (wi, wo) and (wo, wi) up to the
  // order of two multiplications, which is commutative: f(wi, wo) == f(wo, wi) exactly.
  return s.diffuse * burley_factor(wi.z, wo.z, lh, s.roughness);
}
