// lambert: f_r = kd / pi (Lambert 1760; the lecture's "Pure Lambertian" slide: rho_d / pi).

struct LambertParams {
  rgb kd;
};

struct LambertState {
  rgb diffuse;  // kd / pi
};

inline LambertState lambert_prepare(LambertParams p) {
  LambertState s;
  s.diffuse = p.kd * SL_INV_PI;
  return s;
}

inline rgb lambert_eval(LambertState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  return s.diffuse;
}
