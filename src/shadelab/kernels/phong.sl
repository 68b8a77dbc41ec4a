// phong and phong-modified: the Phong lobe (R.L)^n about the mirror direction R of the viewer.
//   phong:          f_r = kd' + ks N (R.L)^n / (N.L)   (Phong 1975 as a BRDF; lecture 5, "Phong Reflection Model")
//   phong-modified: f_r = kd' + ks N (R.L)^n            (Lewis 1994; Lafortune & Willems 1994)
// normalization exact: N = (n + 1)/(2 pi) (phong) or (n + 2)/(2 pi) (phong-modified), the zoo's RDF rows
// (Schüler 2011), and kd' = kd/pi; normalization none: N = 1 and kd' = kd (the lecture's unnormalized form).

const int PHONG_NORMALIZATION_NONE = 0;
const int PHONG_NORMALIZATION_EXACT = 1;

struct PhongParams {
  rgb kd;
  rgb ks;
  real n;
  int normalization;  // PHONG_NORMALIZATION_*
  int modified;       // 0: phong (divides by N.L), 1: phong-modified
};

struct PhongState {
  rgb diffuse;    // kd' (kd/pi or kd)
  rgb ks_scaled;  // ks N
  real n;
  int modified;
};

// The constant N in front of the lobe (zoo, Phong rows).
inline real phong_normalization(real n, int normalization, int modified) {
  if (normalization == PHONG_NORMALIZATION_NONE) return 1.0;
  return modified != 0 ? (n + 2.0) * SL_INV_TWO_PI : (n + 1.0) * SL_INV_TWO_PI;
}

inline PhongState phong_prepare(PhongParams p) {
  PhongState s;
  s.diffuse = p.normalization == PHONG_NORMALIZATION_NONE ? p.kd : p.kd * SL_INV_PI;
  s.ks_scaled = p.ks * phong_normalization(p.n, p.normalization, p.modified);
  s.n = p.n;
  s.modified = p.modified;
  return s;
}

inline rgb phong_eval(PhongState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  real c = -wo.x * wi.x - wo.y * wi.y + wo.z * wi.z;  // R.L, R = reflect(V, N) = (-V.x, -V.y, V.z)
  if (c <= 0.0) return s.diffuse;
  real lobe = pow(c, s.n);
  if (s.modified != 0) return s.diffuse + s.ks_scaled * lobe;
  return s.diffuse + s.ks_scaled * (lobe / safe_divisor(wi.z));
}
