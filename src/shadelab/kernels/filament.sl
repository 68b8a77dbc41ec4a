// filament: Filament's standard (metallic-roughness) model, as its documentation writes it ("Physically Based
// Rendering in Filament", google.github.io/filament/Filament.html, chapter "Material system"; the section
// names below are that document's):
//   f = Fd + Fr                                                              ("Standard model summary")
//   Fd = diffuse_colour / pi (lambert) or diffuse_colour Fd_Burley ("Diffuse BRDF"; burley.sl's factor, given
//        Filament's roughness alpha as Filament's shaders do), diffuse_colour = (1 - metallic) base_colour
//        ("Base color remapping")
//   Fr = D_GGX(N.H, a) V_SmithGGXCorrelated(N.V, N.L, a) F_Schlick(L.H, f0, f90 = 1), a = perceptual_roughness^2
//        ("Normal distribution function (specular D)", "Geometric shadowing (specular G)", "Fresnel (specular
//        F)"; microfacet.sl D_ggx and V_smith_ggx_correlated, fresnel.sl F_schlick_rgb)
//   f0 = 0.16 reflectance^2 (1 - metallic) + base_colour metallic              ("Reflectance remapping")
//   energy_compensation = on: Fr *= 1 + f0 (1 / E(N.V) - 1)                    ("Energy loss in specular
//        reflectance"), E = dfg.y = the single-scattering albedo with F = 1; here ggx_energy (height-correlated).
// The compensation depends on N.V only, so with f0 > 0 the model is not reciprocal (Filament's choice).

const int FILAMENT_DIFFUSE_LAMBERT = 0;
const int FILAMENT_DIFFUSE_BURLEY = 1;

struct FilamentParams {
  rgb base_color;
  real metallic;
  real perceptual_roughness;
  real reflectance;
  int diffuse;              // FILAMENT_DIFFUSE_*
  int energy_compensation;  // 0 off, 1 on
};

struct FilamentState {
  rgb diffuse_colour;  // (1 - metallic) base_colour
  rgb f0;
  real alpha;
  int diffuse;
  int energy_compensation;
  GgxEnergyRows e_rows;  // the energy table's rows at alpha (height-correlated)
};

inline FilamentState filament_prepare(FilamentParams p) {
  FilamentState s;
  s.diffuse_colour = p.base_color * (1.0 - p.metallic);
  s.f0 = rgb(0.16 * p.reflectance * p.reflectance * (1.0 - p.metallic)) + p.base_color * p.metallic;
  s.alpha = alpha_from_roughness(p.perceptual_roughness);
  s.diffuse = p.diffuse;
  s.energy_compensation = p.energy_compensation;
  s.e_rows = ggx_energy_rows(GGX_ENERGY_G_CORRELATED, s.alpha);
  return s;
}

// Filament's energy compensation factor 1 + f0 (1/E - 1) for the single-scattering albedo E = E(N.V) with
// F = 1 ("Energy loss in specular reflectance"); the game renderer's split-sum applies it with E = A + B.
inline rgb filament_energy_compensation(rgb f0, real e) {
  return split_sum_energy_compensation(f0, e);
}

// The split-sum description (split_sum.sl): rho_d = (1 - metallic) base_colour, r = sqrt(alpha), f0, f90 = 1
// ("Fresnel (specular F)"), and with energy compensation on, c = f0 ("Energy loss in specular reflectance").
inline SplitSumMaterial filament_split_sum(FilamentState s) {
  SplitSumMaterial m;
  m.diffuse = s.diffuse_colour;
  m.roughness = roughness_from_alpha(s.alpha);
  m.f0 = s.f0;
  m.f90 = rgb(1.0);
  m.compensation = s.energy_compensation == 1 ? s.f0 : rgb(0.0);
  m.ms_albedo = rgb(0.0);
  return m;
}

inline rgb filament_eval(FilamentState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  vec3 h = half_vector(wi, wo);
  real lh = 0.5 * (dot(wi, h) + dot(wo, h));
  real fd = SL_INV_PI;
  if (s.diffuse == FILAMENT_DIFFUSE_BURLEY) fd = burley_factor(wi.z, wo.z, lh, s.alpha) * SL_INV_PI;
  rgb f = s.diffuse_colour * fd;
  real dv = D_ggx(h.z, s.alpha) * V_smith_ggx_correlated(wo.z, wi.z, s.alpha);
  if (dv > 0.0 && lh > 0.0) {
    rgb fr = F_schlick_rgb(lh, s.f0) * dv;
    if (s.energy_compensation == 1) {
      fr = fr * filament_energy_compensation(s.f0, ggx_energy_at(s.e_rows, wo.z));
    }
    f = f + fr;
  }
  return f;
}
