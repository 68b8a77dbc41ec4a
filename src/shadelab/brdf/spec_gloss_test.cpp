// The spec-gloss material (brdf/spec_gloss.h) against the gltf model (kernels/gltf.sl, a different kernel from the
// ggx one spec_gloss evaluates) in the two cases where the extension's formulas make them related exactly, and its
// reciprocity.
#include "shadelab/brdf/spec_gloss.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/analysis/albedo.h"
#include "shadelab/brdf/gltf.h"
#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {

using testing::dir;

const double kThetas[] = {0.0, 15.0, 40.0, 65.0, 85.0};
const double kPhis[] = {0.0, 70.0, 180.0, 250.0};

// The metal branch of glTF core (base_color + (1 - base_color)(1 - V.H)^5) D V is the spec-gloss specular lobe with
// F0 = base_color: f_sg = c_diff / pi + gltf(metallic 1, base_color = specular, roughness = 1 - glossiness).
TEST(SpecGloss, IsLambertPlusTheGltfMetalLobeWithF0Specular) {
  for (const double g : {0.0, 0.35, 0.8, 0.97}) {
    SpecGloss::Params p;
    p.diffuse = Rgb{0.6, 0.3, 0.1};
    p.specular = Rgb{0.9, 0.5, 0.2};
    p.glossiness = g;
    const SpecGloss sg(p);
    Gltf::Params m;
    m.base_color = p.specular;
    m.metallic = 1.0;
    m.roughness = 1.0 - g;
    const Gltf metal(m);
    const Rgb c_diff = p.diffuse * (1.0 - 0.9);  // diffuse (1 - max(specular)), written out
    for (const double ti : kThetas) {
      for (const double pi_ : kPhis) {
        for (const double to : kThetas) {
          const Vec3 wi = dir(ti, pi_), wo = dir(to, 0.0);
          testing::expect_rgb_near(sg.eval(wi, wo), metal.eval(wi, wo) + c_diff * inv_pi, 1e-12);
        }
      }
    }
  }
}

// At specular = 0.04 the spec-gloss diffuse weight is the constant 0.96; glTF's dielectric (metallic 0, ior 1.5,
// specular 1, white specular_color: f0 = 0.04) weighs it by 1 - F(V.H) = 0.96 (1 - (1 - V.H)^5). Their difference is
// exactly -0.96 (1 - V.H)^5 diffuse / pi: the part a metallic-roughness material cannot represent.
TEST(SpecGloss, DiffersFromGltfsDielectricByTheFresnelWeightedDiffuse) {
  SpecGloss::Params p;
  p.diffuse = Rgb{0.8, 0.5, 0.25};
  p.specular = Rgb{0.04, 0.04, 0.04};
  p.glossiness = 0.6;
  const SpecGloss sg(p);
  Gltf::Params m;
  m.base_color = p.diffuse;
  m.metallic = 0.0;
  m.roughness = 0.4;
  const Gltf dielectric(m);
  for (const double ti : kThetas) {
    for (const double pi_ : kPhis) {
      for (const double to : kThetas) {
        const Vec3 wi = dir(ti, pi_), wo = dir(to, 0.0);
        const double vh = dot(wo, normalize(wi + wo));
        const Rgb expected = p.diffuse * (-0.96 * std::pow(1.0 - vh, 5.0) * inv_pi);
        const Rgb got = dielectric.eval(wi, wo) - sg.eval(wi, wo);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-12) << ti << " " << pi_ << " " << to;
      }
    }
  }
}

TEST(SpecGloss, IsReciprocalAndItsDiffuseAlbedoIsCDiff) {
  SpecGloss::Params p;
  p.diffuse = Rgb{0.7, 0.4, 0.2};
  p.specular = Rgb{0.3, 0.2, 0.5};
  p.glossiness = 0.5;
  const SpecGloss sg(p);
  EXPECT_LT(reciprocity_error(sg).max_relative_error, 1e-12);
  testing::expect_rgb_near(sg.diffuse_albedo(), Rgb{0.35, 0.2, 0.1}, 1e-12);
  // Lambertian c_diff plus a specular lobe of albedo in (0, 1): the albedo at normal incidence lies between c_diff
  // and c_diff + 1 (a bound, not a value).
  const Rgb a = directional_albedo(sg, 0.0).albedo;
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(a[c], sg.diffuse_albedo()[c]);
    EXPECT_LT(a[c], sg.diffuse_albedo()[c] + 1.0);
  }
}

}  // namespace
}  // namespace shadelab
