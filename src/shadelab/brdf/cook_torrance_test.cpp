#include "shadelab/brdf/cook_torrance.h"

#include "shadelab/brdf/fresnel.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/test_util.h"

#include <cmath>

namespace shadelab {
namespace {
using testing::dir;
using testing::make;

TEST(CookTorrance, Form1981IsFourTimesMicrofacet) {
  for (const char* g : {"cook-torrance", "kelemen", "smith"}) {
    const auto a = make("cook-torrance", {{"kd", "0"}, {"g", g}, {"form", "1981"}});
    const auto b = make("cook-torrance", {{"kd", "0"}, {"g", g}, {"form", "microfacet"}});
    const Rgb fa = a->eval(dir(30, 0), dir(50, 170));
    const Rgb fb = b->eval(dir(30, 0), dir(50, 170));
    EXPECT_NEAR(fa.r, 4.0 * fb.r, 1e-14 * fa.r) << g;
  }
}

TEST(CookTorrance, LectureFormulaWithBeckmannAndMinG) {
  // Lecture 5: R_s = F D G / (pi (N.L)(N.V)), D = exp(-(tan a / m)^2) / (m^2 cos^4 a), G = min(1, ...).
  const double m = 0.35;
  const auto f = make("cook-torrance", {{"kd", "0"}, {"ks", "1"}, {"m", "0.35"}, {"g", "cook-torrance"},
                                        {"f", "dielectric"}, {"ior", "1.6"}, {"form", "1981"}});
  const Vec3 l = dir(20, 30);
  const Vec3 v = dir(65, 200);
  const Vec3 h = normalize(l + v);
  const double a = std::acos(h.z);
  const double d = std::exp(-std::pow(std::tan(a) / m, 2)) / (m * m * std::pow(std::cos(a), 4));
  const double vh = dot(v, h);
  const double g = std::min({1.0, 2 * h.z * v.z / vh, 2 * h.z * l.z / vh});
  const double fr = F_dielectric(vh, 1.6);
  const double expected = fr * d * g / (pi * l.z * v.z);
  EXPECT_NEAR(f->eval(l, v).r, expected, 1e-12 * expected);
}

TEST(CookTorrance, KelemenVisibility) {
  const auto f = make("cook-torrance", {{"kd", "0"}, {"ks", "1"}, {"g", "kelemen"}, {"f", "none"}, {"m", "0.4"}});
  const Vec3 l = dir(60, 0);
  const Vec3 v = dir(10, 90);
  const Vec3 h = normalize(l + v);
  const double expected = D_beckmann(h.z, 0.4) / (4.0 * dot(l, h) * dot(l, h));
  EXPECT_NEAR(f->eval(l, v).g, expected, 1e-13 * expected);
}

TEST(CookTorrance, ExponentAndRoughnessAreInterchangeable) {
  // n = 2/m^2 - 2: giving n = 48 is the same as m = 0.2.
  const auto a = make("cook-torrance", {{"n", "48"}});
  const auto b = make("cook-torrance", {{"m", "0.2"}});
  EXPECT_NEAR(a->eval(dir(30, 0), dir(40, 180)).r, b->eval(dir(30, 0), dir(40, 180)).r, 1e-12);
  EXPECT_FALSE(make_brdf("cook-torrance", {{"n", "48"}, {"m", "0.2"}}).has_value());
}

TEST(CookTorrance, BlinnPhongDistributionIsHeightfieldNormalized) {
  const auto f = make("cook-torrance", {{"kd", "0"}, {"d", "blinn-phong"}, {"n", "40"}, {"g", "kelemen"}, {"f", "none"}});
  const Vec3 l = dir(30, 0);
  const Vec3 v = dir(30, 180);  // mirror pair: H = N, L.H = cos 30
  const double expected = (40.0 + 2.0) / (2 * pi) / (4.0 * std::pow(std::cos(deg_to_rad(30)), 2));
  EXPECT_NEAR(f->eval(l, v).b, expected, 1e-12 * expected);
}

TEST(CookTorrance, ConductorFresnelUsesComplexIor) {
  const auto f = make("cook-torrance", {{"kd", "0"}, {"f", "conductor"}, {"ior", "0.2,0.4,1.4"}, {"k", "3.6,2.6,1.9"}});
  const auto* ct = dynamic_cast<const CookTorrance*>(f.get());
  ASSERT_NE(ct, nullptr);
  EXPECT_NEAR(ct->fresnel(1.0).r, f0_from_ior(0.2, 3.6), 1e-12);
  EXPECT_NEAR(ct->fresnel(1.0).b, f0_from_ior(1.4, 1.9), 1e-12);
}

// The Blinn-Phong-distribution sampler draws H with density D cos(theta_h) = (n+2)/(2pi) cos^(n+1): for
// t = cos(theta_h) that is (n+2) t^(n+1) on [0, 1], whose E[ln t] = -1/(n+2). A sampler drawing the exponent
// n instead of n + 1 (with the pdf unchanged) gives -1/(n+1): 5% off at n = 20, 100% at n = 0. The u grid
// is stratified (a quadrature of the sampler's inverse CDF), so the mean is deterministic to ~1e-4.
// (issue 16, 7: this injected bug survived the chi-square test at n = 100 with 500,000 samples.)
TEST(CookTorrance, BlinnPhongSamplerDrawsTheExponentNPlusOne) {
  for (const double n : {0.0, 3.0, 20.0}) {
    const auto f = make("cook-torrance", {{"kd", "0"}, {"d", "blinn-phong"}, {"n", std::to_string(n)}});
    const Vec3 wo{0.0, 0.0, 1.0};  // wi + wo = 2 (N.H) H: H is recovered exactly, on the upper side
    const int count = 100000;
    double sum_log = 0.0;
    int used = 0;
    for (int i = 0; i < count; ++i) {
      const Vec2 u{(i + 0.5) / count, std::fmod(i * 0.6180339887498949, 1.0)};
      const BrdfSample s = f->sample(wo, u, 0.5);
      const Vec3 h = normalize(s.wi + wo);  // wi = reflect(wo, h) = 2 (wo.h) h - wo
      sum_log += std::log(h.z);
      ++used;
    }
    const double mean = sum_log / used;
    EXPECT_NEAR(mean, -1.0 / (n + 2.0), 2e-3 / (n + 2.0)) << "n = " << n << " (exponent n would give " << -1.0 / (n + 1.0) << ")";
  }
}

// Smith's Lambda for Beckmann from its definition as a slope integral (Smith 1967; Walter et al. 2007,
// eq. 27 before integration): Lambda = (1/mu) integral_mu^inf (q - mu) p(q) dq, mu = cot(theta), with the
// Beckmann marginal slope density p(q) = exp(-q^2/m^2) / (m sqrt(pi)). Simpson's rule, written here.
double lambda_by_slope_integral(double cos_theta, double m) {
  const double mu = cos_theta / std::sqrt(1.0 - cos_theta * cos_theta);
  const double top = mu + 12.0 * m;  // exp(-144): nothing left
  const int n = 20000;
  const double h = (top - mu) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double q = mu + i * h;
    const double g = (q - mu) * std::exp(-q * q / (m * m)) / (m * std::sqrt(pi));
    sum += g * (i == 0 || i == n ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
  }
  return sum * h / 3.0 / mu;
}

// The default cook-torrance (kd 0.2, ks 1, Beckmann m = 0.3, height-correlated Smith G, Schlick f0 = 0.04,
// microfacet form) pinned against f = kd/pi + F D G / (4 N.L N.V) built here from the definitions: Beckmann
// D = exp(-tan^2/m^2) / (pi m^2 cos^4), G = 1/(1 + Lambda(L) + Lambda(V)) with Lambda by slope integral,
// F = f0 + (1 - f0)(1 - L.H)^5. (issue 16, 7: G evaluated with twice the roughness survived the suite.)
TEST(CookTorrance, DefaultConfigurationMatchesAnIndependentValue) {
  const auto f = make("cook-torrance");
  const double m = 0.3, kd = 0.2, f0 = 0.04;
  struct Pair {
    double theta_i, phi_i, theta_o, phi_o;
  };
  for (const Pair& p : {Pair{30, 0, 50, 170}, Pair{60, 10, 60, 190}, Pair{75, 0, 20, 150}, Pair{10, 40, 80, 230}}) {
    const Vec3 l = dir(p.theta_i, p.phi_i);
    const Vec3 v = dir(p.theta_o, p.phi_o);
    const Vec3 h = normalize(l + v);
    const double c2 = h.z * h.z;
    const double d = std::exp(-(1.0 - c2) / c2 / (m * m)) / (pi * m * m * c2 * c2);
    const double g = 1.0 / (1.0 + lambda_by_slope_integral(l.z, m) + lambda_by_slope_integral(v.z, m));
    const double fr = f0 + (1.0 - f0) * std::pow(1.0 - dot(l, h), 5.0);
    const double expected = kd / pi + fr * d * g / (4.0 * l.z * v.z);
    const Rgb got = f->eval(l, v);
    EXPECT_NEAR(got.r, expected, 1e-9 * expected) << p.theta_i << " " << p.theta_o;
    EXPECT_EQ(got.r, got.b);
  }
}

}  // namespace
}  // namespace shadelab
