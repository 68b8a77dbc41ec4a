// shadelab split-sum lobes: where and how wide the split sum reads its GGX chain for each of its two parts,
// matched to the first moments of the true lobes (shadelab's own correction of the split sum's lobe shape;
// measured by `shadelab ibl-error` against the path tracer, docs/envmap.md).
//
// The split sum (Karis 2013) shades f0 A + f90 B times one read of the chain along R at the roughness r:
// the chain's lobe is the n = v = R GGX lobe, D(h) (R.l) about R, radially symmetric. The true lobes of A and
// B (their weights (1 - Fc) D G2 / (4 N.V) and Fc D G2 / (4 N.V), dfg.h) are neither centred on R nor as
// wide at oblique view: cut by the horizon, stretched, and (B, the Fresnel part) leaning toward grazing.
// Matching first moments: part k's mean direction m_k = integral w_k l dl / integral w_k dl and its spread
// 1 - |m_k| (dfg_lobe_moments) give
//   direction d_k = n rotated toward R by angle_k (the angle of m_k from n, in the plane of n and R), and
//   roughness r_k = sqrt(alpha_k), alpha_k the chain lobe whose spread 1 - mean(R.l) equals part k's,
// except that B is read no rougher than r (split_sum_lobes.cpp says why),
// so that the split sum becomes f0 A chain(d_A, r_A) + f90 B chain(d_B, r_B): two reads of the same chain,
// the same DFG table (the same storage), exact for any environment linear in l (for which a lobe's average
// is L(mean direction) scaled by |m|, matched by the spread), where the single read along R is not.
//
// The chain lobe's spread: with n = v = R, K dl = D(h) (R.l) dl = 4 t D cos(theta_h) d(omega_h), t = R.l =
// cos(2 theta_h); in u = ln(1 + tan^2(theta_h) / alpha^2) (D cos(theta_h) d(omega_h) = e^-u du dphi / (2 pi),
// Walter et al. 2007 eq. 35) spread(alpha) = integral t (1 - t) e^-u du / integral t e^-u du over
// tan^2(theta_h) = alpha^2 (e^u - 1) < 1, with 1 - t = 2 tan^2 / (1 + tan^2). spread(1) = 1/3 (the cosine
// lobe, mean R.l = 2/3), the widest the chain has: a part wider than that reads roughness 1.
//
// Table: SPLIT_SUM_LOBE_SIZE^2 texels as the DFG table's (dfg.h): x = N.V = (i + 0.5) / size, y = perceptual
// roughness r = (j + 0.5) / size, alpha = r^2, read bilinearly between texel centres, clamped at the edges
// but below the first row's centre, where it goes linearly to the mirror (r = 0: angle acos(N.V), roughness 0).
// Computed row by row at first use, by dfg_lobe_moments_gauss (the fixed rule split_sum_lobe_rule(); within
// 1.2e-4 rad and 2e-6 in roughness of the texels from the adaptive moments at relative tolerance 1e-9, measured
// in split_sum_lobes_test.cpp) and the inverse of spread(alpha) (log-log interpolation between 513 nodes,
// alpha in [1e-4, 1]).
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include "shadelab/envmap/specular/dfg.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

// The chain lobe's spread 1 - mean(R.l) at GGX alpha in (0, 1], by adaptive quadrature (above).
double ggx_chain_spread(double alpha);
// Its inverse: the alpha in [1e-4, 1] whose chain lobe has the given spread (1 for spreads of 1/3 and more).
double ggx_chain_alpha_for_spread(double spread);

struct SplitSumLobe {
  double angle = 0.0;      // radians from n toward R
  double roughness = 0.0;  // perceptual roughness the chain is read at
};
struct SplitSumLobes {
  SplitSumLobe a;  // the f0 A part
  SplitSumLobe b;  // the f90 B part
};

// The fixed rule the table's moments are taken with (dfg_lobe_moments_gauss).
DfgGaussRule split_sum_lobe_rule();

// One texel's lobes from the moments at (mu = N.V, perceptual roughness r).
SplitSumLobes split_sum_lobes_at(double mu, double roughness);

constexpr int split_sum_lobe_size = 32;

// The table, each row (a roughness, split_sum_lobe_size texels, a few ms) computed at its first read, once,
// by whichever thread reads it first (others reading it wait; no parallel work inside, so a reader inside a
// TBB task cannot be handed a task that waits on the same row). A render reads the rows its materials'
// roughness values need; all() computes the rest in parallel.
class SplitSumLobeTable {
 public:
  explicit SplitSumLobeTable(int size = split_sum_lobe_size);
  // A table of stored texels (row-major, size^2 of them; split_sum_lobes.json as `bake ibl` writes it), read
  // as they are: nothing is computed.
  SplitSumLobeTable(int size, std::vector<SplitSumLobes> texels);
  int size() const { return size_; }
  // Texel (i, j): N.V column i, roughness row j, each in [0, size).
  const SplitSumLobes& at(int i, int j) const;
  // Every texel, row-major (row = roughness).
  const std::vector<SplitSumLobes>& all() const;

 private:
  void fill_row(int j) const;
  int size_;
  bool stored_ = false;
  mutable std::vector<SplitSumLobes> texels_;
  mutable std::unique_ptr<std::once_flag[]> row_once_;
};
const SplitSumLobeTable& split_sum_lobe_table();

// The table read bilinearly at (N.V, perceptual roughness), as dfg_lookup reads the DFG table: the kernel text
// kernels/game_ibl.sl split_sum_lobes_read (mu or r not finite reads as 0).
SplitSumLobes split_sum_lobes(const SplitSumLobeTable& table, double mu, double roughness);

// The table as the kernels' fetch split_sum_lobe_texel reads it (rows computed at their first read).
void bind_split_sum_lobe_table(kernel::IblTexels& texels, const SplitSumLobeTable& table);

}  // namespace shadelab
