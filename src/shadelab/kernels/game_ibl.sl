// game_ibl: the split sum's per-pixel reads of the files `shadelab bake ibl` writes, written once for the game
// renderer (render/game_renderer.cpp), the exported shaders (`shadelab shader --ibl`) and the browser explorer:
// - the prefiltered GGX chain (envmap/prefilter_ggx.h) read at perceptual roughness r: level lod(r) of a chain
//   of L levels, lod = r (L - 1) (linear) or r (2 - r)(L - 1) (filament: Filament's cmgen / ibl shaders'
//   lodFromPerceptualRoughness), clamped to the chain, each level read seamlessly (cube.sl) and the two
//   levels around lod mixed linearly;
// - the DFG table (envmap/dfg.h): A (channel 0) and B (channel 1) at (N.V, r), texel (i, j) at
//   ((i + 1/2)/n, (j + 1/2)/n), bilinear between texel centres and clamped at the edges.
// The split sum itself (prefiltered (f0 A + f90 B), Karis 2013) and its lookups are game_ambient.sl's. The
// texels come from the language-specific fetches cube_texel / cube_size (the chain's level i is cube i) and
// dfg_texel(i, j, channel) (C++: kernels.h; shaders: their textures).

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
  DfgScaleBias out;
  out.a = (dfg_texel(x0, y0, 0) * (1.0 - tx) + dfg_texel(x1, y0, 0) * tx) * (1.0 - ty) +
          (dfg_texel(x0, y1, 0) * (1.0 - tx) + dfg_texel(x1, y1, 0) * tx) * ty;
  out.b = (dfg_texel(x0, y0, 1) * (1.0 - tx) + dfg_texel(x1, y0, 1) * tx) * (1.0 - ty) +
          (dfg_texel(x0, y1, 1) * (1.0 - tx) + dfg_texel(x1, y1, 1) * tx) * ty;
  return out;
}
