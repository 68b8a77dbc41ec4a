// principled_v1: Blender 3.4's Principled BSDF as Cycles 3.4 evaluates it, reflection only (shading dialect,
// sl.h). Read from Cycles 3.4's source (github.com/blender/cycles, tag v3.4.0; the same files sit under
// intern/cycles/ in Blender's tree) and written again here; every term names the file and function it follows.
// With t = the tangent rotated by 2 pi anisotropic_rotation about the normal (svm/closure.h,
// svm_node_closure_bsdf, "rotate tangent"):
//
//   f = f_diffuse + f_sheen + f_specular + f_clearcoat       (the closures svm_node_closure_bsdf allocates,
//                                                              summed with their weights, none dimming another)
//   f_diffuse  = base_color (1 - metallic) / pi [(1 - FV/2)(1 - FL/2) + RR (FL + FV + FL FV (RR - 1))],
//                FL = (1 - N.L)^5, FV = (1 - N.V)^5, RR = roughness (1 + L.V) = 2 roughness (L.H)^2
//                (closure/bsdf_principled_diffuse.h, bsdf_principled_diffuse_compute_brdf, PRINCIPLED_DIFFUSE_FULL;
//                algebraically Burley 2012's (1 + (F_D90 - 1) FL)(1 + (F_D90 - 1) FV), F_D90 = 0.5 + RR)
//   f_sheen    = sheen (1 - metallic) C_sheen (1 - L.H)^5, no 1/pi (bsdf_principled_sheen.h,
//                calculate_principled_sheen_brdf; Burley 2012's F_sheen), C_sheen = mix(1, base_color / Y709,
//                sheen_tint), Y709 = 0.2126729 r + 0.7151522 g + 0.0721750 b (svm/closure.h "sheen",
//                linear_rgb_to_gray with scene/shader.cpp's Rec.709 rgb_to_y), C = 1 where Y709 = 0
//   f_specular = F D_GGX(h; a_x, a_y) G1(L) G1(V) / (4 N.L N.V), separable Smith
//                (bsdf_microfacet.h, bsdf_microfacet_ggx_eval_reflect; G1 = 2 / (1 + sqrt(1 + a^2 tan^2)) with
//                a^2 projected on the azimuth, = 1 / (1 + Lambda)),
//                r2 = roughness^2, aspect = sqrt(1 - 0.9 anisotropic), a_x = min(1, r2 / aspect),
//                a_y = min(1, r2 aspect) (svm/closure.h; bsdf_microfacet_ggx_fresnel_setup's saturatef),
//                F = cspec0 (1 - FH) + FH, FH = (F_dielectric(L.H, eta) - F0) / (1 - F0), F0 = F_dielectric(1, eta),
//                eta = 2 / (1 - sqrt(0.08 specular)) - 1, so F0 = 0.08 specular (bsdf_util.h,
//                interpolate_fresnel_color; bsdf_microfacet.h, reflection_color),
//                cspec0 = saturate(0.08 specular mix(1, base_color / Y_spec, specular_tint) (1 - metallic)
//                + base_color metallic), Y_spec = 0.3 r + 0.6 g + 0.1 b, tint 1 where Y_spec = 0 (svm/closure.h)
//   f_clearcoat = 0.25 clearcoat F_dielectric(L.H, 1.5) D_GTR1(N.H; clearcoat_roughness^2) G1_0.25(L) G1_0.25(V)
//                / (4 N.L N.V) (bsdf_microfacet.h, bsdf_microfacet_ggx_eval_reflect's CLEARCOAT branch: D_GTR1,
//                G with a fixed alpha 0.25; cspec0 = 0.04 = F0 of eta 1.5, so interpolate_fresnel_color is the
//                exact dielectric F), D_GTR1 = (a^2 - 1) / (pi ln(a^2) (1 + (a^2 - 1) (N.H)^2)), 1/pi for a >= 1
//                (Burley 2012, appendix B, eq. 4; bsdf_microfacet.h, D_GTR1).
//
// Left out (docs/models/principled-v1.md): transmission, subsurface, emission, alpha, the clearcoat normal;
// Multiscatter GGX (Cycles' stochastic random walk; Blender 3.4's node defaults to GGX); the closure weight
// cutoff 1e-5 below which Cycles drops a lobe. Each lobe is symmetric in L and V as written (L.H is taken as
// the mean of L.H and V.H, the rest are products and sums of symmetric terms), so f(wi, wo) == f(wo, wi).

// Cycles' Rec.709 luminance weights (scene/shader.cpp, ShaderManager::init_xyz_transforms, rgb_to_y): the
// sheen tint's luminance. Blender's own colour configuration gives the same row to the digits shown.
const real PRINCIPLED_V1_Y709_R = 0.2126729;
const real PRINCIPLED_V1_Y709_G = 0.7151522;
const real PRINCIPLED_V1_Y709_B = 0.0721750;
// The clearcoat's masking-shadowing roughness, fixed whatever clearcoat_roughness is (bsdf_microfacet.h,
// bsdf_microfacet_ggx_eval_reflect: "alpha2 = 0.0625f").
const real PRINCIPLED_V1_CLEARCOAT_G_ALPHA = 0.25;
const real PRINCIPLED_V1_CLEARCOAT_ETA = 1.5;

struct PrincipledV1Params {
  rgb base_color;
  real metallic;
  real specular;
  real specular_tint;
  real roughness;
  real anisotropic;
  real anisotropic_rotation;  // in turns: the tangent turns by 2 pi anisotropic_rotation about the normal
  real sheen;
  real sheen_tint;
  real clearcoat;
  real clearcoat_roughness;
};

struct PrincipledV1State {
  rgb diffuse;          // base_color (1 - metallic) / pi
  real roughness;       // the diffuse retro-reflection's roughness (the socket value)
  rgb sheen;            // sheen (1 - metallic) C_sheen
  rgb cspec0;           // the specular colour at normal incidence
  real spec_eta;        // eta of the specular Fresnel, from specular
  real spec_f0;         // F_dielectric(1, eta) = 0.08 specular
  real alpha_x;         // specular GGX roughness along the rotated tangent
  real alpha_y;         // and along the rotated bitangent
  real cos_rot;         // the rotation of the tangent
  real sin_rot;
  real clearcoat;       // 0.25 clearcoat
  real clearcoat_alpha; // clearcoat_roughness^2, GTR1's alpha
  real clearcoat_norm;  // (a^2 - 1) / (pi ln(a^2)), GTR1's normalization (1/pi for a >= 1)
};

// Cycles' Schlick weight (1 - u)^5 with 1 - u clamped to [0, 1] (bsdf_util.h, schlick_fresnel).
inline real principled_v1_schlick_weight(real u) {
  real m = clamp(1.0 - u, 0.0, 1.0);
  real m2 = m * m;
  return m2 * m2 * m;
}

// The hue of base_color at unit luminance, luminance = w . base_color: base_color / luminance, white where the
// luminance is not positive (svm/closure.h: "normalize lum. to isolate hue+sat").
inline rgb principled_v1_hue(rgb c, real wr, real wg, real wb) {
  real lum = wr * c.r + wg * c.g + wb * c.b;
  if (lum > 0.0) return c / lum;
  return rgb(1.0);
}

// x / ln(1 + x) for x = a^2 - 1 in (-1, 0]: GTR1's normalization times pi. Near x = 0 (a -> 1) the quotient
// is 0/0 and a float log near 1 has an absolute, not relative, error bound (the Vulkan spec allows 2^-21), so
// its series 1 + x/2 - x^2/12 + x^3/24 (next term 19 x^4 / 720 < 3e-10 for |x| < 0.01) is taken there.
inline real principled_v1_gtr1_norm_pi(real a2) {
  real x = a2 - 1.0;
  if (x >= 0.0) return 1.0;  // a >= 1: GTR1 is the uniform 1/pi (bsdf_microfacet.h, D_GTR1)
  if (x > -0.01) return 1.0 + x * (0.5 + x * (-1.0 / 12.0 + x / 24.0));
  return x / log(a2);  // a2 > 0: clearcoat_roughness >= 0.02 (the parameter's range)
}

// GTR1 (Burley 2012, appendix B, eq. 4), with its normalization given: norm / (a^2 h.z^2 + h.x^2 + h.y^2),
// the denominator 1 + (a^2 - 1) h.z^2 written so that float keeps its precision near h = +Z (where it is a^2,
// not 1 - (1 - a^2)).
inline real D_gtr1(vec3 h, real a2, real norm) {
  if (h.z <= 0.0) return 0.0;
  return norm / (a2 * h.z * h.z + h.x * h.x + h.y * h.y);
}

inline PrincipledV1State principled_v1_prepare(PrincipledV1Params p) {
  PrincipledV1State s;
  real diffuse_weight = 1.0 - clamp(p.metallic, 0.0, 1.0);  // (1 - saturate(metallic)) (1 - transmission)
  s.diffuse = p.base_color * (diffuse_weight * SL_INV_PI);
  s.roughness = p.roughness;
  rgb sheen_colour = rgb(1.0 - p.sheen_tint) +
                     principled_v1_hue(p.base_color, PRINCIPLED_V1_Y709_R, PRINCIPLED_V1_Y709_G, PRINCIPLED_V1_Y709_B) *
                         p.sheen_tint;
  s.sheen = sheen_colour * (p.sheen * diffuse_weight);
  rgb tint = rgb(1.0 - p.specular_tint) + principled_v1_hue(p.base_color, 0.3, 0.6, 0.1) * p.specular_tint;
  rgb c0 = tint * (p.specular * 0.08 * (1.0 - p.metallic)) + p.base_color * p.metallic;
  s.cspec0 = rgb(clamp(c0.r, 0.0, 1.0), clamp(c0.g, 0.0, 1.0), clamp(c0.b, 0.0, 1.0));
  // 1 - sqrt(0.08 specular) >= 1 - sqrt(0.08) > 0.71 for specular in [0, 1]: no division by zero.
  s.spec_eta = 2.0 / (1.0 - sqrt(0.08 * p.specular)) - 1.0;
  s.spec_f0 = F_dielectric(1.0, s.spec_eta);
  real aspect = sqrt(1.0 - 0.9 * p.anisotropic);  // >= sqrt(0.1)
  real r2 = p.roughness * p.roughness;
  s.alpha_x = min(1.0, r2 / aspect);
  s.alpha_y = min(1.0, r2 * aspect);
  real angle = 2.0 * SL_PI * p.anisotropic_rotation;
  s.cos_rot = cos(angle);
  s.sin_rot = sin(angle);
  s.clearcoat = 0.25 * p.clearcoat;
  s.clearcoat_alpha = min(1.0, p.clearcoat_roughness * p.clearcoat_roughness);
  s.clearcoat_norm = principled_v1_gtr1_norm_pi(s.clearcoat_alpha * s.clearcoat_alpha) * SL_INV_PI;
  return s;
}

// A direction in the frame of the rotated tangent t = (cos, sin, 0) and bitangent n x t = (-sin, cos, 0)
// (Cycles' make_orthonormals_tangent: the bitangent is N x T).
inline vec3 principled_v1_to_tangent_frame(PrincipledV1State s, vec3 w) {
  return vec3(s.cos_rot * w.x + s.sin_rot * w.y, s.cos_rot * w.y - s.sin_rot * w.x, w.z);
}

// The specular lobe's Fresnel colour at L.H = lh (bsdf_util.h, interpolate_fresnel_color). FH >= 0 in exact
// arithmetic (a dielectric's F rises monotonically from F0); the max only removes rounding below 0.
inline rgb principled_v1_specular_fresnel(PrincipledV1State s, real lh) {
  // 1 - F0 = 1 - 0.08 specular >= 0.92.
  real fh = max(0.0, (F_dielectric(lh, s.spec_eta) - s.spec_f0) / (1.0 - s.spec_f0));
  return s.cspec0 * (1.0 - fh) + rgb(fh);
}

inline rgb principled_v1_eval(PrincipledV1State s, vec3 wi, vec3 wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return rgb(0.0);
  vec3 h = half_vector(wi, wo);
  // L.H == V.H for a reflection pair in exact arithmetic; their mean keeps f(wi, wo) == f(wo, wi) exactly.
  real lh = 0.5 * (dot(wi, h) + dot(wo, h));
  // Diffuse with retro-reflection (bsdf_principled_diffuse_compute_brdf).
  real fl = principled_v1_schlick_weight(wi.z);
  real fv = principled_v1_schlick_weight(wo.z);
  real rr = s.roughness * (1.0 + dot(wi, wo));
  rgb f = s.diffuse * ((1.0 - 0.5 * fv) * (1.0 - 0.5 * fl) + rr * (fl + fv + fl * fv * (rr - 1.0)));
  // Sheen (calculate_principled_sheen_brdf).
  f = f + s.sheen * principled_v1_schlick_weight(lh);
  if (lh <= 0.0) return f;
  // 4 N.L N.V > 0 here (both above the horizon).
  real inv_4nlnv = 0.25 / (wi.z * wo.z);
  // Specular GGX, separable Smith, in the rotated tangent frame (bsdf_microfacet_ggx_eval_reflect).
  vec3 ht = principled_v1_to_tangent_frame(s, h);
  real d = D_ggx_aniso(ht, s.alpha_x, s.alpha_y);
  if (d > 0.0) {
    vec3 wit = principled_v1_to_tangent_frame(s, wi);
    vec3 wot = principled_v1_to_tangent_frame(s, wo);
    real g = G2_ggx_separable(wit, wot, s.alpha_x, s.alpha_y);
    f = f + principled_v1_specular_fresnel(s, lh) * (d * g * inv_4nlnv);
  }
  // Clearcoat: GTR1 D, GGX G at alpha 0.25, dielectric F at eta 1.5, weight 0.25 clearcoat.
  if (s.clearcoat > 0.0) {
    real dc = D_gtr1(h, s.clearcoat_alpha * s.clearcoat_alpha, s.clearcoat_norm);
    real gc = G2_ggx_separable(wi, wo, PRINCIPLED_V1_CLEARCOAT_G_ALPHA, PRINCIPLED_V1_CLEARCOAT_G_ALPHA);
    f = f + rgb(s.clearcoat * F_dielectric(lh, PRINCIPLED_V1_CLEARCOAT_ETA) * dc * gc * inv_4nlnv);
  }
  return f;
}
