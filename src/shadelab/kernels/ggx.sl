// ggx: the GGX (Trowbridge-Reitz) microfacet model engines ship, over a Lambertian base (shading dialect, sl.h):
//   f_r = kd/pi + ks (F(L.H) D(h) G2(wi, wo) / (4 N.L N.V)  [+ f_ms])
// D = D_ggx_aniso (alpha_x, alpha_y; microfacet.sl), G2 = height-correlated (Heitz 2014 eq. 99) or separable
// (eq. 98) Smith, F = F_by_kind_rgb (fresnel.sl: schlick f0 | dielectric ior | conductor ior, k | none).
// ms = kulla-conty adds the multiple-scattering lobe of Kulla & Conty 2017 ("Revisiting Physically Based
// Shading at Imageworks", SIGGRAPH course, slides 16-19; the lobe shape is Kelemen & Szirmay-Kalos 2001's)
//   f_ms = F_ms (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg)),  F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)),
// E(mu) the directional albedo of the lobe with F = 1 and E_avg = 2 integral E(mu) mu d(mu) its average, read
// from the tables of ggx_energy.sl at alpha = sqrt(alpha_x alpha_y) (exact for isotropic roughness; an
// approximation when alpha_x != alpha_y). With F = 1 the lobe restores exactly the energy the single-
// scattering lobe loses (up to the tables' interpolation error), and it is symmetric in wi and wo.

const int GGX_MS_NONE = 0;
const int GGX_MS_KULLA_CONTY = 1;

struct GgxParams {
  rgb kd;
  rgb ks;        // a tint of the specular lobe (1: the plain model; Cycles' Glossy BSDF colour)
  real alpha_x;  // GGX roughness along the tangent (alpha = perceptual roughness squared)
  real alpha_y;  // and along the bitangent
  int f;         // FRESNEL_* (fresnel.sl)
  rgb f0;
  rgb ior;
  rgb k;
  int g;   // GGX_ENERGY_G_* (ggx_energy.sl): height-correlated or separable Smith
  int ms;  // GGX_MS_*
};

struct GgxState {
  rgb diffuse;  // kd / pi
  GgxParams p;
  GgxEnergyRows ms_rows;  // the energy tables' rows at alpha = sqrt(alpha_x alpha_y)
  rgb ms_scale;           // ks F_ms / (pi (1 - E_avg)); 0 without multiple scattering
};

inline GgxState ggx_prepare(GgxParams p) {
  GgxState s;
  s.diffuse = p.kd * SL_INV_PI;
  s.p = p;
  s.ms_rows = ggx_energy_rows(p.g, sqrt(p.alpha_x * p.alpha_y));
  s.ms_scale = rgb(0.0);
  if (p.ms == GGX_MS_KULLA_CONTY) {
    real e_avg = ggx_energy_average_at(s.ms_rows);
    // 1 - E_avg vanishes only as alpha -> 0, where 1 - E(mu) vanishes too and the lobe is 0.
    if (1.0 - e_avg > 1e-12) {
      rgb f_avg = F_average_by_kind_rgb(p.f, p.ior, p.k, p.f0);
      rgb f_ms = f_avg * f_avg * e_avg / (rgb(1.0) - f_avg * (1.0 - e_avg));
      s.ms_scale = p.ks * f_ms * (SL_INV_PI / (1.0 - e_avg));
    }
  }
  return s;
}

// The single-scattering specular lobe F D G2 / (4 N.L N.V), for wi and wo above the horizon.
inline rgb ggx_single_scattering(GgxState s, vec3 wi, vec3 wo) {
  vec3 h = half_vector(wi, wo);
  // L.H == V.H for a reflection pair in exact arithmetic; their mean keeps f(wi, wo) == f(wo, wi) exactly.
  real lh = 0.5 * (dot(wi, h) + dot(wo, h));
  real d = D_ggx_aniso(h, s.p.alpha_x, s.p.alpha_y);
  if (d == 0.0 || lh <= 0.0) return rgb(0.0);
  real g = s.p.g == GGX_ENERGY_G_CORRELATED ? G2_ggx_correlated(wi, wo, s.p.alpha_x, s.p.alpha_y)
                                            : G2_ggx_separable(wi, wo, s.p.alpha_x, s.p.alpha_y);
  return s.p.ks * F_by_kind_rgb(s.p.f, lh, s.p.ior, s.p.k, s.p.f0) * (d * g / (4.0 * (wi.z * wo.z)));
}

inline rgb ggx_eval(GgxState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  rgb f = s.diffuse + ggx_single_scattering(s, wi, wo);
  if (s.p.ms == GGX_MS_KULLA_CONTY) {
    // The cubic interpolation may overshoot 1 by a hair where E ~ 1; the clamp keeps the lobe >= 0.
    real ei = max(0.0, 1.0 - ggx_energy_at(s.ms_rows, wi.z));
    real eo = max(0.0, 1.0 - ggx_energy_at(s.ms_rows, wo.z));
    f = f + s.ms_scale * (ei * eo);
  }
  return f;
}

// The directional albedo of the multiple-scattering lobe at mu_o for a directional albedo e_o = E(mu_o):
// integral f_ms mu_i d(wi) = ms_scale (1 - e_o) 2 pi integral_0^1 (1 - E(mu)) mu d(mu) = ms_scale (1 - e_o) pi
// (1 - E_avg) = ks F_ms (1 - e_o) (Kulla & Conty 2017, slide 18). 0 without multiple scattering. The game
// renderer's split-sum passes e_o from its DFG table and lights this diffuse-like lobe with the irradiance.
inline rgb ggx_ms_albedo_scale(GgxState s) {
  if (s.p.ms != GGX_MS_KULLA_CONTY) return rgb(0.0);
  return s.ms_scale * (SL_PI * (1.0 - ggx_energy_average_at(s.ms_rows)));
}
inline rgb ggx_ms_albedo(GgxState s, real e_o) {
  return split_sum_ms_albedo(ggx_ms_albedo_scale(s), e_o);
}

// The split-sum description (split_sum.sl): rho_d = kd, r = sqrt(alpha), alpha = sqrt(alpha_x alpha_y), f0 = ks F(1) (the
// Fresnel kind's reflectance at normal incidence), f90 = ks, and with ms = kulla-conty the lobe's albedo scale.
inline SplitSumMaterial ggx_split_sum(GgxState s) {
  SplitSumMaterial m;
  m.diffuse = s.p.kd;
  m.roughness = roughness_from_alpha(sqrt(s.p.alpha_x * s.p.alpha_y));
  m.f0 = s.p.ks * F_by_kind_rgb(s.p.f, 1.0, s.p.ior, s.p.k, s.p.f0);
  m.f90 = s.p.ks;
  m.compensation = rgb(0.0);
  m.ms_albedo = ggx_ms_albedo_scale(s);
  return m;
}

