// game_ambient: the baked-environment terms of the game shading equation (render/game_renderer.h; the zoo
// article's shader form; Lagarde, "PI or not to PI in game lighting equation", 2012), written once for the
// game renderer and for the browser explorer's lit sphere (web/):
//   diffuse ambient:   L += rho_d (E/pi)(n), E/pi from sh9_irradiance_game (sh9.sl) or an irradiance map;
//   specular ambient:  L += rho_s(cos theta_o) prefiltered(R, n_phong), R = 2 (wo.n) n - wo the mirror
//     direction, the prefiltered cube read at the level whose Phong exponent is n_phong (envmap/prefilter.h's
//     gloss mapping n_i = 2^(scale (1 - i/(M - 1)) + bias) inverted), rho_s the specular lobe's directional
//     albedo tabulated over cos(theta_o) (brdf/game_lobe.h);
//   split-sum specular ambient (microfacet-GGX materials, Karis 2013 "Real Shading in Unreal Engine 4" eqs.
//     4-8; Filament's documentation, "Image based lights"): L += prefiltered_ggx(R, r) (f0 A + f90 B), the GGX
//     chain (envmap/prefilter_ggx.h) read at the perceptual roughness r and A, B the DFG table's scale and
//     bias at (N.V, r) (envmap/dfg.h); the chain read along R as published, or along the dominant direction
//     normalize(mix(R, n, alpha^2)), alpha = r^2 (game_split_sum_lookup below).

const int GAME_ALBEDO_BINS = 32;

// rho_s at cos(theta_o) = (b + 0.5) / GAME_ALBEDO_BINS for bin b.
struct GameSpecularAlbedo {
  rgb bin[GAME_ALBEDO_BINS];
};

// rho_s(cos theta_o): linear between bin centres, the end bins' values beyond the first and last centre.
inline rgb game_specular_albedo(GameSpecularAlbedo table, real cos_o) {
  real c = clamp(cos_o, 0.0, 1.0);
  real pos = clamp(c * real(GAME_ALBEDO_BINS) - 0.5, 0.0, real(GAME_ALBEDO_BINS - 1));
  int b0 = int(pos);
  int b1 = b0 + 1 < GAME_ALBEDO_BINS - 1 ? b0 + 1 : GAME_ALBEDO_BINS - 1;
  real t = pos - real(b0);
  return table.bin[b0] * (1.0 - t) + table.bin[b1] * t;
}

// The (fractional) mip level of a chain of `levels` levels whose level i has the Phong exponent
// 2^(scale (1 - i/(levels - 1)) + bias): i = (levels - 1)(1 - (log2 n - bias)/scale), clamped to the chain.
// n is floored at 1e-9 so that log2 stays finite.
inline real game_prefiltered_level(real n_phong, real levels, real gloss_scale, real gloss_bias) {
  real level = (levels - 1.0) * (1.0 - (log2(max(n_phong, 1.0e-9)) - gloss_bias) / gloss_scale);
  return clamp(level, 0.0, levels - 1.0);
}

// The mirror direction of wo about the normal n (both unit, world space): R = 2 (wo.n) n - wo.
inline vec3 game_reflect(vec3 wo, vec3 n) {
  return n * (2.0 * dot(wo, n)) - wo;
}

// The split sum's lookup direction leaned from the mirror direction r toward the normal n, the "dominant
// direction" of the GGX lobe (the idea: Lagarde & de Rousiers 2014, "Moving Frostbite to PBR", sec. 4.9.3;
// this lerp factor: Filament's shaders, getSpecularDominantDirection): d = normalize(mix(r, n, alpha^2)),
// alpha = perceptual roughness^2. The chain's lobe about R is radially symmetric (n = v = R), while the rough
// lobe at oblique view leans toward the normal: d is R for a mirror, n for alpha = 1. Measured by
// `shadelab ibl-error` (render/ibl_error.h, docs/envmap.md) against the path tracer.
inline vec3 game_split_sum_lookup(vec3 n, vec3 r, real alpha) {
  real t = clamp(alpha * alpha, 0.0, 1.0);
  return normalize(r * (1.0 - t) + n * t);
}

// The split sum's lobe-matched lookup direction (envmap/split_sum_lobes.h): the normal n rotated toward the
// mirror direction r by `angle` radians in the plane of n and r (a negative angle turns past n, away from r);
// r parallel to n (normal view) gives n.
inline vec3 game_split_sum_lobe_direction(vec3 n, vec3 r, real angle) {
  vec3 t = r - n * dot(r, n);
  real len = length(t);
  if (len < 1.0e-12) return n;
  return n * cos(angle) + t * (sin(angle) / len);
}

// The diffuse ambient: a surface of diffuse albedo rho_d under an environment of irradiance E shows
// rho_d E/pi (game units: e_over_pi is E/pi, the exit radiance of a white Lambert surface).
inline rgb game_diffuse_ambient(rgb diffuse_albedo, rgb e_over_pi) {
  return diffuse_albedo * e_over_pi;
}

// The specular ambient: rho_s times the prefiltered radiance about the mirror direction.
inline rgb game_specular_ambient(rgb rho_s, rgb prefiltered) {
  return rho_s * prefiltered;
}

// The split-sum specular ambient: the GGX-prefiltered radiance about R times the environment BRDF
// f0 A + f90 B (A, B from the DFG table at N.V and the roughness).
inline rgb game_split_sum_specular(rgb prefiltered, rgb f0, rgb f90, real a, real b) {
  return prefiltered * (f0 * a + f90 * b);
}

// The same with the chain read once per part (the lobe-matched lookup, envmap/split_sum_lobes.h): the A part's
// read times f0 A plus the B part's read times f90 B.
inline rgb game_split_sum_specular_lobes(rgb prefiltered_a, rgb prefiltered_b, rgb f0, rgb f90, real a, real b) {
  return prefiltered_a * (f0 * a) + prefiltered_b * (f90 * b);
}

