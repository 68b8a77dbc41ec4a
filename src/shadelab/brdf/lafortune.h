// lafortune: the generalized cosine lobes of Lafortune, Foo, Torrance & Greenberg, "Non-Linear
// Approximation of Reflectance Functions", SIGGRAPH 1997, eq. 3-4 (lecture 5 "Empirical BRDF
// Representation"):
//
//   f_r = kd/pi + ks sum_j max(0, Cx_j L.x V.x + Cy_j L.y V.y + Cz_j L.z V.z)^n_j
//
// Each lobe j is (Cx, Cy, Cz, n); Cx = Cy = -1, Cz = 1 is the modified Phong lobe about the mirror direction
// (unnormalized); |C| > 1 brightens a lobe, Cx = Cy > 0 makes it retro-reflective, |Cx| != |Cy| anisotropic.
// Reciprocal (the form is symmetric in L and V). Not energy conserving in general: the lobe magnitudes are
// free parameters, as in the paper's fits.
// eval is the kernel kernels/lafortune.sl (the text shaders also use); at most kernel::LAFORTUNE_MAX_LOBES lobes.
// Sampling: lobe j is |s|^n (s^.L)^n with s = (Cx V.x, Cy V.y, Cz V.z); it is sampled as a power-cosine lobe
// of exponent n about s^, chosen with probability proportional to its albedo estimate.
#pragma once

#include <vector>

#include "shadelab/brdf/lobe_mixture.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {

class Lafortune final : public LobeMixtureBrdf {
 public:
  struct Lobe {
    double cx = -1.0;
    double cy = -1.0;
    double cz = 1.0;
    double n = 20.0;
  };
  // lobes: 1 .. kernel::LAFORTUNE_MAX_LOBES (the registry refuses more).
  Lafortune(const Rgb& kd, const Rgb& ks, std::vector<Lobe> lobes);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return kernel::lafortune_eval(m_k, wi, wo); }
  std::optional<KernelBinding> kernel_binding() const override;
  double game_phong_exponent() const override { return m_lobes.front().n; }  // the first lobe's

 protected:
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return eval_kernel_batch<kernel::lafortune_eval>(m_k, wi, wo, out, n, check_unit);
  }

  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  // The lobe axes s_j for this wo and each lobe's selection probability (summing to 1).
  struct Axes {
    std::vector<Vec3> axis;
    std::vector<double> probability;
  };
  Axes axes(const Vec3& wo) const;

  std::vector<Lobe> m_lobes;
  kernel::LafortuneState m_k;
};

}  // namespace shadelab
