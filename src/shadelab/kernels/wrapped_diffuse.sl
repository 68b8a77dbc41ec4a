// wrapped-diffuse: energy-conserving wrap lighting (McAuley, "Energy-Conserving Wrapped Diffuse", 2011;
// Lagarde, "PI or not to PI in game lighting equation", 2012):
//   f_r cos(theta_i) = kd (cos(theta_i) + w) / (pi (1 + w)^2),   i.e.   f_r = kd (N.L + w) / (pi (1 + w)^2 N.L)

struct WrappedDiffuseParams {
  rgb kd;
  real w;  // wrap amount in [0, 1]; 0 is Lambert
};

struct WrappedDiffuseState {
  rgb kd;
  real w;
};

inline WrappedDiffuseState wrapped_diffuse_prepare(WrappedDiffuseParams p) {
  WrappedDiffuseState s;
  s.kd = p.kd;
  s.w = p.w;
  return s;
}

inline rgb wrapped_diffuse_eval(WrappedDiffuseState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  // The 1/N.L diverges at the horizon for w > 0; clamped at 1e-12 so eval stays finite (the product
  // f cos(theta_i), which is what any estimator uses, is unaffected above that).
  real cos_i = safe_divisor(wi.z);
  real one_w = 1.0 + s.w;
  return s.kd * ((wi.z + s.w) / (SL_PI * one_w * one_w * cos_i));  // McAuley 2011
}
