// gltf: glTF 2.0's metallic-roughness material with KHR_materials_ior, _specular, _anisotropy, _sheen and _clearcoat,
// as the specifications write the BRDF (shading dialect, sl.h). Sources: glTF 2.0 specification, Appendix B ("BRDF
// Implementation"); each extension's README, section "Implementation" (github.com/KhronosGroup/glTF,
// extensions/2.0/Khronos/). Reflection only: transmission, volume and emission are not part of f.
//   specular_brdf = D_GGX V_GGX: anisotropic GGX with alpha_t = mix(alpha, 1, anisotropy_strength^2) along the
//       anisotropy direction (the tangent rotated by anisotropy_rotation about the normal), alpha_b = alpha =
//       roughness^2, V the height-correlated Smith term G2 / (4 N.L N.V) (KHR_materials_anisotropy; Appendix B)
//   metal_brdf = specular_brdf (base_color + (1 - base_color) (1 - |V.H|)^5)          (Appendix B, conductor_fresnel)
//   dielectric_brdf = (1 - specular max3(F)) base_color / pi + specular F specular_brdf,
//       F = f0 + (1 - f0) (1 - |V.H|)^5, f0 = min(((ior - 1)/(ior + 1))^2 specular_color, 1)
//       (KHR_materials_specular's fresnel_mix with KHR_materials_ior's ior)
//   material = mix(dielectric_brdf, metal_brdf, metallic)                                   (Appendix B)
//   sheen_layer = sheen_color D_charlie V_sheen + material s, s = min(1 - max3(sheen_color) E(N.V),
//       1 - max3(sheen_color) E(N.L)), E the sheen lobe's directional albedo (sheen.sl's table)  (KHR_materials_sheen)
//       s is clamped to >= 0 here: E exceeds 1 near grazing at low sheen roughness (sheen.sl), where the
//       specification's factor would make f negative.
//   f = (1 - clearcoat Fc) sheen_layer + clearcoat Fc D_GGX(alpha_c) V_GGX(alpha_c), Fc = 0.04 + 0.96 (1 - N.V)^5,
//       alpha_c = clearcoat_roughness^2 (KHR_materials_clearcoat's fresnel_coat: Schlick at N.V with the coat's
//       ior 1.5, the coat normal = the surface normal here)
// fresnel_mix and the sheen scaling use V.H and both directions alike, so without a clearcoat f is reciprocal;
// fresnel_coat reads N.V alone, so with clearcoat > 0 it is not (the specification's choice, measured in
// docs/models/gltf.md).

// Each rgb field starts a 16-byte row (three rgb + real pairs first, then the scalars), so that std140 and HLSL's
// cbuffer packing (which lets a float3 follow a float inside a row) give the same offsets.
struct GltfParams {
  rgb base_color;
  real metallic;
  rgb specular_color;
  real roughness;  // perceptual: alpha = roughness^2
  rgb sheen_color;
  real sheen_roughness;
  real ior;
  real specular;
  real anisotropy_strength;
  real anisotropy_rotation;  // radians, counter-clockwise from the tangent
  int sheen_visibility;      // SHEEN_VISIBILITY_* (sheen.sl)
  real clearcoat;
  real clearcoat_roughness;
};

struct GltfState {
  rgb base_color;
  real metallic;
  real specular;
  rgb f0;        // the dielectric's f0: min(((ior - 1)/(ior + 1))^2 specular_color, 1)
  real alpha_t;  // along the anisotropy direction
  real alpha_b;  // across it
  real cos_rotation;
  real sin_rotation;
  rgb sheen_color;
  real sheen_max;
  real sheen_alpha;
  int sheen_visibility;
  SheenEnergyRows sheen_rows;
  real clearcoat;
  real clearcoat_alpha;
};

// The floor of the GGX roughness alpha (glTF allows roughness 0, a mirror the BRDF cannot represent as a function).
const real GLTF_ALPHA_MIN = 1e-4;

inline GltfState gltf_prepare(GltfParams p) {
  GltfState s;
  s.base_color = p.base_color;
  s.metallic = p.metallic;
  s.specular = p.specular;
  real q = (p.ior - 1.0) / (p.ior + 1.0);
  rgb f0 = p.specular_color * (q * q);
  s.f0 = rgb(min(f0.r, 1.0), min(f0.g, 1.0), min(f0.b, 1.0));
  real alpha = max(alpha_from_roughness(p.roughness), GLTF_ALPHA_MIN);
  s.alpha_t = mix(alpha, 1.0, p.anisotropy_strength * p.anisotropy_strength);
  s.alpha_b = alpha;
  s.cos_rotation = cos(p.anisotropy_rotation);
  s.sin_rotation = sin(p.anisotropy_rotation);
  s.sheen_color = p.sheen_color;
  s.sheen_max = max(p.sheen_color.r, max(p.sheen_color.g, p.sheen_color.b));
  s.sheen_alpha = sheen_alpha(p.sheen_roughness);
  s.sheen_visibility = p.sheen_visibility;
  s.sheen_rows = sheen_energy_rows(p.sheen_visibility, p.sheen_roughness);
  s.clearcoat = p.clearcoat;
  s.clearcoat_alpha = max(alpha_from_roughness(p.clearcoat_roughness), GLTF_ALPHA_MIN);
  return s;
}

// w in the anisotropy frame: x along the anisotropy direction (the tangent rotated by the rotation), y across it.
inline vec3 gltf_anisotropy_frame(GltfState s, vec3 w) {
  return vec3(s.cos_rotation * w.x + s.sin_rotation * w.y, -s.sin_rotation * w.x + s.cos_rotation * w.y, w.z);
}

// (1 - c)^5 for Schlick's weight.
inline real gltf_schlick_weight(real c) {
  real t = clamp(1.0 - c, 0.0, 1.0);
  real t2 = t * t;
  return t2 * t2 * t;
}

// The sheen scaling of the layers below: min over both directions of 1 - max3(sheen_color) E, clamped to >= 0.
inline real gltf_sheen_scaling(GltfState s, real nl, real nv) {
  real e = max(sheen_energy_at(s.sheen_rows, nl), sheen_energy_at(s.sheen_rows, nv));
  return max(0.0, 1.0 - s.sheen_max * e);
}

// The clearcoat's Fresnel weight of fresnel_coat: 0.04 + 0.96 (1 - N.V)^5.
inline real gltf_clearcoat_fresnel(real nv) {
  return 0.04 + 0.96 * gltf_schlick_weight(nv);
}

inline rgb gltf_eval(GltfState s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  vec3 h = half_vector(wi, wo);
  real w = gltf_schlick_weight(0.5 * (dot(wi, h) + dot(wo, h)));
  vec3 ai = gltf_anisotropy_frame(s, wi);
  vec3 ao = gltf_anisotropy_frame(s, wo);
  real dv = D_ggx_aniso(gltf_anisotropy_frame(s, h), s.alpha_t, s.alpha_b) *
            G2_ggx_correlated(ai, ao, s.alpha_t, s.alpha_b) / (4.0 * wi.z * wo.z);
  rgb metal = (s.base_color + (rgb(1.0) - s.base_color) * w) * dv;
  rgb fr = s.f0 + (rgb(1.0) - s.f0) * w;
  real fr_max = max(fr.r, max(fr.g, fr.b));
  rgb dielectric = s.base_color * ((1.0 - s.specular * fr_max) * SL_INV_PI) + fr * (s.specular * dv);
  rgb f = mix(dielectric, metal, s.metallic);
  if (s.sheen_max > 0.0) {
    f = f * gltf_sheen_scaling(s, wi.z, wo.z) + s.sheen_color * sheen_dv(s.sheen_visibility, wi, wo, s.sheen_alpha);
  }
  if (s.clearcoat > 0.0) {
    real fc = s.clearcoat * gltf_clearcoat_fresnel(wo.z);
    // D from h's components (D_ggx_aniso with equal roughness): near the mirror direction of a sharp coat,
    // (a^2 - 1) cos^2 + 1 formed from cos^2 loses digits in single precision that h.x^2 + h.y^2 keeps.
    real coat = D_ggx_aniso(h, s.clearcoat_alpha, s.clearcoat_alpha) *
                V_smith_ggx_correlated(wo.z, wi.z, s.clearcoat_alpha);
    f = f * (1.0 - fc) + rgb(fc * coat);
  }
  return f;
}
