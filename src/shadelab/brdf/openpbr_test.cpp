// The openpbr model (brdf/openpbr.h, kernels/openpbr.sl) against an independent computation of OpenPBR 1.1's
// formulas written out here (the spec's anisotropy mapping, GGX D and Smith G from their definitions, Walter et
// al.'s form of the dielectric Fresnel, F82-tint, EON, the coat's ior ratio with the TIR fix, roughening,
// darkening, absorption, the fuzz LTC in an explicit world frame); the energy tables are the kernel's (their own
// proofs: kernels/openpbr_test.cpp). Also: parameter errors, and reciprocity in both layering forms.
#include "shadelab/brdf/openpbr.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "shadelab/brdf/test_util.h"

namespace shadelab {
namespace {

using testing::dir;
using testing::make;

struct Spec {
  double base_weight = 1.0;
  Rgb base_color{0.8, 0.8, 0.8};
  double metalness = 0.0, diffuse_roughness = 0.0;
  double specular_weight = 1.0;
  Rgb specular_color{1, 1, 1};
  double roughness = 0.3, anisotropy = 0.0, ior = 1.5;
  double coat = 0.0;
  Rgb coat_color{1, 1, 1};
  double coat_roughness = 0.0, coat_ior = 1.6, darkening = 1.0;
  double fuzz = 0.0;
  Rgb fuzz_color{1, 1, 1};
  double fuzz_roughness = 0.5;
  bool reciprocal = false;
};

ParamAssignments params_of(const Spec& s) {
  const auto c = [](const Rgb& x) { return std::to_string(x.r) + "," + std::to_string(x.g) + "," + std::to_string(x.b); };
  const auto n = [](double x) { return std::to_string(x); };
  return {{"base_weight", n(s.base_weight)},     {"base_color", c(s.base_color)},
          {"base_metalness", n(s.metalness)},    {"base_diffuse_roughness", n(s.diffuse_roughness)},
          {"specular_weight", n(s.specular_weight)}, {"specular_color", c(s.specular_color)},
          {"specular_roughness", n(s.roughness)}, {"specular_roughness_anisotropy", n(s.anisotropy)},
          {"specular_ior", n(s.ior)},            {"coat_weight", n(s.coat)},
          {"coat_color", c(s.coat_color)},       {"coat_roughness", n(s.coat_roughness)},
          {"coat_ior", n(s.coat_ior)},           {"coat_darkening", n(s.darkening)},
          {"fuzz_weight", n(s.fuzz)},            {"fuzz_color", c(s.fuzz_color)},
          {"fuzz_roughness", n(s.fuzz_roughness)}, {"layering", s.reciprocal ? "reciprocal" : "view"}};
}

// Fresnel of a dielectric, Walter et al. 2007 eq. 22: g = sqrt(eta^2 - 1 + c^2), F = (g - c)^2 / (2 (g + c)^2)
// (1 + ((c (g + c) - 1) / (c (g - c) + 1))^2).
double fresnel(double c, double eta) {
  if (eta == 1.0) return 0.0;
  const double g = std::sqrt(eta * eta - 1.0 + c * c);
  const double a = (g - c) / (g + c);
  const double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

// GGX D (anisotropic, Heitz 2014 eq. 85 written with slopes) and Smith's Lambda (eq. 86).
double ggx_d(const Vec3& h, double ax, double ay) {
  if (h.z <= 0.0) return 0.0;
  const double c2 = h.z * h.z;
  const double tx = h.x * h.x / (ax * ax * c2), ty = h.y * h.y / (ay * ay * c2);
  return 1.0 / (pi * ax * ay * c2 * c2 * std::pow(1.0 + tx + ty, 2.0));
}
double lambda(const Vec3& w, double ax, double ay) {
  const double a2 = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / (w.z * w.z);
  return 0.5 * (std::sqrt(1.0 + a2) - 1.0);
}

Rgb reference(const Spec& s, const Vec3& wi, const Vec3& wo) {
  if (wi.z <= 0.0 || wo.z <= 0.0) return {};
  const Vec3 h = normalize(wi + wo);
  const double vh = dot(wo, h);
  const double C = s.coat;
  // Roughening and the anisotropy mapping.
  const double rb = s.roughness + C * (std::pow(std::min(1.0, std::pow(s.roughness, 4) + 2.0 * std::pow(s.coat_roughness, 4)), 0.25) - s.roughness);
  const double r2 = rb * rb;
  const double at = std::max(1e-4, r2 * std::sqrt(2.0 / (1.0 + std::pow(1.0 - s.anisotropy, 2))));
  const double ab = std::max(1e-4, (1.0 - s.anisotropy) * r2 * std::sqrt(2.0 / (1.0 + std::pow(1.0 - s.anisotropy, 2))));
  const double alpha = std::max(1e-4, r2);
  const double dg = ggx_d(h, at, ab) / (1.0 + lambda(wi, at, ab) + lambda(wo, at, ab)) / (4.0 * wi.z * wo.z);
  // The dielectric's ior ratio and specular_weight's modulation.
  const double eta_bc = s.coat_ior > s.ior ? s.coat_ior / s.ior : s.ior / s.coat_ior;
  const double eta_s = (1.0 - C) * s.ior + C * eta_bc;
  const double fs = std::pow((1.0 - eta_s) / (1.0 + eta_s), 2.0);
  const double eps = std::sqrt(std::clamp(s.specular_weight * fs, 0.0, 1.0));
  const double eta_p = (1.0 + eps) / (1.0 - eps);
  const kernel::OpenpbrDielectricRows drows = kernel::openpbr_dielectric_rows(alpha, eps);
  const auto e_d = [&](double mu) { return kernel::openpbr_dielectric_energy_at(drows, mu); };
  // EON.
  const double sigma = s.diffuse_roughness;
  const double A = 1.0 / (1.0 + (0.5 - 2.0 / (3.0 * pi)) * sigma), B = sigma * A;
  const double eavg = A * (1.0 + (2.0 / 3.0 - 28.0 / (15.0 * pi)) * sigma);
  const auto e_fon = [&](double mu) {
    const double si = std::sqrt(1.0 - mu * mu);
    return A + B / pi * (si * (std::acos(mu) - si * mu) + 2.0 / 3.0 * ((si / mu) * (1.0 - si * si * si) - si));
  };
  const double sv = dot(wi, wo) - wi.z * wo.z;
  const double t = sv > 0.0 ? std::max(wi.z, wo.z) : 1.0;
  Rgb f;
  for (int c = 0; c < 3; ++c) {
    const double rho = s.base_color[c];
    double diffuse = s.base_weight * rho / pi * (A + B * sv / t);
    if (sigma > 0.0) {
      const double rho_ms = rho * rho * eavg / (1.0 - rho * (1.0 - eavg));
      diffuse += s.base_weight * rho_ms / pi * (1.0 - e_fon(wi.z)) * (1.0 - e_fon(wo.z)) / (1.0 - eavg);
    }
    const double scale = s.reciprocal ? (1.0 - e_d(wi.z)) * (1.0 - e_d(wo.z)) / (1.0 - kernel::openpbr_dielectric_energy_average_at(drows))
                                      : 1.0 - e_d(wo.z);
    const double dielectric = s.specular_color[c] * fresnel(vh, eta_p) * dg + scale * diffuse;
    // F82-tint metal with its Kulla-Conty lobe.
    const double f0 = s.base_weight * rho;
    const auto schlick = [&](double mu) { return f0 + (1.0 - f0) * std::pow(1.0 - mu, 5.0); };
    const double mb = 1.0 / 7.0;
    const double fbar = s.specular_color[c] * schlick(mb);
    const double f82 = schlick(vh) - vh * std::pow(1.0 - vh, 6.0) / (mb * std::pow(1.0 - mb, 6.0)) * (schlick(mb) - fbar);
    const double a82 = (schlick(mb) - fbar) / (mb * std::pow(1.0 - mb, 6.0));
    const double favg = s.specular_weight * (f0 + (1.0 - f0) / 21.0 - a82 / 126.0);
    const kernel::GgxEnergyRows g = kernel::ggx_energy_rows(kernel::GGX_ENERGY_G_CORRELATED, alpha);
    const double ems = kernel::ggx_energy_average_at(g);
    const double fms = favg * favg * ems / (1.0 - favg * (1.0 - ems));
    const double metal = s.specular_weight * f82 * dg + fms * (1.0 - kernel::ggx_energy_at(g, wi.z)) *
                                                           (1.0 - kernel::ggx_energy_at(g, wo.z)) / (pi * (1.0 - ems));
    f[c] = s.metalness * metal + (1.0 - s.metalness) * dielectric;
  }
  if (C > 0.0) {
    const double ac = std::max(1e-4, s.coat_roughness * s.coat_roughness);
    const double ec = (s.coat_ior - 1.0) / (s.coat_ior + 1.0);
    const kernel::OpenpbrDielectricRows crows = kernel::openpbr_dielectric_rows(ac, ec);
    const auto e_d_coat = [](const kernel::OpenpbrDielectricRows& rows, double mu) {
      return kernel::openpbr_dielectric_energy_at(rows, mu);
    };
    const double fc = fresnel(vh, s.coat_ior) * ggx_d(h, ac, ac) / (1.0 + lambda(wi, ac, ac) + lambda(wo, ac, ac)) /
                      (4.0 * wi.z * wo.z);
    const double ks = s.reciprocal ? 0.5 * (fresnel(wi.z, s.coat_ior) + fresnel(wo.z, s.coat_ior)) : fresnel(wo.z, s.coat_ior);
    const double ef = kernel::openpbr_dielectric_energy_average_at(kernel::openpbr_dielectric_rows(0.0, ec));
    const double kr = 1.0 - (1.0 - ef) / (s.coat_ior * s.coat_ior);
    const double xifs = std::clamp(s.specular_weight * fs, 0.0, 1.0);
    const double rd = 1.0 + (s.roughness - 1.0) * xifs;
    const double rbe = rd + (s.roughness - rd) * s.metalness;
    const double k = ks + (kr - ks) * rbe;
    const double ed1 = e_d(1.0);
    const double mi = std::sqrt(1.0 - (1.0 - wi.z * wi.z) / (s.coat_ior * s.coat_ior));
    const double mo = std::sqrt(1.0 - (1.0 - wo.z * wo.z) / (s.coat_ior * s.coat_ior));
    const double e_scale = s.reciprocal ? (1.0 - e_d_coat(crows, wi.z)) * (1.0 - e_d_coat(crows, wo.z)) : 1.0 - e_d_coat(crows, wo.z);
    for (int c = 0; c < 3; ++c) {
      const double eb = (1.0 - s.metalness) * (s.specular_color[c] * ed1 + (1.0 - ed1) * s.base_weight * s.base_color[c]) +
                        s.metalness * s.specular_weight * s.base_weight * s.base_color[c];
      const double delta = (1.0 - k) / (1.0 - eb * k);
      const double tr = std::pow(s.coat_color[c], 0.5 * (1.0 / mi + 1.0 / mo));
      f[c] = C * fc + (1.0 - C + C * tr * e_scale) * (1.0 + C * s.darkening * (delta - 1.0)) * f[c];
    }
  }
  if (s.fuzz > 0.0) {
    // The LTC in a world frame: x along wo's projection, y = n x x.
    const double l = std::hypot(wo.x, wo.y);
    const Vec3 x = l > 0.0 ? Vec3{wo.x / l, wo.y / l, 0.0} : Vec3{1.0, 0.0, 0.0};
    const Vec3 y = cross(Vec3{0.0, 0.0, 1.0}, x);
    const double r = std::clamp(s.fuzz_roughness, 0.01, 1.0), m = wo.z;
    const double sg = r * (0.0206607 + 1.58491 * r) / (0.0379424 + r * (1.32227 + r));
    const double mm = r * (-0.193854 + r * (-1.14885 + r * (1.7932 - 0.95943 * r * r))) / (0.046391 + r);
    const double o = r * (0.000654023 + (-0.0207818 + 0.119681 * r) * r) / (1.26264 + r * (-1.92021 + r));
    const auto albedo = [&](double mu) {
      return std::clamp(std::exp(-0.5 * std::pow((mu - mm) / sg, 2.0)) / (sg * std::sqrt(2.0 * pi)) + o, 0.0, 1.0);
    };
    const double ai = (2.58126 * m + 0.813703 * r) * r / (1.0 + 0.310327 * m * m + 2.60994 * m * r);
    const double bi = std::sqrt(1.0 - m) * (r - 1.0) * r * r * r / (0.0000254053 + 1.71228 * m - 1.71506 * m * r + 1.34174 * r * r);
    const Vec3 w{dot(wi, x), dot(wi, y), wi.z};
    const Vec3 v{ai * w.x + bi * w.z, ai * w.y, w.z};  // M^-1 w
    const double len = std::sqrt(dot(v, v));
    const double d = (v.z / len) / pi * ai * ai / (len * len * len);  // D_o(v/|v|) |M^-1| / |M^-1 w|^3
    const double eo = s.fuzz * albedo(wo.z);
    const double scale = s.reciprocal ? (1.0 - s.fuzz * albedo(wi.z)) * (1.0 - eo) : 1.0 - eo;
    for (int c = 0; c < 3; ++c) f[c] = s.fuzz_color[c] * eo * d / wi.z + scale * f[c];
  }
  return f;
}

std::vector<Spec> specs() {
  std::vector<Spec> v;
  v.push_back({});  // OpenPBR's defaults
  Spec s;
  s.base_color = {0.7, 0.3, 0.1};
  s.diffuse_roughness = 0.8;
  s.roughness = 0.5;
  s.anisotropy = 0.6;
  s.specular_color = {1.0, 0.8, 0.6};
  s.ior = 1.33;
  s.specular_weight = 0.7;
  v.push_back(s);
  s.metalness = 0.4;
  s.base_weight = 0.9;
  s.coat = 0.7;
  s.coat_color = {0.9, 0.6, 0.3};
  s.coat_roughness = 0.2;
  s.coat_ior = 1.8;  // above the base's: the TIR fix
  s.darkening = 0.6;
  v.push_back(s);
  s.fuzz = 0.8;
  s.fuzz_color = {0.9, 0.5, 0.2};
  s.fuzz_roughness = 0.3;
  v.push_back(s);
  s.reciprocal = true;
  v.push_back(s);
  s.metalness = 1.0;
  s.roughness = 0.0;
  s.anisotropy = 1.0;
  s.coat_ior = 1.3;
  s.fuzz_roughness = 0.0;
  v.push_back(s);
  return v;
}

// Where wi lies exactly at wo's mirror direction the near-mirror lobes make f huge and relative rounding fine;
// the pairs avoid it at roughness 0 (phi_i = phi_o + 180 with theta_i = theta_o).
TEST(Openpbr, KernelIsTheSpecification) {
  for (const Spec& s : specs()) {
    const BrdfPtr f = make("openpbr", params_of(s));
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

TEST(Openpbr, DefaultsAreOpenPbrs) {
  const auto* m = find_brdf_model("openpbr");
  ASSERT_NE(m, nullptr);
  const auto def = [&](const char* name) {
    for (const auto& p : m->params) {
      if (p.name == name) return p.default_value;
    }
    return std::string("?");
  };
  EXPECT_EQ(def("base_color"), "0.8");
  EXPECT_EQ(def("specular_roughness"), "0.3");
  EXPECT_EQ(def("specular_ior"), "1.5");
  EXPECT_EQ(def("coat_ior"), "1.6");
  EXPECT_EQ(def("coat_darkening"), "1");
  EXPECT_EQ(def("fuzz_roughness"), "0.5");
  EXPECT_EQ(def("layering"), "view");
  EXPECT_TRUE(m->no_shader.size() > 0);
}

TEST(Openpbr, BadValuesNameTheParameter) {
  auto r = make_brdf("openpbr", {{"coat_ior", "0.5"}});
  ASSERT_FALSE(r.has_value());
  EXPECT_NE(r.error().message.find("coat_ior"), std::string::npos) << r.error().message;
  auto l = make_brdf("openpbr", {{"layering", "both"}});
  ASSERT_FALSE(l.has_value());
  EXPECT_NE(l.error().message.find("layering"), std::string::npos) << l.error().message;
  auto n = make_brdf("openpbr", {{"fuzz_weight", "nan"}});
  ASSERT_FALSE(n.has_value());
  EXPECT_NE(n.error().message.find("fuzz_weight"), std::string::npos) << n.error().message;
}

// The reciprocal form is reciprocal to rounding without fuzz (the LTC lobe is a function of wo); the view form is
// not wherever one layer scales another, and its defect max |f(i,o) - f(o,i)| / f is printed.
TEST(Openpbr, ReciprocityOfBothForms) {
  Spec s = specs()[2];
  s.reciprocal = true;
  const BrdfPtr r = make("openpbr", params_of(s));
  EXPECT_TRUE(r->is_reciprocal());
  s.reciprocal = false;
  const BrdfPtr v = make("openpbr", params_of(s));
  EXPECT_FALSE(v->is_reciprocal());
  double worst_r = 0.0, worst_v = 0.0;
  for (double ta : {0.0, 15.0, 45.0, 70.0, 85.0, 89.0}) {
    for (double tb : {5.0, 30.0, 60.0, 80.0, 88.0}) {
      for (double phi : {0.0, 90.0, 200.0}) {
        const Vec3 a = dir(ta, phi), b = dir(tb, 17.0);
        for (int c = 0; c < 3; ++c) {
          const double x = r->eval(a, b)[c], y = r->eval(b, a)[c];
          worst_r = std::max(worst_r, std::abs(x - y) / std::max(x, y));
          const double p = v->eval(a, b)[c], q = v->eval(b, a)[c];
          worst_v = std::max(worst_v, std::abs(p - q) / std::max(p, q));
        }
      }
    }
  }
  std::printf("[ openpbr  ] reciprocity defect max |f(i,o) - f(o,i)| / f: reciprocal form %.2e, view form %.3f\n", worst_r,
              worst_v);
  EXPECT_LE(worst_r, 1e-12);
  EXPECT_GT(worst_v, 1e-3);
  s.fuzz = 0.5;
  s.reciprocal = true;
  EXPECT_FALSE(make("openpbr", params_of(s))->is_reciprocal());
}

}  // namespace
}  // namespace shadelab
