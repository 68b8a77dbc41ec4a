// sh9: order-3 (nine-coefficient) spherical harmonics of a radiance environment, evaluated as irradiance
// with the clamped-cosine band factors (Ramamoorthi & Hanrahan, "An Efficient Representation for Irradiance
// Environment Maps", SIGGRAPH 2001, eq. 7-8). The basis is the real SH with the Condon-Shortley phase, z the
// polar axis, in the order of Sloan, "Stupid Spherical Harmonics (SH) Tricks", GDC 2008 (envmap/sh.h):
//   Y0 = 1/(2 sqrt(pi)); Y1 = -c1 y, Y2 = c1 z, Y3 = -c1 x with c1 = sqrt(3/(4 pi));
//   Y4 = c2 xy, Y5 = -c2 yz, Y7 = -c2 xz with c2 = sqrt(15/(4 pi)); Y6 = c3 (3z^2 - 1), c3 = sqrt(5/(16 pi));
//   Y8 = c4 (x^2 - y^2), c4 = sqrt(15/(16 pi)).
// The coefficients c_i are RGB, as `shadelab bake sh --json` writes them (radiance units of the map).

const real SH9_C0 = 0.28209479177387814;  // 1 / (2 sqrt(pi))
const real SH9_C1 = 0.48860251190291992;  // sqrt(3 / (4 pi))
const real SH9_C2 = 1.09254843059207907;  // sqrt(15 / (4 pi))
const real SH9_C3 = 0.31539156525252001;  // sqrt(5 / (16 pi))
const real SH9_C4 = 0.54627421529603953;  // sqrt(15 / (16 pi))

struct Sh9Coefficients {
  rgb c[9];
};

struct Sh9Basis {
  real y[9];
};

// The nine basis functions at a unit direction n.
inline Sh9Basis sh9_basis(vec3 n) {
  Sh9Basis b;
  b.y[0] = SH9_C0;
  b.y[1] = -SH9_C1 * n.y;
  b.y[2] = SH9_C1 * n.z;
  b.y[3] = -SH9_C1 * n.x;
  b.y[4] = SH9_C2 * n.x * n.y;
  b.y[5] = -SH9_C2 * n.y * n.z;
  b.y[6] = SH9_C3 * (3.0 * n.z * n.z - 1.0);
  b.y[7] = -SH9_C2 * n.x * n.z;
  b.y[8] = SH9_C4 * (n.x * n.x - n.y * n.y);
  return b;
}

// sum_i A_l(i) c_i Y_i(n), with the band factors a0, a1, a2 of bands l = 0, 1, 2.
inline rgb sh9_evaluate(Sh9Coefficients sh, vec3 n, real a0, real a1, real a2) {
  Sh9Basis b = sh9_basis(n);
  rgb sum = rgb(0.0);
  for (int i = 0; i < 9; ++i) {
    real a = i == 0 ? a0 : (i < 4 ? a1 : a2);
    sum += sh.c[i] * (b.y[i] * a);
  }
  return sum;
}

// Irradiance E(n) in W/m^2 (radiometric): band factors (pi, 2 pi/3, pi/4) (Ramamoorthi & Hanrahan eq. 8).
inline rgb sh9_irradiance(Sh9Coefficients sh, vec3 n) {
  return sh9_evaluate(sh, n, SL_PI, 2.0 * SL_PI / 3.0, 0.25 * SL_PI);
}

// Game units, E/pi: the exit radiance of a white Lambert surface; band factors (1, 2/3, 1/4). A diffuse
// surface of albedo kd shows kd * sh9_irradiance_game(sh, n).
inline rgb sh9_irradiance_game(Sh9Coefficients sh, vec3 n) {
  return sh9_evaluate(sh, n, 1.0, 2.0 / 3.0, 0.25);
}

// Wrapped diffuse of wrap w in game units: band factors (1, (2 - w)/3, (1 - w)^2/4) (Hill, "Righting Wrap",
// 2011; the PI-or-not article), the bands of max(0, cos + w) / (pi (1 + w)^2); w = 0 is sh9_irradiance_game.
inline rgb sh9_irradiance_game_wrapped(Sh9Coefficients sh, vec3 n, real w) {
  return sh9_evaluate(sh, n, 1.0, (2.0 - w) / 3.0, 0.25 * (1.0 - w) * (1.0 - w));
}
