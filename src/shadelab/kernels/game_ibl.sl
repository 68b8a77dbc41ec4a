// game_ibl: the split sum's per-pixel reads of the files `shadelab bake ibl` writes, written once for the game
// renderer (render/game_renderer.cpp), the exported shaders (`shadelab shader --ibl`) and the browser explorer:
// - the prefiltered GGX chain (envmap/prefilter_ggx.h) read at perceptual roughness r: level lod(r) of a chain
//   of L levels, lod = r (L - 1) (linear) or r (2 - r)(L - 1) (filament: Filament's cmgen / ibl shaders'
//   lodFromPerceptualRoughness), clamped to the chain, each level read seamlessly (cube.sl) and the two
//   levels around lod mixed linearly;
// - the DFG table (envmap/dfg.h): A (channel 0) and B (channel 1) at (N.V, r), texel (i, j) at
//   ((i + 1/2)/n, (j + 1/2)/n), bilinear between texel centres and clamped at the edges.
// - the lobe-matched lookup's table (envmap/split_sum_lobes.h), read as the DFG table but going to the mirror
//   below its first row;
// - the split sum at a shading point (game_split_sum_ambient): the lookup (mirror, dominant or lobes), the chain
//   reads and prefiltered (f0 A + f90 B) of game_ambient.sl (Karis 2013);
// - with a model's split-sum description (split_sum.sl), the specular ambient and its energy terms
//   (game_split_sum_shade: what the game renderer calls per pixel) and the whole environment lighting of the
//   game shading equation, SH9 diffuse plus split-sum specular (game_ibl_ambient: what `shadelab shader --ibl`
//   exports).
// The texels come from the language-specific fetches cube_texel / cube_size (the chain's level i is cube i),
// dfg_texel(i, j, channel) and split_sum_lobe_texel(i, j, channel) (C++: kernels.h; shaders: their textures).

const int GGX_MIP_MAPPING_LINEAR = 0;
const int GGX_MIP_MAPPING_FILAMENT = 1;

// The chain's (fractional) level for perceptual roughness r in [0, 1], before clamping to the chain.
inline real ggx_chain_lod(real r, int levels, int mapping) {
  real scale = levels > 1 ? real(levels - 1) : 0.0;
  if (mapping == GGX_MIP_MAPPING_FILAMENT) return scale * r * (2.0 - r);
  return scale * r;
}

// The prefiltered GGX radiance along dir (not zero) at perceptual roughness r (clamped to [0, 1]) from a chain
// of `levels` levels (cubes 0 .. levels - 1); black for an empty chain.
inline rgb ggx_chain_read(vec3 dir, real roughness, int levels, int mapping) {
  if (levels < 1) return rgb(0.0);
  real lod = clamp(ggx_chain_lod(clamp(roughness, 0.0, 1.0), levels, mapping), 0.0, real(levels - 1));
  int l0 = min(int(lod), levels - 1);
  int l1 = min(l0 + 1, levels - 1);
  real t = lod - real(l0);
  rgb v0 = cube_sample_seamless(l0, dir);
  if (t <= 0.0 || l1 == l0) return v0;
  return v0 * (1.0 - t) + cube_sample_seamless(l1, dir) * t;
}

struct DfgScaleBias {
  real a;  // the scale of f0
  real b;  // the bias, the scale of f90
};

// A and B of an n x n DFG table at (mu, r) = (N.V, perceptual roughness), each in [0, 1]: texel centres at
// (i + 1/2)/n, bilinear between them, clamped at the table's edges.
inline DfgScaleBias dfg_read(real mu, real roughness, int n) {
  real fn = real(n);
  real px = clamp(mu * fn - 0.5, 0.0, fn - 1.0);
  real py = clamp(roughness * fn - 0.5, 0.0, fn - 1.0);
  int x0 = min(int(px), n - 1);
  int x1 = min(x0 + 1, n - 1);
  int y0 = min(int(py), n - 1);
  int y1 = min(y0 + 1, n - 1);
  real tx = px - real(x0);
  real ty = py - real(y0);
  DfgScaleBias ab;
  ab.a = (dfg_texel(x0, y0, 0) * (1.0 - tx) + dfg_texel(x1, y0, 0) * tx) * (1.0 - ty) +
          (dfg_texel(x0, y1, 0) * (1.0 - tx) + dfg_texel(x1, y1, 0) * tx) * ty;
  ab.b = (dfg_texel(x0, y0, 1) * (1.0 - tx) + dfg_texel(x1, y0, 1) * tx) * (1.0 - ty) +
          (dfg_texel(x0, y1, 1) * (1.0 - tx) + dfg_texel(x1, y1, 1) * tx) * ty;
  return ab;
}

struct SplitSumLobeReads {
  real angle_a;      // the f0 A part: radians from n toward R
  real roughness_a;  // the f0 A part: the perceptual roughness the chain is read at
  real angle_b;      // the f90 B part
  real roughness_b;
};

// One channel of the lobe table between four texels, as dfg_read combines them.
inline real split_sum_lobe_bilinear(int x0, int x1, int y0, int y1, real tx, real ty, int channel) {
  return (split_sum_lobe_texel(x0, y0, channel) * (1.0 - tx) + split_sum_lobe_texel(x1, y0, channel) * tx) * (1.0 - ty) +
         (split_sum_lobe_texel(x0, y1, channel) * (1.0 - tx) + split_sum_lobe_texel(x1, y1, channel) * tx) * ty;
}

// The lobe-matched lookup's n x n table (envmap/split_sum_lobes.h; `bake ibl`'s split_sum_lobes.json, channels
// angle_a, roughness_a, angle_b, roughness_b) at (mu, r) = (N.V, perceptual roughness): read as dfg_read reads
// the DFG table, except below the first row's centre r0 = 1/(2n), where it goes linearly to the mirror (r = 0:
// both lobes the delta at R, at the angle acos(mu) from n, roughness 0) instead of clamping to the first row.
inline SplitSumLobeReads split_sum_lobes_read(real mu, real roughness, int n) {
  real fn = real(n);
  real px = clamp(mu * fn - 0.5, 0.0, fn - 1.0);
  real py = clamp(roughness * fn - 0.5, 0.0, fn - 1.0);
  int x0 = min(int(px), n - 1);
  int x1 = min(x0 + 1, n - 1);
  int y0 = min(int(py), n - 1);
  int y1 = min(y0 + 1, n - 1);
  real tx = px - real(x0);
  real ty = py - real(y0);
  SplitSumLobeReads reads;
  reads.angle_a = split_sum_lobe_bilinear(x0, x1, y0, y1, tx, ty, 0);
  reads.roughness_a = split_sum_lobe_bilinear(x0, x1, y0, y1, tx, ty, 1);
  reads.angle_b = split_sum_lobe_bilinear(x0, x1, y0, y1, tx, ty, 2);
  reads.roughness_b = split_sum_lobe_bilinear(x0, x1, y0, y1, tx, ty, 3);
  real r0 = 0.5 / fn;
  if (roughness < r0) {
    real w = max(roughness, 0.0) / r0;
    real mirror_angle = acos(clamp(mu, 0.0, 1.0));
    reads.angle_a = mirror_angle + (reads.angle_a - mirror_angle) * w;
    reads.roughness_a = reads.roughness_a * w;
    reads.angle_b = mirror_angle + (reads.angle_b - mirror_angle) * w;
    reads.roughness_b = reads.roughness_b * w;
  }
  return reads;
}

// The split sum's lookups (render/game_renderer.h GameSplitSumLookup; `render --split-sum-lookup`).
const int SPLIT_SUM_LOOKUP_MIRROR = 0;    // the chain read once along R (Karis 2013 as published)
const int SPLIT_SUM_LOOKUP_DOMINANT = 1;  // once along normalize(mix(R, n, alpha^2)) (game_split_sum_lookup)
const int SPLIT_SUM_LOOKUP_LOBES = 2;     // each part once along and at its lobe's first moments (the default)

// The game shading equation's split-sum specular ambient at a shading point, before a model's energy terms:
// n the unit normal and wo the unit direction to the viewer (world space), mu = N.V in [0, 1], r the
// perceptual roughness, f0 and f90 the model's (brdf.h SplitSumInputs), ab the DFG table's A and B at (mu, r)
// (dfg_read; the caller keeps E = A + B for the energy terms), the chain of `levels` levels and its mip
// mapping, and for the lobes lookup the lobe table's size.
inline rgb game_split_sum_ambient(vec3 n, vec3 wo, real mu, real roughness, rgb f0, rgb f90, DfgScaleBias ab, int lookup,
                                  int levels, int mapping, int lobe_size) {
  vec3 r = game_reflect(wo, n);
  if (lookup == SPLIT_SUM_LOOKUP_LOBES) {
    SplitSumLobeReads lobes = split_sum_lobes_read(mu, roughness, lobe_size);
    vec3 da = game_split_sum_lobe_direction(n, r, lobes.angle_a);
    vec3 db = game_split_sum_lobe_direction(n, r, lobes.angle_b);
    return game_split_sum_specular_lobes(ggx_chain_read(da, lobes.roughness_a, levels, mapping),
                                         ggx_chain_read(db, lobes.roughness_b, levels, mapping), f0, f90, ab.a, ab.b);
  }
  if (lookup == SPLIT_SUM_LOOKUP_DOMINANT) r = game_split_sum_lookup(n, r, alpha_from_roughness(roughness));
  return game_split_sum_specular(ggx_chain_read(r, roughness, levels, mapping), f0, f90, ab.a, ab.b);
}

// The split-sum specular ambient of a model at a shading point, energy terms included: n the unit normal and wo
// the unit direction to the viewer (world space), m the model's description (split_sum.sl), e_over_pi the
// irradiance E/pi at n (lights the multiple-scattering lobe), the lookup, the chain (levels, mip mapping), the
// DFG table's size and the lobe table's size (lookup lobes). mu = N.V and r are clamped to [0, 1].
inline rgb game_split_sum_shade(vec3 n, vec3 wo, SplitSumMaterial m, rgb e_over_pi, int lookup, int levels, int mapping,
                                int dfg_size, int lobe_size) {
  real mu = clamp(dot(n, wo), 0.0, 1.0);
  real roughness = clamp(m.roughness, 0.0, 1.0);
  DfgScaleBias ab = dfg_read(mu, roughness, dfg_size);
  rgb spec = game_split_sum_ambient(n, wo, mu, roughness, m.f0, m.f90, ab, lookup, levels, mapping, lobe_size);
  return split_sum_energy_terms(spec, m, ab.a + ab.b, e_over_pi);
}

// The environment lighting of the game shading equation for a split-sum model (game units): the diffuse ambient
// rho_d E/pi (e_over_pi from sh9_irradiance_game, or an irradiance map) plus the split-sum specular ambient.
inline rgb game_ibl_ambient(vec3 n, vec3 wo, SplitSumMaterial m, rgb e_over_pi, int lookup, int levels, int mapping,
                            int dfg_size, int lobe_size) {
  return game_diffuse_ambient(m.diffuse, e_over_pi) +
         game_split_sum_shade(n, wo, m, e_over_pi, lookup, levels, mapping, dfg_size, lobe_size);
}
