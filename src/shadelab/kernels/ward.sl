// ward and ward-anisotropic: Ward's Gaussian-slope lobe (Ward, "Measuring and Modeling Anisotropic
// Reflection", SIGGRAPH 1992, eq. 4 and 5a; lecture 5 "Ward Model"):
//   f_r = kd/pi + ks exp(-tan^2(theta_h)(cos^2(phi_h)/ax^2 + sin^2(phi_h)/ay^2)) / (4 pi ax ay sqrt(N.L N.V))
// (ward is ax = ay = alpha). Tangent = +X (alpha_x), bitangent = +Y (alpha_y).

struct WardParams {
  rgb kd;
  rgb ks;
  real alpha_x;
  real alpha_y;
};

struct WardState {
  rgb diffuse;  // kd / pi
  rgb ks;
  real ax;
  real ay;
};

inline WardState ward_prepare(WardParams p) {
  WardState s;
  s.diffuse = p.kd * SL_INV_PI;
  s.ks = p.ks;
  s.ax = p.alpha_x;
  s.ay = p.alpha_y;
  return s;
}

// The exponent's argument tan^2(theta_h)(cos^2/ax^2 + sin^2/ay^2) for a unit half vector h:
// tan^2(theta) cos^2(phi) = (h.x/h.z)^2 and tan^2(theta) sin^2(phi) = (h.y/h.z)^2.
inline real ward_slope_term(vec3 h, real ax, real ay) {
  real sx = h.x / (ax * h.z);
  real sy = h.y / (ay * h.z);
  return sx * sx + sy * sy;
}

inline rgb ward_eval(WardState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  vec3 h = half_vector(wi, wo);
  if (h.z <= 0.0) return s.diffuse;
  // Ward 1992 eq. 5a: exp(-tan^2 (...)) / (4 pi ax ay sqrt(N.L N.V))
  real value = exp(-ward_slope_term(h, s.ax, s.ay)) / (4.0 * SL_PI * s.ax * s.ay * sqrt(safe_divisor(wi.z * wo.z)));
  return s.diffuse + s.ks * value;
}
