// The gltf model (brdf/gltf.h, kernels/gltf.sl) against an independent computation of the glTF specification's
// formulas written out here (Appendix B's D, V and Fresnel mixes, KHR_materials_anisotropy's alpha_t and
// direction, KHR_materials_sheen's scaling, KHR_materials_clearcoat's fresnel_coat), against the registry's ggx
// model where the two must agree, and its reciprocity as the specification makes it.
#include "shadelab/brdf/gltf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "shadelab/brdf/test_util.h"
#include "shadelab/kernels/kernels.h"

namespace shadelab {
namespace {

using testing::dir;
using testing::make;

struct Spec {
  Rgb base{1, 1, 1};
  double metallic = 1.0, roughness = 1.0, ior = 1.5, specular = 1.0;
  Rgb specular_color{1, 1, 1};
  double aniso = 0.0, rotation = 0.0;
  Rgb sheen{0, 0, 0};
  double sheen_r = 0.0;
  bool ashikhmin = false;
  double clearcoat = 0.0, clearcoat_r = 0.0;
};

ParamAssignments params_of(const Spec& s) {
  const auto c = [](const Rgb& x) { return std::to_string(x.r) + "," + std::to_string(x.g) + "," + std::to_string(x.b); };
  return {{"base_color", c(s.base)},           {"metallic", std::to_string(s.metallic)},
          {"roughness", std::to_string(s.roughness)}, {"ior", std::to_string(s.ior)},
          {"specular", std::to_string(s.specular)},   {"specular_color", c(s.specular_color)},
          {"anisotropy_strength", std::to_string(s.aniso)}, {"anisotropy_rotation", std::to_string(s.rotation)},
          {"sheen_color", c(s.sheen)},          {"sheen_roughness", std::to_string(s.sheen_r)},
          {"sheen_visibility", s.ashikhmin ? "ashikhmin" : "charlie"}, {"clearcoat", std::to_string(s.clearcoat)},
          {"clearcoat_roughness", std::to_string(s.clearcoat_r)}};
}

// The specification's BRDF, term by term, in world coordinates with an explicit tangent frame (not the kernel's
// rotated coordinates): D = 1 / (pi at ab ((t.h/at)^2 + (b.h/ab)^2 + (n.h)^2)^2), V = 1 / (2 (N.L |(at t.V, ab b.V,
// N.V)| + N.V |(at t.L, ab b.L, N.L)|)) (KHR_materials_anisotropy, "Implementation").
Rgb reference(const Spec& s, const Vec3& l, const Vec3& v) {
  if (l.z <= 0.0 || v.z <= 0.0) return {};
  const Vec3 h = normalize(l + v);
  const double vh = dot(v, h);
  const Vec3 t{std::cos(s.rotation), std::sin(s.rotation), 0.0};
  const Vec3 b{-std::sin(s.rotation), std::cos(s.rotation), 0.0};
  const double a = std::max(s.roughness * s.roughness, 1e-4);
  const double at = a + (1.0 - a) * s.aniso * s.aniso;
  const double ab = a;
  const double th = dot(t, h) / at, bh = dot(b, h) / ab;
  const double d = 1.0 / (pi * at * ab * std::pow(th * th + bh * bh + h.z * h.z, 2.0));
  const double lv = l.z * std::hypot(at * dot(t, v), ab * dot(b, v), v.z);
  const double ll = v.z * std::hypot(at * dot(t, l), ab * dot(b, l), l.z);
  const double vis = 0.5 / (lv + ll);
  const double sb = std::pow(1.0 - vh, 5.0);
  Rgb f;
  for (int c = 0; c < 3; ++c) {
    const double metal = (s.base[c] + (1.0 - s.base[c]) * sb) * d * vis;
    double fr[3];
    for (int k = 0; k < 3; ++k) {
      const double f0 = std::min(std::pow((s.ior - 1.0) / (s.ior + 1.0), 2.0) * s.specular_color[k], 1.0);
      fr[k] = f0 + (1.0 - f0) * sb;
    }
    const double fmax = std::max({fr[0], fr[1], fr[2]});
    const double dielectric = (1.0 - s.specular * fmax) * s.base[c] / pi + s.specular * fr[c] * d * vis;
    f[c] = (1.0 - s.metallic) * dielectric + s.metallic * metal;
  }
  const double smax = std::max({s.sheen.r, s.sheen.g, s.sheen.b});
  if (smax > 0.0) {
    const double r = std::clamp(s.sheen_r, 0.07, 1.0);
    const double as = r * r;
    const double sin2 = 1.0 - h.z * h.z;
    const double dc = (2.0 + 1.0 / as) * std::pow(sin2, 0.5 / as) / (2.0 * pi);
    const double vs = s.ashikhmin
                          ? 1.0 / (4.0 * (l.z + v.z - l.z * v.z))
                          : 1.0 / ((1.0 + kernel::sheen_lambda(v.z, as) + kernel::sheen_lambda(l.z, as)) * 4.0 * l.z * v.z);
    const int vis_kind = s.ashikhmin ? 1 : 0;
    const double scale = std::max(0.0, std::min(1.0 - smax * kernel::sheen_energy(vis_kind, v.z, r),
                                                 1.0 - smax * kernel::sheen_energy(vis_kind, l.z, r)));
    for (int c = 0; c < 3; ++c) f[c] = f[c] * scale + s.sheen[c] * dc * vs;
  }
  if (s.clearcoat > 0.0) {
    const double ac = std::max(s.clearcoat_r * s.clearcoat_r, 1e-4);
    const double dcc = ac * ac / (pi * std::pow(h.z * h.z * (ac * ac - 1.0) + 1.0, 2.0));
    const double g = [&] {
      const auto lambda = [&](double c) { return 0.5 * (std::sqrt(1.0 + ac * ac * (1.0 - c * c) / (c * c)) - 1.0); };
      return 1.0 / (1.0 + lambda(l.z) + lambda(v.z));
    }();
    const double fc = s.clearcoat * (0.04 + 0.96 * std::pow(1.0 - v.z, 5.0));
    for (int c = 0; c < 3; ++c) f[c] = f[c] * (1.0 - fc) + fc * dcc * g / (4.0 * l.z * v.z);
  }
  return f;
}

std::vector<Spec> specs() {
  std::vector<Spec> v;
  v.push_back({});
  Spec s;
  s.base = {0.8, 0.3, 0.1};
  s.metallic = 0.0;
  s.roughness = 0.4;
  v.push_back(s);
  s.ior = 1.33;
  s.specular = 0.7;
  s.specular_color = {2.0, 1.0, 0.4};
  s.aniso = 0.6;
  s.rotation = 0.9;
  v.push_back(s);
  s.metallic = 0.4;
  s.sheen = {0.9, 0.5, 0.2};
  s.sheen_r = 0.35;
  v.push_back(s);
  s.ashikhmin = true;
  s.clearcoat = 0.8;
  s.clearcoat_r = 0.2;
  v.push_back(s);
  s.sheen_r = 0.02;  // below the clamp
  s.roughness = 0.0;
  v.push_back(s);
  return v;
}

TEST(Gltf, KernelIsTheSpecification) {
  for (const Spec& s : specs()) {
    const BrdfPtr f = make("gltf", params_of(s));
    ASSERT_TRUE(f);
    for (double ti : {0.0, 20.0, 55.0, 80.0, 88.0}) {
      for (double to : {5.0, 40.0, 70.0, 86.0}) {
        for (double phi : {0.0, 37.0, 150.0, 260.0}) {
          const Vec3 wi = dir(ti, phi), wo = dir(to, 10.0);
          testing::expect_rgb_near(f->eval(wi, wo), reference(s, wi, wo), 1e-9);
        }
      }
    }
  }
}

// A metal without anisotropy, sheen or clearcoat is the ggx model with Schlick's F (f0 = base_color), no diffuse,
// the height-correlated Smith G2: two registry models that must agree to rounding.
TEST(Gltf, MetalIsTheGgxModelWithSchlick) {
  const BrdfPtr g = make("gltf", {{"base_color", "0.9,0.6,0.3"}, {"metallic", "1"}, {"roughness", "0.5"}});
  const BrdfPtr r = make("ggx", {{"kd", "0"}, {"ks", "1"}, {"alpha", "0.25"}, {"f", "schlick"}, {"f0", "0.9,0.6,0.3"}});
  for (double ti : {0.0, 30.0, 75.0}) {
    for (double to : {10.0, 60.0, 85.0}) {
      testing::expect_rgb_near(g->eval(dir(ti, 40.0), dir(to, 200.0)), r->eval(dir(ti, 40.0), dir(to, 200.0)), 1e-12);
    }
  }
}

// fresnel_mix and the sheen scaling treat both directions alike; fresnel_coat reads N.V alone.
TEST(Gltf, ReciprocalWithoutClearcoatOnly) {
  Spec s = specs()[3];
  const BrdfPtr f = make("gltf", params_of(s));
  EXPECT_TRUE(f->is_reciprocal());
  const Vec3 a = dir(25.0, 10.0), b = dir(70.0, 160.0);
  testing::expect_rgb_near(f->eval(a, b), f->eval(b, a), 1e-13);
  s.clearcoat = 1.0;
  const BrdfPtr c = make("gltf", params_of(s));
  EXPECT_FALSE(c->is_reciprocal());
  EXPECT_GT(std::abs(c->eval(a, b).g - c->eval(b, a).g), 1e-3 * c->eval(a, b).g);
}

// At low sheen roughness the specification's scaling 1 - max3(sheen_color) E is negative near grazing (E > 1):
// the model clamps it, so f stays non-negative.
TEST(Gltf, SheenScalingIsClampedWhereTheAlbedoExceedsOne) {
  const BrdfPtr f = make("gltf", {{"metallic", "0"}, {"sheen_color", "1"}, {"sheen_roughness", "0.07"}});
  const Vec3 wo = dir(89.0, 0.0);
  EXPECT_GT(kernel::sheen_energy(kernel::SHEEN_VISIBILITY_CHARLIE, wo.z, 0.07), 1.0);
  for (double t : {0.0, 45.0, 89.0}) {
    const Rgb v = f->eval(dir(t, 180.0), wo);
    EXPECT_GE(v.min_component(), 0.0) << t;
  }
}

TEST(Gltf, EmissionIsCarriedNotReflected) {
  const BrdfPtr f = make("gltf", {{"emissive", "1,0.5,0.25"}, {"emissive_strength", "4"}});
  const auto* g = dynamic_cast<const Gltf*>(f.get());
  ASSERT_NE(g, nullptr);
  testing::expect_rgb_near(g->emission(), Rgb{4.0, 2.0, 1.0}, 0.0);
  const BrdfPtr plain = make("gltf");
  testing::expect_rgb_near(f->eval(dir(10, 0), dir(30, 90)), plain->eval(dir(10, 0), dir(30, 90)), 0.0);
}

}  // namespace
}  // namespace shadelab
