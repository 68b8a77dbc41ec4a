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
// Sampling: lobe j is |s|^n (s^.L)^n with s = (Cx V.x, Cy V.y, Cz V.z); it is sampled as a power-cosine lobe
// of exponent n about s^, chosen with probability proportional to its albedo estimate.
#pragma once

#include <vector>

#include "shadelab/brdf/layered.h"

namespace shadelab {

class Lafortune final : public LayeredBrdf {
 public:
  struct Lobe {
    double cx = -1.0;
    double cy = -1.0;
    double cz = 1.0;
    double n = 20.0;
  };
  Lafortune(const Rgb& kd, const Rgb& ks, std::vector<Lobe> lobes);

 protected:
  Rgb specular_eval(const Vec3& wi, const Vec3& wo) const override;
  double specular_pdf(const Vec3& wi, const Vec3& wo) const override;
  Vec3 specular_sample(const Vec3& wo, Vec2 u, double u_lobe) const override;

 private:
  // The lobe axes s_j for this wo and each lobe's selection probability (summing to 1).
  struct Axes {
    std::vector<Vec3> axis;
    std::vector<double> probability;
  };
  Axes axes(const Vec3& wo) const;

  Rgb m_ks;
  std::vector<Lobe> m_lobes;
};

}  // namespace shadelab
