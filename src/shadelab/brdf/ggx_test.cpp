// The GGX family against independent computations: every term written here again from its published
// formula (not the kernels' functions), normalizations and Smith's Lambda by numeric integration, the
// samplers' distributions through their inverse CDFs, Filament's model from its documentation's formulas.
#include "shadelab/brdf/ggx.h"

#include <cmath>
#include <functional>

#include "shadelab/brdf/burley.h"
#include "shadelab/brdf/filament.h"
#include "shadelab/brdf/fresnel.h"
#include "shadelab/brdf/microfacet.h"
#include "shadelab/brdf/test_util.h"
#include "shadelab/numeric/quadrature.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

using testing::dir;
using testing::make;

// ---- independent formulas ----

// GGX / Trowbridge-Reitz, Walter et al. 2007 eq. 33 (isotropic), Heitz 2014 eq. 85 (anisotropic).
double ref_d(const Vec3& h, double ax, double ay) {
  if (h.z <= 0.0) return 0.0;
  const double c2 = h.z * h.z;
  const double tan2_over = (h.x * h.x / (ax * ax) + h.y * h.y / (ay * ay)) / c2;
  return 1.0 / (pi * ax * ay * c2 * c2 * (1.0 + tan2_over) * (1.0 + tan2_over));
}

// Heitz 2014 eq. 86 with the projected roughness alpha_o = sqrt(cos^2 phi ax^2 + sin^2 phi ay^2) (eq. 80).
double ref_lambda(const Vec3& w, double ax, double ay) {
  const double sin2 = 1.0 - w.z * w.z;
  if (sin2 <= 0.0) return 0.0;
  const double cos2_phi = w.x * w.x / sin2;
  const double sin2_phi = w.y * w.y / sin2;
  const double a2 = cos2_phi * ax * ax + sin2_phi * ay * ay;
  const double tan2 = sin2 / (w.z * w.z);
  return (-1.0 + std::sqrt(1.0 + a2 * tan2)) / 2.0;
}

double ref_schlick(double c, double f0) { return f0 + (1.0 - f0) * std::pow(1.0 - c, 5.0); }

double ref_ggx(const Vec3& wi, const Vec3& wo, double ax, double ay, bool correlated, double f0, double kd) {
  const Vec3 h = normalize(wi + wo);
  const double li = ref_lambda(wi, ax, ay);
  const double lo = ref_lambda(wo, ax, ay);
  const double g2 = correlated ? 1.0 / (1.0 + li + lo) : 1.0 / ((1.0 + li) * (1.0 + lo));
  return kd / pi + ref_schlick(dot(wi, h), f0) * ref_d(h, ax, ay) * g2 / (4.0 * wi.z * wo.z);
}

TEST(Ggx, EvalMatchesThePublishedFormula) {
  const Vec3 pairs[][2] = {{dir(20, 10), dir(40, 200)}, {dir(70, 80), dir(5, 0)}, {dir(85, 30), dir(88, 215)}, {dir(0, 0), dir(0, 0)}};
  for (bool correlated : {true, false}) {
    for (const auto& [ax, ay] : {std::pair{0.3, 0.3}, std::pair{0.05, 0.6}, std::pair{1.0, 1.0}}) {
      const auto f = make("ggx", {{"kd", "0.25"}, {"f0", "0.3"}, {"alpha_x", std::to_string(ax)}, {"alpha_y", std::to_string(ay)},
                                  {"g", correlated ? "smith-correlated" : "smith-separable"}});
      for (const auto& p : pairs) {
        const double expected = ref_ggx(p[0], p[1], ax, ay, correlated, 0.3, 0.25);
        EXPECT_NEAR(f->eval(p[0], p[1]).r, expected, 1e-12 * expected) << ax << " " << ay << " " << correlated;
      }
    }
  }
  // Below the horizon: 0.
  EXPECT_TRUE(make("ggx")->eval(dir(100, 0), dir(30, 0)).is_black());
}

TEST(Ggx, RoughnessIsAlphaSquaredAndParametersAreChecked) {
  const auto a = make("ggx", {{"alpha", "0.09"}});
  const auto r = make("ggx", {{"roughness", "0.3"}});
  EXPECT_NEAR(a->eval(dir(30, 0), dir(40, 170)).r, r->eval(dir(30, 0), dir(40, 170)).r, 1e-15);
  EXPECT_FALSE(make_brdf("ggx", {{"alpha", "0.1"}, {"roughness", "0.3"}}));
  EXPECT_FALSE(make_brdf("ggx", {{"alpha_x", "0.1"}}));
  EXPECT_FALSE(make_brdf("ggx", {{"alpha", "0.1"}, {"alpha_x", "0.1"}, {"alpha_y", "0.2"}}));
  const auto e = make_brdf("ggx", {{"alpha", "0"}});
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("'alpha'"), std::string::npos) << e.error().message;
}

// Projected area: integral of D(h) cos(theta_h) d(omega_h) = 1, isotropic and anisotropic (2D midpoint rule in
// (theta, phi) written here, not the library's quadrature).
TEST(Ggx, DistributionIsProjectedAreaNormalized) {
  for (const auto& [ax, ay] : {std::pair{0.02, 0.02}, std::pair{0.2, 0.2}, std::pair{1.0, 1.0}, std::pair{0.1, 0.5}}) {
    // Substitution tan(theta) = a tan(s) (a = min(ax, ay)) puts the peak's width on a fixed scale.
    const double a = std::min(ax, ay);
    const int ns = 4000;
    const int np = 256;
    double sum = 0.0;
    for (int i = 0; i < ns; ++i) {
      const double s = (i + 0.5) * (0.5 * pi / ns);
      const double theta = std::atan(a * std::tan(s));
      const double dtheta_ds = a / (std::cos(s) * std::cos(s) * (1.0 + a * a * std::tan(s) * std::tan(s)));
      for (int j = 0; j < np; ++j) {
        const double phi = (j + 0.5) * (two_pi / np);
        const Vec3 h{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
        sum += D_ggx_aniso(h, ax, ay) * h.z * std::sin(theta) * dtheta_ds;
      }
    }
    EXPECT_NEAR(sum * (0.5 * pi / ns) * (two_pi / np), 1.0, 1e-6) << ax << " " << ay;
  }
  EXPECT_NEAR(D_ggx(0.8, 0.3), ref_d({0.6, 0.0, 0.8}, 0.3, 0.3), 1e-14);
}

// Smith's Lambda from its definition: Lambda = integral_{mu}^{inf} (q - mu) P2(q) dq / mu, mu = cot(theta), with
// GGX's marginal slope density P2(q) = 1 / (2 alpha (1 + q^2/alpha^2)^(3/2)) (Heitz 2014 eqs. 72, 86); and
// G1 against the closed form 2 / (1 + sqrt(1 + alpha^2 tan^2)) (Walter et al. 2007 eq. 34).
TEST(Ggx, SmithG1MatchesItsDefinitionAndClosedForm) {
  for (double alpha : {0.05, 0.3, 1.0}) {
    for (double theta_deg : {10.0, 45.0, 70.0, 85.0, 89.5}) {
      const double t = deg_to_rad(theta_deg);
      const double mu = std::cos(t) / std::sin(t);
      // q = mu + alpha tan(s), s in [0, pi/2): the tail decays like q^-2.
      const int cells = 400000;
      double sum = 0.0;
      for (int i = 0; i < cells; ++i) {
        const double s = (i + 0.5) * (0.5 * pi / cells);
        const double q = mu + alpha * std::tan(s);
        const double dq = alpha / (std::cos(s) * std::cos(s));
        sum += (q - mu) / (2.0 * alpha * std::pow(1.0 + q * q / (alpha * alpha), 1.5)) * dq;
      }
      const double lambda = sum * (0.5 * pi / cells) / mu;
      const Vec3 w{std::sin(t), 0.0, std::cos(t)};
      EXPECT_NEAR(lambda_ggx(w, alpha, alpha), lambda, 1e-6 * std::max(1.0, lambda)) << alpha << " " << theta_deg;
      const double g1 = 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * std::tan(t) * std::tan(t)));
      EXPECT_NEAR(G1_ggx(w, alpha, alpha), g1, 1e-14) << alpha << " " << theta_deg;
    }
  }
  // Anisotropic: the projected roughness of eq. 80.
  const Vec3 w = dir(60, 35);
  EXPECT_NEAR(lambda_ggx(w, 0.1, 0.7), ref_lambda(w, 0.1, 0.7), 1e-14);
  EXPECT_DOUBLE_EQ(lambda_ggx({0.0, 0.0, 1.0}, 0.5, 0.5), 0.0);
}

TEST(Ggx, FilamentVisibilityIsTheCorrelatedG2OverFourCosines) {
  for (double alpha : {0.01, 0.2, 0.9}) {
    for (const auto& [l, v] : {std::pair{dir(10, 0), dir(50, 120)}, std::pair{dir(85, 0), dir(89, 200)}}) {
      const double g2 = 1.0 / (1.0 + ref_lambda(l, alpha, alpha) + ref_lambda(v, alpha, alpha));
      EXPECT_NEAR(V_smith_ggx_correlated(v.z, l.z, alpha), g2 / (4.0 * l.z * v.z), 1e-12 * g2 / (4.0 * l.z * v.z));
    }
  }
}

// The NDF sampler inverts the GGX CDF of theta_h under D cos, U = tan^2 / (alpha^2 + tan^2) (isotropic), and
// puts phi where the stretched slopes point.
TEST(Ggx, NdfSamplerInvertsTheCdf) {
  for (double u : {0.05, 0.5, 0.97}) {
    const Vec3 h = sample_ggx_ndf({u, 0.3}, 0.4, 0.4);
    const double tan2 = (1.0 - h.z * h.z) / (h.z * h.z);
    EXPECT_NEAR(tan2 / (0.16 + tan2), u, 1e-12);
    EXPECT_NEAR(std::atan2(h.y, h.x), two_pi * 0.3, 1e-12);
  }
  // Anisotropic: the stretched slope (h.x / (ax h.z), h.y / (ay h.z)) has radius sqrt(u / (1 - u)), angle 2 pi u.y.
  const Vec3 h = sample_ggx_ndf({0.6, 0.1}, 0.2, 0.8);
  const double sx = h.x / (0.2 * h.z);
  const double sy = h.y / (0.8 * h.z);
  EXPECT_NEAR(std::hypot(sx, sy), std::sqrt(0.6 / 0.4), 1e-12);
  EXPECT_NEAR(std::atan2(sy, sx), two_pi * 0.1, 1e-12);
}

// The two visible-normal samplers draw the same density from the same u up to a measure-preserving remapping;
// here: both produce h with wo.h > 0 and h.z > 0, and their pdf is G1(wo) D / (4 wo.z).
TEST(Ggx, VisibleNormalPdfIsG1DOverFourCos) {
  const Vec3 wo = dir(65, 20);
  const double ax = 0.3;
  const double ay = 0.1;
  Pcg32 rng(7, 9);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 u{rng.next_double(), rng.next_double()};
    for (const Vec3& h : {sample_ggx_vndf_heitz(wo, u, ax, ay), sample_ggx_vndf_caps(wo, u, ax, ay), sample_ggx_vndf_bounded(wo, u, ax, ay)}) {
      ASSERT_GE(h.z, 0.0);
      ASSERT_GT(dot(wo, h), -1e-12);
      const Vec3 wi = reflect(wo, h);
      const double expected = ref_d(h, ax, ay) / (1.0 + ref_lambda(wo, ax, ay)) / (4.0 * wo.z);
      EXPECT_NEAR(ggx_vndf_pdf(wi, wo, ax, ay), expected, 1e-9 * expected);
    }
  }
}

// Bounded VNDF: k of Eto & Tokuyoshi eq. 5 and the pdf scaled by the cut cap's area, (1 + wo_s.z) / (1 + k wo_s.z).
TEST(Ggx, BoundedVndfPdfIsTheCutCapsShare) {
  const Vec3 wo = dir(40, 0);
  const double a = 0.4;
  const double s = 1.0 + std::sin(deg_to_rad(40.0));
  const double k = (1.0 - a * a) * s * s / (s * s + a * a * wo.z * wo.z);
  EXPECT_NEAR(ggx_vndf_bounded_k(wo, a, a), k, 1e-15);
  const double len = std::sqrt(a * a * (1.0 - wo.z * wo.z) + wo.z * wo.z);
  const double vz = wo.z / len;
  const Vec3 wi = dir(30, 180);
  EXPECT_NEAR(ggx_vndf_bounded_pdf(wi, wo, a, a), ggx_vndf_pdf(wi, wo, a, a) * (1.0 + vz) / (1.0 + k * vz), 1e-12);
  // At alpha = 1, k = 0 and the reflected direction is uniform over the upper hemisphere (VNDF reflection of the
  // alpha = 1 GGX maps the cap point to wi itself).
  EXPECT_NEAR(ggx_vndf_bounded_pdf(dir(75, 300), wo, 1.0, 1.0), 1.0 / two_pi, 1e-12);
}

// As alpha -> 0 the lobe narrows to the mirror direction: f cos integrated against a smooth g tends to
// F(theta_o) g(mirror) (Walter et al. 2007 section 5).
TEST(Ggx, SmallAlphaApproachesTheMirror) {
  const Vec3 wo = dir(35, 0);
  const Vec3 mirror{-wo.x, -wo.y, wo.z};
  const auto g = [](const Vec3& w) { return 1.0 + 0.5 * w.x + 0.25 * w.y * w.y; };
  double previous = 1.0;
  for (double alpha : {1e-2, 1e-3, 1e-4}) {
    const auto f = make("ggx", {{"kd", "0"}, {"f0", "0.5"}, {"alpha", std::to_string(alpha)}});
    QuadratureOptions o;
    o.rel_tol = 1e-10;
    o.initial_intervals = 4;
    const VectorQuadratureResult r = integrate_directions(
        [&](const Vec3& wi, std::span<double> out) { out[0] = f->eval(wi, wo).r * wi.z * g(wi); }, 1, mirror,
        SphereRegion::upper, o);
    const double expected = ref_schlick(wo.z, 0.5) * g(mirror);
    const double err = std::abs(r.value[0] - expected) / expected;
    EXPECT_LT(err, previous) << alpha;  // converging
    previous = err;
  }
  EXPECT_LT(previous, 1e-3);
}

// Kulla-Conty: with F = 1 the lobe's colour factor is 1; with Schlick F_avg = (20 f0 + 1)/21; the exact forms'
// F_avg against adaptive quadrature of 2 integral F mu d(mu).
TEST(Ggx, FresnelAverages) {
  EXPECT_EQ(Rgb(kernel::F_average_by_kind_rgb(kernel::FRESNEL_NONE, kernel::rgb(1.5), kernel::rgb(0.0), kernel::rgb(0.04))).r, 1.0);
  EXPECT_NEAR(Rgb(kernel::F_average_by_kind_rgb(kernel::FRESNEL_SCHLICK, kernel::rgb(1.5), kernel::rgb(0.0), kernel::rgb(0.3))).r,
              (20.0 * 0.3 + 1.0) / 21.0, 1e-15);
  QuadratureOptions o;
  o.rel_tol = 1e-12;
  const double schlick = integrate([](double mu) { return 2.0 * mu * ref_schlick(mu, 0.3); }, 0.0, 1.0, o).value;
  EXPECT_NEAR(schlick, (20.0 * 0.3 + 1.0) / 21.0, 1e-12);
  for (const auto& nk : {std::pair{1.5, 0.0}, std::pair{0.27, 3.4}, std::pair{1.1, 6.9}}) {
    const double n = nk.first, k = nk.second;  // not a structured binding: clang 14 cannot capture those
    const double exact = integrate([&](double mu) { return 2.0 * mu * F_conductor(mu, n, k); }, 0.0, 1.0, o).value;
    const kernel::rgb avg = kernel::F_average_by_kind_rgb(k == 0.0 ? kernel::FRESNEL_DIELECTRIC : kernel::FRESNEL_CONDUCTOR,
                                                          kernel::rgb(n), kernel::rgb(k), kernel::rgb(0.0));
    EXPECT_NEAR(avg.r, exact, 2e-6) << n << " " << k;  // Simpson over 32 intervals (fresnel.sl)
  }
}

TEST(Ggx, MultipleScatteringLobeIsSymmetricAndScalesWithTheTables) {
  const auto ss = make("ggx", {{"kd", "0"}, {"f", "none"}, {"alpha", "0.6"}});
  const auto ms = make("ggx", {{"kd", "0"}, {"f", "none"}, {"alpha", "0.6"}, {"ms", "kulla-conty"}});
  const Vec3 a = dir(20, 0);
  const Vec3 b = dir(70, 140);
  const double lobe = ms->eval(a, b).r - ss->eval(a, b).r;
  const double ea = kernel::ggx_energy(kernel::GGX_ENERGY_G_CORRELATED, a.z, 0.6);
  const double eb = kernel::ggx_energy(kernel::GGX_ENERGY_G_CORRELATED, b.z, 0.6);
  const double e_avg = kernel::ggx_energy_average(kernel::GGX_ENERGY_G_CORRELATED, 0.6);
  EXPECT_NEAR(lobe, (1.0 - ea) * (1.0 - eb) / (pi * (1.0 - e_avg)), 1e-12);
  EXPECT_EQ(ms->eval(a, b).r, ms->eval(b, a).r);
}

// cook-torrance with d = ggx is the same lobe as ggx (microfacet form, height-correlated Smith), term by term.
TEST(Ggx, CookTorranceWithGgxDistributionIsGgx) {
  const auto ct = make("cook-torrance", {{"kd", "0.1"}, {"ks", "1"}, {"d", "ggx"}, {"m", "0.35"}, {"f", "schlick"}, {"f0", "0.2"}});
  const auto g = make("ggx", {{"kd", "0.1"}, {"alpha", "0.35"}, {"f0", "0.2"}});
  for (const auto& [l, v] : {std::pair{dir(15, 0), dir(60, 190)}, std::pair{dir(80, 45), dir(30, 250)}}) {
    EXPECT_NEAR(ct->eval(l, v).r, g->eval(l, v).r, 1e-13 * g->eval(l, v).r);
  }
  // The 1981 form is four times the specular part.
  const auto ct81 = make("cook-torrance", {{"kd", "0"}, {"d", "ggx"}, {"m", "0.35"}, {"f", "none"}, {"form", "1981"}});
  const auto g0 = make("ggx", {{"kd", "0"}, {"alpha", "0.35"}, {"f", "none"}});
  EXPECT_NEAR(ct81->eval(dir(15, 0), dir(60, 190)).r, 4.0 * g0->eval(dir(15, 0), dir(60, 190)).r, 1e-12);
}

// ---- Burley ----

TEST(Burley, MatchesThePublishedFormulaAndIsSymmetric) {
  for (double roughness : {0.0, 0.5, 1.0}) {
    const auto f = make("burley", {{"kd", "0.6"}, {"roughness", std::to_string(roughness)}});
    const Vec3 l = dir(30, 0);
    const Vec3 v = dir(75, 160);
    const Vec3 h = normalize(l + v);
    const double fd90 = 0.5 + 2.0 * roughness * dot(l, h) * dot(l, h);
    const double expected = 0.6 / pi * (1.0 + (fd90 - 1.0) * std::pow(1.0 - l.z, 5.0)) * (1.0 + (fd90 - 1.0) * std::pow(1.0 - v.z, 5.0));
    EXPECT_NEAR(f->eval(l, v).r, expected, 1e-14) << roughness;
    EXPECT_EQ(f->eval(l, v).r, f->eval(v, l).r) << roughness;
  }
  // At normal incidence and view the factors are 1: kd / pi.
  EXPECT_NEAR(make("burley", {{"kd", "0.6"}})->eval(dir(0, 0), dir(0, 0)).r, 0.6 / pi, 1e-15);
}

// ---- Filament: its documentation's formulas, written here ----

double fil_d(double noh, double a) {
  const double a2 = a * a;
  const double f = (noh * a2 - noh) * noh + 1.0;
  return a2 / (pi * f * f);
}
double fil_v(double nov, double nol, double a) {
  const double a2 = a * a;
  const double ggxl = nov * std::sqrt(nol * nol * (1.0 - a2) + a2);
  const double ggxv = nol * std::sqrt(nov * nov * (1.0 - a2) + a2);
  return 0.5 / (ggxv + ggxl);
}
// The single-scattering albedo with F = 1 (Filament's dfg.y), by 2D quadrature over wi written here: the
// lobe D V (no Fresnel) times N.L.
double fil_e(double nov, double a) {
  const Vec3 wo{std::sqrt(1.0 - nov * nov), 0.0, nov};
  QuadratureOptions o;
  o.rel_tol = 1e-10;
  o.initial_intervals = 4;
  const VectorQuadratureResult r = integrate_directions(
      [&](const Vec3& wi, std::span<double> out) {
        const Vec3 h = normalize(wi + wo);
        out[0] = wi.z > 0.0 ? fil_d(h.z, a) * fil_v(nov, wi.z, a) * wi.z : 0.0;
      },
      1, Vec3{-wo.x, 0.0, wo.z}, SphereRegion::upper, o);
  return r.value[0];
}

TEST(Filament, MetallicRoughOneMatchesTheDocumentedFormulas) {
  // metallic = 1, perceptual roughness = 1: f0 = base_color, no diffuse, a = 1; compensation 1 + f0 (1/E - 1).
  const Rgb base{0.95, 0.64, 0.54};
  const auto f = make("filament", {{"base_color", "0.95,0.64,0.54"}, {"metallic", "1"}, {"perceptual_roughness", "1"}});
  const auto off = make("filament", {{"base_color", "0.95,0.64,0.54"}, {"metallic", "1"}, {"perceptual_roughness", "1"},
                                     {"energy_compensation", "off"}});
  for (const auto& [l, v] : {std::pair{dir(20, 0), dir(45, 180)}, std::pair{dir(70, 10), dir(10, 100)}, std::pair{dir(85, 0), dir(80, 60)}}) {
    const Vec3 h = normalize(l + v);
    const double e = fil_e(v.z, 1.0);
    for (int c = 0; c < 3; ++c) {
      const double fr = fil_d(h.z, 1.0) * fil_v(v.z, l.z, 1.0) * ref_schlick(dot(l, h), base[c]);
      EXPECT_NEAR(off->eval(l, v)[c], fr, 1e-12 * fr);
      // The table's E differs from the quadrature by its interpolation error (below 3e-4, ggx_energy_test).
      const double compensated = fr * (1.0 + base[c] * (1.0 / e - 1.0));
      EXPECT_NEAR(f->eval(l, v)[c], compensated, 1e-3 * compensated) << c;
    }
  }
}

TEST(Filament, DielectricRemapping) {
  // f0 = 0.16 reflectance^2, diffuse colour = base colour; at normal incidence and view F = f0.
  const auto f = make("filament", {{"base_color", "0.5"}, {"reflectance", "0.7"}, {"perceptual_roughness", "0.4"},
                                   {"energy_compensation", "off"}});
  const Vec3 n = dir(0, 0);
  const double a = 0.16;
  const double expected = 0.5 / pi + fil_d(1.0, a) * fil_v(1.0, 1.0, a) * (0.16 * 0.49);
  EXPECT_NEAR(f->eval(n, n).r, expected, 1e-13);
  // Burley diffuse: Filament passes roughness alpha to Fd_Burley; at normal incidence it is 1/pi.
  const auto b = make("filament", {{"base_color", "0.5"}, {"diffuse", "burley"}, {"energy_compensation", "off"}});
  const Vec3 l = dir(60, 0);
  const Vec3 v = dir(30, 180);
  const Vec3 h = normalize(l + v);
  const double alpha = 0.25;
  const double f90 = 0.5 + 2.0 * alpha * dot(l, h) * dot(l, h);
  const double fd = (1.0 + (f90 - 1.0) * std::pow(1.0 - l.z, 5.0)) * (1.0 + (f90 - 1.0) * std::pow(1.0 - v.z, 5.0)) / pi;
  const double fr = fil_d(h.z, alpha) * fil_v(v.z, l.z, alpha) * ref_schlick(dot(l, h), 0.04);
  EXPECT_NEAR(b->eval(l, v).r, 0.5 * fd + fr, 1e-13);
}

TEST(Filament, ReciprocityClaim) {
  EXPECT_FALSE(make("filament")->is_reciprocal());  // compensation on, f0 = 0.04
  EXPECT_TRUE(make("filament", {{"energy_compensation", "off"}})->is_reciprocal());
  EXPECT_TRUE(make("filament", {{"reflectance", "0"}})->is_reciprocal());  // f0 = 0: the factor is 1
}

}  // namespace
}  // namespace shadelab
