// shadelab prefiltered GGX cube mip chain: the radiance convolved with the GGX lobe of the split-sum
// approximation (Karis 2013, "Real Shading in Unreal Engine 4"), one perceptual roughness per mip level, as
// engines sample it by roughness next to the DFG table (dfg.h).
//
// Under Karis's n = v = R assumption (normal and view both along the lookup direction R), the value at R is
//   out(R) = integral L(l) D(h) max(R.l, 0) dl / integral D(h) max(R.l, 0) dl,   h = normalize(R + l),
// D = GGX (microfacet.sl D_ggx) at alpha = r^2, r the perceptual roughness. Derivation: Karis's estimator is
// sum L(l_k) (n.l_k) / sum (n.l_k) with h_k drawn from D(h) (n.h), i.e. l_k from D (n.h) / (4 v.h), which is
// D / 4 when n = v; its limit is the ratio above (the 1/4 cancels).
//
// Contract:
// - Level i has face size max(1, size >> i) and roughness r_i of the mapping (GgxMipMapping); level 0
//   (r = 0, a delta lobe) is the input, bit for bit.
// - Method (GgxFilterMethod::sum, the default): the formula above summed over the input texels. Levels of
//   face n with n^2 N^2 <= 2^24 (N the input's face size; 16 and below for N = 256), and every level of an
//   input smaller than 8, are summed exactly over every input texel (exact). The others are summed near
//   and far (lobe_near_far.h): exactly over the input texels within near_angle of R, over mid cells of
//   B x B input texels (B = max(4, N / 64)) within mid_angle, and over coarse cells of 4B x 4B beyond it,
//   each cell's flux at its radiance centroid. With w = 2 alpha (the angle from R where D falls to 1/4):
//   near_angle = max(near_cells x 2 B / N, 3 w), mid_angle = max(coarse_cells x 8 B / N, 8 w, near_angle +
//   8 B / N) (2 B / N: a mid cell's angle at a face centre; defaults near_cells 12, coarse_cells 4: 21.5 and
//   28.6 degrees at N = 256 for narrow lobes). A point source is exact wherever it lies; radiance spread
//   over a cell errs by the lobe's curvature across the cell (lobe_near_far.h). Measured against the brute
//   force in docs/envmap.md: 2e-5 to 1.5e-3 in the mean, at most 8.4e-3 (studio), on Blender's 8 HDRIs at N = 256.
// - Method (GgxFilterMethod::sampled): filtered importance sampling (Krivanek & Colbert 2008, "Real-time
//   Shading with Filtered Importance Sampling", eq. 7-8): `samples` deterministic Hammersley half vectors drawn from D(h) (n.h)
//   per output texel (the same set for every texel, rotated into the frame of R); sample k with l-space
//   pdf p_k = D(h_k) / 4 reads the input pyramid (solid-angle-weighted halving) at
//   lod = max(0, 0.5 log2(Omega_s / Omega_p) + lod_bias), Omega_s = 1 / (samples p_k) the sample's solid
//   angle and Omega_p = 4 pi / (6 N^2) the mean solid angle of an input texel; trilinear between pyramid
//   levels, bilinear inside one with taps that cross face edges (a tap past an edge reads the texel of the
//   neighbouring face that its direction falls in; a tap past a corner, the mean of the three texels
//   meeting there), so there are no seams. Coarse levels are summed exactly instead: the formula above over
//   every input texel with its solid angle (prefilter_ggx_brute_force), for every level of face n with
//   3 n^2 <= samples, which keeps those sums together below the cost of sampling the chain (512 samples:
//   faces 8 and below; 1024: 16 and below). Sampling misses or over-weights small bright sources (a sun, a
//   studio light) on the coarse levels, where a sample's footprint is large: the exact sum has no such error.
//   GgxPrefilteredCube::exact says which levels.
// - Deterministic: the same options give the same bits for any thread count (TBB over rows, fixed samples).
// - Errors throw std::invalid_argument naming the option: levels < 0 or > log2(size) + 1 ("levels"), a face
//   size that is not a power of two with more than one level ("size"), samples < 1 or > 2^20 ("samples"),
//   a non-finite or negative lod_bias ("lod_bias"), near_cells or coarse_cells not finite or <= 0 (named), an empty
//   input ("radiance").
#pragma once

#include <string>
#include <vector>

#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/envmap/base/progress.h"
#include "shadelab/envmap/specular/dfg.h"

namespace shadelab {

// How mip level i of L maps to perceptual roughness (the shader's lod for roughness r is the inverse).
enum class GgxRoughnessMapping {
  linear,    // lod = r (L - 1), r_i = i / (L - 1) (glTF-Sample-Viewer's ibl_sampler / shader)
  filament,  // lod = r (2 - r) (L - 1), r_i = 1 - sqrt(1 - i / (L - 1)) (Filament's perceptualRoughnessToLod)
};

// The mapping of a baked chain, as the container writers store it (KTX2 key/value, DDS sidecar JSON).
struct GgxMipMapping {
  GgxRoughnessMapping kind = GgxRoughnessMapping::linear;
  int levels = 1;

  double roughness(int level) const;  // perceptual roughness r_i of level i
  double lod(double r) const;         // the (fractional) level a shader reads for perceptual roughness r
  const char* name() const;           // "linear" | "filament"
  std::string formula() const;        // e.g. "lod = r * (levels - 1)", levels written out
};

// "linear" / "filament" -> the mapping; throws std::invalid_argument naming the option "mapping" otherwise.
GgxRoughnessMapping parse_ggx_roughness_mapping(const std::string& name);

// How the levels below 0 are computed (header: Method).
enum class GgxFilterMethod {
  sum,      // the lobe summed: exact on the coarse levels, near field exact + far field by cells on the rest
  sampled,  // filtered importance sampling, exact on the levels of face n with 3 n^2 <= samples
};
// "sum" / "sampled" -> the method; throws std::invalid_argument naming the option "method" otherwise.
GgxFilterMethod parse_ggx_filter_method(const std::string& name);
const char* ggx_filter_method_name(GgxFilterMethod method);

// How one level of a chain was computed.
enum class GgxLevelMethod { input, exact, near_far, sampled };
const char* ggx_level_method_name(GgxLevelMethod method);  // "input" | "exact" | "near-far" | "sampled"

struct GgxPrefilterOptions {
  int levels = 0;     // 0: down to 1 x 1 (log2(size) + 1 levels)
  GgxRoughnessMapping mapping = GgxRoughnessMapping::linear;
  GgxFilterMethod method = GgxFilterMethod::sum;
  int samples = 1024;     // sampled: Hammersley half vectors per output texel
  double lod_bias = 0.0;  // sampled: added to the solid-angle-matched level (Krivanek & Colbert suggest 1)
  double near_cells = 12.0;  // sum: the near field's radius in mid cells (the cell's angle at a face centre)
  double coarse_cells = 4.0;  // sum: the mid field's radius in coarse cells (at least a coarse cell beyond near)
  ProgressFn progress;    // called on the calling thread between chunks of rows
};

struct GgxPrefilteredCube {
  std::vector<CubeMap> levels;
  GgxMipMapping mapping;
  std::vector<double> roughness;  // perceptual roughness of each level
  std::vector<bool> exact;        // per level: summed exactly over the input (true) or not
  std::vector<GgxLevelMethod> method;  // per level: how it was computed
  GgxFilterMethod filter = GgxFilterMethod::sum;
  int samples = 0;      // sampled: half vectors per texel
  int far_block = 0;     // near_far levels: mid cells of far_block x far_block input texels
  int coarse_block = 0;  // near_far levels: coarse cells of coarse_block x coarse_block input texels
  std::vector<double> near_angle;  // per level: the near field's radius (radians; 0 unless near_far)
  std::vector<double> mid_angle;   // per level: the mid field's radius (radians; 0 unless near_far)
};

// The mip chain described above; the face size of level 0 is radiance.size.
GgxPrefilteredCube prefilter_ggx(const CubeMap& radiance, const GgxPrefilterOptions& options);

// The reference: out(R) of the formula above summed over every input texel with its exact solid angle
// (no sampling, no pyramid), at perceptual roughness r > 0. O(6 N^2) per direction.
Rgb prefilter_ggx_brute_force(const CubeMap& radiance, const Vec3& r, double roughness);

// The chain read as a shader reads it for perceptual roughness r (the mapping's lod(r)): the kernel text
// kernels/game_ibl.sl ggx_chain_read, sample_cube_seamless in the two levels around the lod, linear between
// them, clamped to the chain; r not finite reads as 0 and is clamped to [0, 1] (ggx_chain_roughness).
Rgb sample_ggx_chain(const GgxPrefilteredCube& chain, const Vec3& dir, double roughness);
double ggx_chain_roughness(double roughness);

// A chain's levels (and optionally a DFG table) as the kernels' fetches read them, built once for many reads
// (the game renderer per render, split_sum_filtered_reads per pixel): cube i is level i. Valid while the
// chain (and table) live unchanged. Bind texels() with kernel::IblBinding around the kernel calls.
struct GgxChainTexels {
  explicit GgxChainTexels(const GgxPrefilteredCube& chain);
  kernel::IblTexels texels(const DfgTable* dfg = nullptr) const;
  std::vector<kernel::CubeTexels> cubes;
  int mapping = kernel::GGX_MIP_MAPPING_LINEAR;  // kernels/game_ibl.sl GGX_MIP_MAPPING_*
};

// The filter of prefilter_ggx at any direction: the input pyramid built once, then out(R) at perceptual
// roughness r > 0 from a sample set (make_samples), exactly as prefilter_ggx computes a texel of R's level.
class GgxFilter {
 public:
  struct Sample {
    Vec3 l;         // local frame, R = +Z
    double weight;  // R.l
    double lod;     // fractional pyramid level
  };
  GgxFilter(const CubeMap& radiance, int samples, double lod_bias);
  std::vector<Sample> make_samples(double roughness) const;
  Rgb eval(const Vec3& r, const std::vector<Sample>& samples) const;
  // out[0] = eval(r, samples), bit for bit, and out[1..3] the same sample set reflected with r: out[o] is
  // the estimate at r's image under the reflections of world axis axes[0] (o & 1) and axes[1] (o & 2),
  // its samples the images of r's (a mirrored frame), each read at the mirror image of r's tap texels
  // (the cube's texel grid is symmetric under every axis reflection). The directions, cube coordinates,
  // lods and tap weights are computed once for the four. axes[0] != axes[1].
  void eval_mirrored(const Vec3& r, const std::vector<Sample>& samples, const int (&axes)[2], Rgb (&out)[4]) const;
  const std::vector<CubeMap>& pyramid() const { return pyramid_; }

 private:
  std::vector<CubeMap> pyramid_;
  int samples_;
  double lod_bias_;
};

}  // namespace shadelab
