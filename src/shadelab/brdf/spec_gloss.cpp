#include "shadelab/brdf/spec_gloss.h"

#include <algorithm>

namespace shadelab {

namespace {

Ggx::Params ggx_params(const SpecGloss::Params& p) {
  Ggx::Params g;
  g.kd = SpecGloss::c_diff(p);
  g.ks = Rgb{1.0, 1.0, 1.0};
  g.alpha_x = SpecGloss::alpha(p);
  g.alpha_y = g.alpha_x;
  g.f = Ggx::FresnelKind::schlick;  // F = f0 + (1 - f0)(1 - L.H)^5, f0 = specular
  g.f0 = p.specular;
  g.g = Ggx::Geometry::smith_correlated;  // glTF core's V (Appendix B)
  g.ms = Ggx::MultipleScattering::none;
  return g;
}

}  // namespace

// c_diff = diffuse.rgb * (1 - max(specular.r, specular.g, specular.b)) (KHR_materials_pbrSpecularGlossiness README).
Rgb SpecGloss::c_diff(const Params& p) { return p.diffuse * (1.0 - p.specular.max_component()); }

// alpha = (1 - glossiness)^2 (the README), floored as kernels/gltf.sl floors roughness^2.
double SpecGloss::alpha(const Params& p) {
  const double r = 1.0 - p.glossiness;
  return std::max(r * r, kernel::GLTF_ALPHA_MIN);
}

SpecGloss::SpecGloss(const Params& p) : m_p(p), m_ggx(ggx_params(p)) {}

}  // namespace shadelab
