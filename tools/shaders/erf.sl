// erf: the error function for shaders (GLSL and HLSL have none; the C++ kernels use std::erf). Abramowitz &
// Stegun, "Handbook of Mathematical Functions", 1964, formula 7.1.26: for x >= 0,
//   erf(x) = 1 - (a1 t + a2 t^2 + a3 t^3 + a4 t^4 + a5 t^5) exp(-x^2),  t = 1 / (1 + p x),
// with |error| <= 1.5e-7 (absolute); erf(-x) = -erf(x). Written in the shading dialect (sl.h) and tested
// against std::erf in erf_test.cpp; the exporter adds it to a shader whose kernels use erf.
inline real erf(real x) {
  real ax = abs(x);
  real t = 1.0 / (1.0 + 0.3275911 * ax);
  real poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
  real y = 1.0 - poly * exp(-ax * ax);
  return x < 0.0 ? -y : y;
}
