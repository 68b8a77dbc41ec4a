// fresnel: exact unpolarized reflectance of a smooth interface, and Schlick's form (shading dialect, sl.h).
//
// Exact: F = (|r_s|^2 + |r_p|^2) / 2 with r_s = (n1 cos_i - n2 cos_t)/(n1 cos_i + n2 cos_t) and
// r_p = (n2 cos_i - n1 cos_t)/(n2 cos_i + n1 cos_t) (Born & Wolf, Principles of Optics, 1.5.2; the lecture's
// slide "Fresnel Equations"). For a conductor n2 = n + ik is complex; the real-arithmetic form below is the
// same expression expanded (a^2 + b^2 = |eta^2 - sin^2|, a = Re sqrt(eta^2 - sin^2); e.g. Lagarde, "Memo on
// Fresnel equations", 2013), tested against std::complex arithmetic in fresnel_test.cpp.
// Schlick: F = F0 + (1 - F0)(1 - cos)^5 (Schlick, "An Inexpensive BRDF Model for Physically-based Rendering",
// Eurographics 1994, eq. 24), F0 = ((n - 1)/(n + 1))^2 at normal incidence.

// Dielectric with relative index eta = n_transmitted / n_incident (real, > 0). cos_i is the cosine of the
// angle between the incident direction and the normal on the incident side; a negative cos_i means the
// light arrives from the other side, and the interface is seen with 1/eta. Total internal reflection gives 1.
inline real F_dielectric(real cos_i, real eta) {
  if (eta == 1.0) return 0.0;  // no interface (index-matched); avoids 0/0 and a spurious TIR at grazing
  real c = clamp(cos_i, -1.0, 1.0);
  real e = eta;
  if (c < 0.0) {  // arriving from the transmitted side: swap the media
    e = 1.0 / e;
    c = -c;
  }
  real sin2_i = max(0.0, 1.0 - c * c);
  real sin2_t = sin2_i / (e * e);  // Snell: sin_t = sin_i / eta
  if (sin2_t >= 1.0) return 1.0;   // total internal reflection
  real cos_t = sqrt(1.0 - sin2_t);
  real r_s = (c - e * cos_t) / (c + e * cos_t);
  real r_p = (e * c - cos_t) / (e * c + cos_t);
  return 0.5 * (r_s * r_s + r_p * r_p);
}

// Conductor (or absorbing dielectric) with complex relative index n + ik, k >= 0, seen from outside.
inline real F_conductor(real cos_i, real n, real k) {
  if (n == 1.0 && k == 0.0) return 0.0;  // no interface (index-matched); avoids 0/0 at grazing
  real c = clamp(cos_i, 0.0, 1.0);
  real c2 = c * c;
  real s2 = 1.0 - c2;
  real t0 = n * n - k * k - s2;
  real a2b2 = sqrt(t0 * t0 + 4.0 * n * n * k * k);  // |eta^2 - sin^2|
  // a = Re sqrt(eta^2 - sin^2), b = Im sqrt(...), a b = n k. When t0 < 0, a^2 + b^2 + t0 cancels, so a is
  // taken as n k / b there (the same quantity without the cancellation; b > 0 because a^2 + b^2 >= -t0 > 0).
  real a = t0 >= 0.0 ? sqrt(0.5 * (a2b2 + t0)) : n * k / sqrt(0.5 * (a2b2 - t0));
  real t1 = a2b2 + c2;
  real t2 = 2.0 * a * c;
  real r_s = (t1 - t2) / (t1 + t2);
  real t3 = c2 * a2b2 + s2 * s2;
  real t4 = t2 * s2;
  real r_p = r_s * (t3 - t4) / (t3 + t4);
  return 0.5 * (r_s + r_p);
}

inline rgb F_conductor_rgb(real cos_i, rgb n, rgb k) {
  return rgb(F_conductor(cos_i, n.r, k.r), F_conductor(cos_i, n.g, k.g), F_conductor(cos_i, n.b, k.b));
}

inline rgb F_dielectric_rgb(real cos_i, rgb eta) {
  return rgb(F_dielectric(cos_i, eta.r), F_dielectric(cos_i, eta.g), F_dielectric(cos_i, eta.b));
}

// Schlick's approximation from the reflectance at normal incidence.
inline real F_schlick(real cos_i, real f0) {
  real m = 1.0 - cos_i;
  real m2 = m * m;
  return f0 + (1.0 - f0) * (m2 * m2 * m);
}

inline rgb F_schlick_rgb(real cos_i, rgb f0) {
  real m = 1.0 - cos_i;
  real m2 = m * m;
  return f0 + (rgb(1.0) - f0) * (m2 * m2 * m);
}

// F82-tint metal: Schlick's F minus a mu (1 - mu)^6 term whose size a makes F at mu_bar = 1/7 (about 82
// degrees) equal tint times Schlick's F there, a = (1 - tint) F_s(mu_bar) / (mu_bar (1 - mu_bar)^6)
// (Hoffman 2023, "Generalization of Adobe's Fresnel Model"; OpenPBR Surface 1.1, section "Metal"). tint = 1
// is Schlick's F.
inline real F_schlick_f82(real cos_i, real f0, real tint) {
  real mu_bar = 1.0 / 7.0;
  real m = 1.0 - mu_bar;
  real m6 = m * m * m * m * m * m;
  real a = (1.0 - tint) * F_schlick(mu_bar, f0) / (mu_bar * m6);
  real c = clamp(cos_i, 0.0, 1.0);
  real n = 1.0 - c;
  real n6 = n * n * n * n * n * n;
  return F_schlick(c, f0) - a * c * n6;
}

inline rgb F_schlick_f82_rgb(real cos_i, rgb f0, rgb tint) {
  return rgb(F_schlick_f82(cos_i, f0.r, tint.r), F_schlick_f82(cos_i, f0.g, tint.g),
             F_schlick_f82(cos_i, f0.b, tint.b));
}

// Reflectance at normal incidence of a dielectric of relative index n: ((n - 1)/(n + 1))^2.
inline real f0_from_ior(real n) {
  real r = (n - 1.0) / (n + 1.0);
  return r * r;
}

// Reflectance at normal incidence of a conductor: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
inline real f0_from_ior_k(real n, real k) {
  return ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
}

// The Fresnel term a microfacet model was configured with (cook-torrance, ggx): exact dielectric (ior),
// exact conductor (ior, k), Schlick (f0) or none (F = 1).
const int FRESNEL_DIELECTRIC = 0;
const int FRESNEL_CONDUCTOR = 1;
const int FRESNEL_SCHLICK = 2;
const int FRESNEL_NONE = 3;

inline rgb F_by_kind_rgb(int kind, real cos_i, rgb ior, rgb k, rgb f0) {
  if (kind == FRESNEL_DIELECTRIC) return F_dielectric_rgb(cos_i, ior);
  if (kind == FRESNEL_CONDUCTOR) return F_conductor_rgb(cos_i, ior, k);
  if (kind == FRESNEL_SCHLICK) return F_schlick_rgb(cos_i, f0);
  return rgb(1.0);
}

// Hemispherical average F_avg = 2 integral_0^1 F(mu) mu d(mu) of that term (Kulla & Conty 2017, "Revisiting
// Physically Based Shading at Imageworks", slide 18). Schlick in closed form, (20 f0 + 1) / 21 (2 integral
// (1 - mu)^5 mu d(mu) = 1/21); the exact forms by composite Simpson's rule over 32 intervals in mu (error
// below 2e-6 absolute for the indices of fresnel_materials, tested against adaptive quadrature).
inline rgb F_average_by_kind_rgb(int kind, rgb ior, rgb k, rgb f0) {
  if (kind == FRESNEL_NONE) return rgb(1.0);
  if (kind == FRESNEL_SCHLICK) return (f0 * 20.0 + 1.0) / 21.0;
  rgb sum = rgb(0.0);
  for (int i = 0; i <= 32; ++i) {
    real mu = real(i) / 32.0;
    real w = (i == 0 || i == 32) ? 1.0 : ((i % 2 == 1) ? 4.0 : 2.0);
    sum = sum + F_by_kind_rgb(kind, mu, ior, k, f0) * (w * mu);
  }
  return sum * (2.0 / (3.0 * 32.0));
}
