// common: constants and helpers every kernel may use (shading dialect, sl.h).

const real SL_PI = 3.14159265358979323846;
const real SL_INV_PI = 0.31830988618379067154;      // 1 / pi: the Lambertian BRDF of albedo 1
const real SL_INV_TWO_PI = 0.15915494309189533577;  // 1 / (2 pi)

// Divisors that vanish at the horizon (N.L in the original Phong forms, sqrt(N.L N.V) in Ward, L.H in the
// minimalist model) are clamped to 1e-12, so eval stays finite for every direction above the horizon; the
// clamp changes f only where the divisor is below 1e-12, a set of measure ~1e-12 of the hemisphere.
inline real safe_divisor(real x) {
  return x > 1e-12 ? x : 1e-12;
}

// Half vector of a reflection pair, on the side of the normal (+Z). wi == -wo has no half vector (a set of
// measure zero); +Z is returned there so that eval stays finite.
inline vec3 half_vector(vec3 wi, vec3 wo) {
  vec3 h = wi + wo;
  real len = length(h);
  if (len == 0.0) return vec3(0.0, 0.0, 1.0);
  h = h / len;
  return h.z < 0.0 ? -h : h;
}

// Catmull-Rom weight of the four samples p[-1], p[0], p[1], p[2] at t in [0, 1] (uniform knots): the
// interpolation of the tables (ggx_energy.sl, sheen.sl).
inline real catmull_rom_weight(int k, real t) {
  real t2 = t * t;
  real t3 = t2 * t;
  if (k == 0) return -0.5 * t3 + t2 - 0.5 * t;
  if (k == 1) return 1.5 * t3 - 2.5 * t2 + 1.0;
  if (k == 2) return -1.5 * t3 + 2.0 * t2 + 0.5 * t;
  return 0.5 * t3 - 0.5 * t2;
}

// log(1 + x) for x > -1 without the cancellation of forming 1 + x in single precision (GLSL and HLSL have no
// log1p): u = 1 + x rounded, then log(u) x / (u - 1), exact to a few ulps (Goldberg 1991, "What Every Computer
// Scientist Should Know About Floating-Point Arithmetic", theorem 4). The tables' warped coordinates need it: a
// coordinate log(1 + 0.01) formed as written loses 7e-6 of itself in float.
inline real log1p_accurate(real x) {
  real u = 1.0 + x;
  if (u == 1.0) return x;
  return log(u) * x / (u - 1.0);
}
