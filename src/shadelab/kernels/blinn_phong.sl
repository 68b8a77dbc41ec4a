// blinn-phong and blinn-phong-modified: the Blinn-Phong lobe (N.H)^n.
//   blinn-phong:          f_r = kd' + ks N (N.H)^n / (N.L)   (Blinn 1977; lecture 5, "The Blinn-Phong Model")
//   blinn-phong-modified: f_r = kd' + ks N (N.H)^n            (lecture 5, "The Modified Blinn-Phong Model")
// N from the zoo (Schüler 2011), normalizing the RDF f_r cos(theta_i) with the viewer on the normal:
//   blinn-phong           exact (n+2)/(4 pi (2 - 2^(-n/2))),   lower (n+2)/(8 pi),   upper (n+4)/(8 pi)
//   blinn-phong-modified  exact (n+2)(n+4)/(8 pi (2^(-n/2)+n)), lower (n+6)/(8 pi), upper (n+8)/(8 pi)
// kd' = kd/pi when normalized, kd with normalization none (N = 1).

const int BLINN_PHONG_NORMALIZATION_NONE = 0;
const int BLINN_PHONG_NORMALIZATION_EXACT = 1;
const int BLINN_PHONG_NORMALIZATION_LOWER = 2;
const int BLINN_PHONG_NORMALIZATION_UPPER = 3;

struct BlinnPhongParams {
  rgb kd;
  rgb ks;
  real n;
  int normalization;  // BLINN_PHONG_NORMALIZATION_*
  int modified;       // 0: blinn-phong (divides by N.L), 1: blinn-phong-modified
};

struct BlinnPhongState {
  rgb diffuse;    // kd' (kd/pi or kd)
  rgb ks_scaled;  // ks N
  real n;
  int modified;
};

// The constant N in front of the lobe (zoo, Blinn-Phong rows and their bounds).
inline real blinn_phong_normalization(real n, int normalization, int modified) {
  real p = exp2(-0.5 * n);  // 2^(-n/2)
  if (normalization == BLINN_PHONG_NORMALIZATION_EXACT) {
    if (modified != 0) return (n + 2.0) * (n + 4.0) / (8.0 * SL_PI * (p + n));  // zoo, Blinn-Phong (modified)
    return (n + 2.0) / (4.0 * SL_PI * (2.0 - p));                               // zoo, Blinn-Phong
  }
  if (normalization == BLINN_PHONG_NORMALIZATION_LOWER) {
    return modified != 0 ? (n + 6.0) / (8.0 * SL_PI) : (n + 2.0) / (8.0 * SL_PI);
  }
  if (normalization == BLINN_PHONG_NORMALIZATION_UPPER) {
    return modified != 0 ? (n + 8.0) / (8.0 * SL_PI) : (n + 4.0) / (8.0 * SL_PI);
  }
  return 1.0;
}

inline BlinnPhongState blinn_phong_prepare(BlinnPhongParams p) {
  BlinnPhongState s;
  s.diffuse = p.normalization == BLINN_PHONG_NORMALIZATION_NONE ? p.kd : p.kd * SL_INV_PI;
  s.ks_scaled = p.ks * blinn_phong_normalization(p.n, p.normalization, p.modified);
  s.n = p.n;
  s.modified = p.modified;
  return s;
}

inline rgb blinn_phong_eval(BlinnPhongState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  vec3 h = half_vector(wi, wo);
  if (h.z <= 0.0) return s.diffuse;
  real lobe = pow(h.z, s.n);
  if (s.modified != 0) return s.diffuse + s.ks_scaled * lobe;
  return s.diffuse + s.ks_scaled * (lobe / safe_divisor(wi.z));
}
