// lafortune: the generalized cosine lobes of Lafortune, Foo, Torrance & Greenberg, "Non-Linear Approximation
// of Reflectance Functions", SIGGRAPH 1997, eq. 3-4 (lecture 5 "Empirical BRDF Representation"):
//   f_r = kd/pi + ks sum_j max(0, Cx_j L.x V.x + Cy_j L.y V.y + Cz_j L.z V.z)^n_j
// At most LAFORTUNE_MAX_LOBES lobes (a fixed size, so that the parameters fit a shader struct).

const int LAFORTUNE_MAX_LOBES = 8;

struct LafortuneParams {
  rgb kd;
  rgb ks;
  int count;  // lobes in use, 1 .. LAFORTUNE_MAX_LOBES
  real cx[LAFORTUNE_MAX_LOBES];
  real cy[LAFORTUNE_MAX_LOBES];
  real cz[LAFORTUNE_MAX_LOBES];
  real n[LAFORTUNE_MAX_LOBES];
};

struct LafortuneState {
  rgb diffuse;  // kd / pi
  LafortuneParams p;
};

inline LafortuneState lafortune_prepare(LafortuneParams p) {
  LafortuneState s;
  s.diffuse = p.kd * SL_INV_PI;
  s.p = p;
  return s;
}

inline rgb lafortune_eval(LafortuneState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  real sum = 0.0;
  for (int j = 0; j < LAFORTUNE_MAX_LOBES; ++j) {
    if (j < s.p.count) {
      real c = s.p.cx[j] * wi.x * wo.x + s.p.cy[j] * wi.y * wo.y + s.p.cz[j] * wi.z * wo.z;  // Lafortune 1997 eq. 4
      if (c > 0.0) sum += pow(c, s.p.n[j]);
    }
  }
  return s.diffuse + s.p.ks * sum;
}
