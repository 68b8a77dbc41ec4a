// split_sum: what the split-sum environment lighting (game_ibl.sl) needs of a microfacet-GGX model, written by
// each model in its own kernel (ggx.sl ggx_split_sum, filament.sl filament_split_sum; C++: Brdf::
// split_sum_inputs, brdf.h), so that the renderer, the exported shaders and the explorer read one description:
// - diffuse: the diffuse albedo rho_d the SH9 diffuse ambient multiplies E/pi by;
// - roughness: the perceptual roughness sqrt(alpha) the chain and the tables are read at (alpha = sqrt(alpha_x
//   alpha_y) for an anisotropic lobe, an approximation as engines make);
// - f0, f90: Schlick's reflectance at normal incidence and at grazing, times the model's specular tint
//   (Karis 2013, "Real Shading in Unreal Engine 4", eqs. 4-8: the environment BRDF f0 A + f90 B);
// - the energy terms, evaluated with E = A + B, the single-scattering albedo with F = 1 of the same DFG table:
//   compensation c multiplies the specular ambient by 1 + c (1/E - 1) (Filament's documentation, "Energy loss
//   in specular reflectance": c = f0; 0: off), and ms_albedo s adds a diffuse-like lobe of directional albedo
//   s (1 - E) lit by the irradiance E/pi (Kulla & Conty 2017, slide 18: ggx.sl ggx_ms_albedo; 0: off).

struct SplitSumMaterial {
  rgb diffuse;
  real roughness;
  rgb f0;
  rgb f90;
  rgb compensation;  // c of 1 + c (1/E - 1); 0 without a multiplicative compensation
  rgb ms_albedo;     // s of s (1 - E) (E/pi); 0 without a multiple-scattering lobe
};

// The multiplicative energy compensation 1 + c (1/E - 1) at the single-scattering albedo E > 0 with F = 1.
inline rgb split_sum_energy_compensation(rgb c, real e) {
  return rgb(1.0) + c * (1.0 / e - 1.0);
}

// The directional albedo s (1 - E) of a Kulla-Conty-style lobe at E = E(mu_o) (clamped at 0 where the
// tables' interpolation overshoots 1).
inline rgb split_sum_ms_albedo(rgb s, real e) {
  return s * max(0.0, 1.0 - e);
}

// The specular ambient with the model's energy terms: spec (the split sum, f0 A + f90 B parts) times the
// compensation, plus the lobe lit by e_over_pi; e = A + B.
inline rgb split_sum_energy_terms(rgb spec, SplitSumMaterial m, real e, rgb e_over_pi) {
  rgb result = spec;
  if (e > 0.0) result = result * split_sum_energy_compensation(m.compensation, e);
  return result + split_sum_ms_albedo(m.ms_albedo, e) * e_over_pi;
}
