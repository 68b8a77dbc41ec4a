// spec_gloss: the specular-glossiness material of KHR_materials_pbrSpecularGlossiness (github.com/KhronosGroup/glTF,
// extensions/2.0/Archived/KHR_materials_pbrSpecularGlossiness/README.md, "Specular - Glossiness"), with the BRDF of
// the glTF 2.0 core specification it was written against (Appendix B: Lambert plus GGX with Schlick's Fresnel):
//
//   f = c_diff / pi + F(V.H) D(h) V(wi, wo)
//   c_diff = diffuse (1 - max(specular.r, specular.g, specular.b))     (the extension's BRDF inputs)
//   F = specular + (1 - specular) (1 - V.H)^5                          (F0 = specular; Schlick 1994)
//   alpha = (1 - glossiness)^2, floored at 1e-4 as the gltf model floors it (kernels/gltf.sl GLTF_ALPHA_MIN)
//   D, V: isotropic GGX and the height-correlated Smith term, as glTF core's (Appendix B)
//
// The diffuse weight is the constant 1 - max(specular) the extension defines, not the 1 - max3(F(V.H)) of
// KHR_materials_specular's dielectric: that difference is what a conversion to metallic-roughness cannot remove.
// eval, pdf and sample are the ggx model's (brdf/ggx.h, kernels/ggx.sl) with kd = c_diff, f = schlick, f0 =
// specular, g = smith-correlated: the formula exists once. Not a registry model (docs/conversions.md).
#pragma once

#include "shadelab/brdf/brdf.h"
#include "shadelab/brdf/ggx.h"

namespace shadelab {

class SpecGloss final : public Brdf {
 public:
  struct Params {
    Rgb diffuse{1.0, 1.0, 1.0};   // diffuseFactor's rgb (linear)
    Rgb specular{1.0, 1.0, 1.0};  // specularFactor (linear): F0
    double glossiness = 1.0;      // glossinessFactor
  };
  explicit SpecGloss(const Params& p);

  Rgb eval(const Vec3& wi, const Vec3& wo) const override { return m_ggx.eval(wi, wo); }
  std::size_t eval_pairs(const Vec3* wi, const Vec3* wo, Rgb* out, std::size_t n, bool check_unit) const override {
    return m_ggx.eval_pairs(wi, wo, out, n, check_unit);
  }
  double pdf(const Vec3& wi, const Vec3& wo) const override { return m_ggx.pdf(wi, wo); }
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override { return m_ggx.sample(wo, u, u_lobe); }
  bool pdf_smooth_below_horizon() const override { return false; }
  Rgb diffuse_albedo() const override { return c_diff(m_p); }

  const Params& params() const { return m_p; }
  // c_diff = diffuse (1 - max3(specular)) (the extension's README).
  static Rgb c_diff(const Params& p);
  // alpha = max((1 - glossiness)^2, 1e-4) (the extension's README; the gltf model's floor).
  static double alpha(const Params& p);

 private:
  Params m_p;
  Ggx m_ggx;
};

}  // namespace shadelab
