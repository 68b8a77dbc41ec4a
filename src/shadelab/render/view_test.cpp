// The view transforms of kernels/display.sl (through render/film.h's apply_view) against implementations written
// here from the published sources, independently of the kernel text: the matrices typed as their sources publish
// them (GLSL's column-major mat3 for Filament/three.js's AgX, HLSL's row-major float3x3 for Hill's ACES), the
// Rec.709 -> Rec.2020 matrix derived here from the ITU-R primaries, PBR Neutral in its specification's
// arrangement (g = 1 / (Kd (p - pn) + 1)); plus the properties the sources state.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "shadelab/image/srgb.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/render/film.h"

namespace shadelab {
namespace {

using V3 = std::array<double, 3>;
using M3 = std::array<V3, 3>;  // rows

V3 mul(const M3& m, const V3& v) {
  V3 o{};
  for (int i = 0; i < 3; ++i) o[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
  return o;
}
M3 mul(const M3& a, const M3& b) {
  M3 o{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) o[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  return o;
}
M3 transpose(const M3& m) {
  M3 o{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) o[i][j] = m[j][i];
  return o;
}
M3 inverse(const M3& m) {  // adjugate / determinant
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  M3 o{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      o[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
    }
  return o;
}
// RGB -> XYZ of primaries (xy) and white (xy): SMPTE RP 177-1993, section 3.3.
M3 rgb_to_xyz(const std::array<std::array<double, 2>, 3>& p, std::array<double, 2> w) {
  M3 P{};
  for (int c = 0; c < 3; ++c) {
    P[0][c] = p[c][0] / p[c][1];
    P[1][c] = 1.0;
    P[2][c] = (1.0 - p[c][0] - p[c][1]) / p[c][1];
  }
  const V3 W{w[0] / w[1], 1.0, (1.0 - w[0] - w[1]) / w[1]};
  const V3 s = mul(inverse(P), W);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) P[r][c] *= s[c];
  return P;
}
const std::array<double, 2> kD65{0.3127, 0.3290};
// ITU-R BT.709-6 and BT.2020-2 primaries.
const M3 kRec709ToXyz = rgb_to_xyz({{{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}}}, kD65);
const M3 kRec2020ToXyz = rgb_to_xyz({{{0.708, 0.292}, {0.170, 0.797}, {0.131, 0.046}}}, kD65);
const M3 k709To2020 = mul(inverse(kRec2020ToXyz), kRec709ToXyz);
const M3 k2020To709 = inverse(k709To2020);

double nonneg(double x) { return x > 0.0 ? x : 0.0; }
double clamp01(double x) { return std::min(1.0, std::max(0.0, x)); }

// AgX as Filament/three.js publish it; the matrices as their GLSL source writes them: mat3(col0, col1, col2).
V3 agx_reference(V3 c) {
  const M3 inset_columns{{{0.856627153315983, 0.137318972929847, 0.11189821299995},
                          {0.0951212405381588, 0.761241990602591, 0.0767994186031903},
                          {0.0482516061458583, 0.101439036467562, 0.811302368396859}}};
  const M3 outset_columns{{{1.1271005818144368, -0.1413297634984383, -0.14132976349843826},
                           {-0.11060664309660323, 1.157823702216272, -0.11060664309660294},
                           {-0.016493938717834573, -0.016493938717834257, 1.2519364065950405}}};
  for (auto& x : c) x = nonneg(x);
  c = mul(transpose(inset_columns), mul(k709To2020, c));
  const double lo = -12.47393, hi = 4.026069;  // as published: log2(0.18) - 10 and log2(0.18) + 6.5, rounded
  for (auto& x : c) {
    const double t = clamp01((std::log2(std::max(x, 1e-10)) - lo) / (hi - lo));
    // Wrensch's polynomial, Horner's form.
    x = ((((((15.5 * t - 40.14) * t + 31.96) * t - 6.868) * t + 0.4298) * t + 0.1191) * t - 0.00232);
  }
  c = mul(transpose(outset_columns), c);
  for (auto& x : c) x = x > 0.0 ? std::pow(x, 2.2) : 0.0;
  c = mul(k2020To709, c);
  for (auto& x : c) x = clamp01(x);
  return c;
}

// Khronos PBR Neutral, the specification's formulas.
V3 pbr_neutral_reference(V3 c) {
  const double F90 = 0.04, Ks = 0.8 - F90, Kd = 0.15;
  for (auto& x : c) x = nonneg(x);
  const double x = std::min({c[0], c[1], c[2]});
  const double f = x <= 2.0 * F90 ? x - x * x / (4.0 * F90) : F90;
  const double p = std::max({c[0] - f, c[1] - f, c[2] - f});
  if (p <= Ks) return {c[0] - f, c[1] - f, c[2] - f};
  const double pn = 1.0 - (1.0 - Ks) * (1.0 - Ks) / (p + 1.0 - 2.0 * Ks);
  const double g = 1.0 / (Kd * (p - pn) + 1.0);
  V3 o{};
  for (int i = 0; i < 3; ++i) o[i] = (c[i] - f) * pn / p * g + pn * (1.0 - g);
  return o;
}

// Hill's ACES fit, the HLSL's float3x3 rows as published.
V3 aces_reference(V3 c) {
  const M3 in{{{0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}}};
  const M3 out{{{1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}}};
  for (auto& x : c) x = nonneg(x);
  c = mul(in, c);
  for (auto& v : c) v = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
  c = mul(out, c);
  for (auto& x : c) x = clamp01(x);
  return c;
}

V3 narkowicz_reference(V3 c) {
  for (auto& x : c) x = nonneg(x), x = clamp01(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14));
  return c;
}

V3 kernel_view(ViewTransform v, V3 c, double stops = 0.0) {
  const kernel::rgb o = kernel::view_transform(static_cast<int>(v), stops, kernel::rgb(c[0], c[1], c[2]));
  return {o.r, o.g, o.b};
}

// Points: greys over 20 stops, primaries and secondaries, random HDR colours (log-uniform, with zeros), negatives.
std::vector<V3> test_points() {
  std::vector<V3> pts;
  for (double e = -12; e <= 8; e += 0.25) pts.push_back({std::exp2(e), std::exp2(e), std::exp2(e)});
  for (double s : {0.01, 0.18, 0.5, 1.0, 4.0, 64.0})
    for (V3 d : {V3{1, 0, 0}, V3{0, 1, 0}, V3{0, 0, 1}, V3{1, 1, 0}, V3{0, 1, 1}, V3{1, 0, 1}}) pts.push_back({d[0] * s, d[1] * s, d[2] * s});
  std::mt19937_64 rng(39);
  std::uniform_real_distribution<double> u(-10.0, 7.0);
  for (int i = 0; i < 3000; ++i) {
    V3 c{std::exp2(u(rng)), std::exp2(u(rng)), std::exp2(u(rng))};
    if (i % 10 == 0) c[i % 3] = 0.0;
    pts.push_back(c);
  }
  pts.push_back({-1.0, 0.5, 2.0});
  pts.push_back({0.0, 0.0, 0.0});
  return pts;
}

void expect_matches(ViewTransform v, V3 (*reference)(V3), double tol) {
  for (const V3& c : test_points()) {
    const V3 got = kernel_view(v, c), want = reference(c);
    for (int i = 0; i < 3; ++i) {
      ASSERT_NEAR(got[i], want[i], tol) << view_name(v) << " at (" << c[0] << ", " << c[1] << ", " << c[2] << ") channel " << i;
    }
  }
}

TEST(ViewTransforms, AgxMatchesFilamentsPublishedForm) { expect_matches(ViewTransform::agx, agx_reference, 1e-12); }
TEST(ViewTransforms, PbrNeutralMatchesItsSpecification) { expect_matches(ViewTransform::pbr_neutral, pbr_neutral_reference, 1e-12); }
TEST(ViewTransforms, AcesMatchesHillsFit) { expect_matches(ViewTransform::aces, aces_reference, 1e-12); }
TEST(ViewTransforms, FilmicIsNarkowiczPerChannel) { expect_matches(ViewTransform::filmic, narkowicz_reference, 1e-15); }
TEST(ViewTransforms, StandardIsTheClamp) {
  expect_matches(ViewTransform::standard, [](V3 c) { for (auto& x : c) x = clamp01(x); return c; }, 0.0);
}

TEST(ViewTransforms, KernelRec709ToRec2020IsThePrimariesMatrix) {
  for (int i = 0; i < 3; ++i) {
    V3 e{};
    e[i] = 1.0;
    const kernel::rgb k = kernel::agx_rec709_to_rec2020(kernel::rgb(e[0], e[1], e[2]));
    const kernel::rgb b = kernel::agx_rec2020_to_rec709(kernel::rgb(e[0], e[1], e[2]));
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(k[r], k709To2020[r][i], 1e-15);
      EXPECT_NEAR(b[r], k2020To709[r][i], 1e-14);
    }
  }
  // BT.2407's published (rounded) matrix, to its 4 decimals.
  EXPECT_NEAR(k709To2020[0][0], 0.6274, 5e-5);
  EXPECT_NEAR(k709To2020[0][1], 0.3293, 5e-5);
  EXPECT_NEAR(k709To2020[2][2], 0.8956, 5e-5);
}

TEST(ViewTransforms, ExposureIsAFactorOfTwoPerStop) {
  for (auto v : {ViewTransform::standard, ViewTransform::filmic, ViewTransform::pbr_neutral, ViewTransform::agx, ViewTransform::aces}) {
    const V3 a = kernel_view(v, {0.1, 0.2, 0.05}, 1.5), b = kernel_view(v, {0.1 * std::exp2(1.5), 0.2 * std::exp2(1.5), 0.05 * std::exp2(1.5)});
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], 1e-14) << view_name(v);
  }
}

// The PBR Neutral specification's properties: below the start of compression, c - f (slope 1: the identity up to
// the offset f, which is F90 = 0.04 once min >= 2 F90); every output < 1; the hue (HSV) is kept.
TEST(ViewTransforms, PbrNeutralProperties) {
  for (double x = 0.08; x <= 0.8; x += 0.01) {
    EXPECT_NEAR(kernel_view(ViewTransform::pbr_neutral, {x, x, x})[0], x - 0.04, 1e-15);
    const V3 c{x, 0.5 * x + 0.1, 0.08};  // min 0.08: f = 0.04; max <= 0.8
    const V3 o = kernel_view(ViewTransform::pbr_neutral, c);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(o[i], c[i] - 0.04, 1e-15);
  }
  const auto hue = [](V3 c) {
    return std::atan2(std::sqrt(3.0) * (c[1] - c[2]), 2.0 * c[0] - c[1] - c[2]);  // invariant under c -> a c + b
  };
  for (const V3& c : test_points()) {
    if (c[0] < 0 || c[1] < 0 || c[2] < 0) continue;
    const V3 o = kernel_view(ViewTransform::pbr_neutral, c);
    for (int i = 0; i < 3; ++i) EXPECT_LT(o[i], 1.0);
    const double chroma = std::max({c[0], c[1], c[2]}) - std::min({c[0], c[1], c[2]});
    const double out_chroma = std::max({o[0], o[1], o[2]}) - std::min({o[0], o[1], o[2]});
    if (chroma > 1e-3 * std::max({c[0], c[1], c[2]}) && out_chroma > 1e-9) {
      EXPECT_NEAR(std::remainder(hue(o) - hue(c), 2.0 * M_PI), 0.0, 1e-6) << c[0] << " " << c[1] << " " << c[2];
    }
  }
  EXPECT_LT(kernel_view(ViewTransform::pbr_neutral, {1e6, 1e6, 1e6})[0], 1.0);
}

// AgX's: greys stay grey and increase along the grey axis over its 16.5 stops; middle grey 0.18 lands in the
// middle of the display range (the sigmoid's pivot: 0.18 -> log encoding 10 / 16.5 -> about 0.5 display-encoded).
TEST(ViewTransforms, AgxGreyAxis) {
  double prev = -1.0;
  for (double e = -12.0; e <= 4.0; e += 0.05) {
    const double g = 0.18 * std::exp2(e);
    const V3 o = kernel_view(ViewTransform::agx, {g, g, g});
    EXPECT_NEAR(o[0], o[1], 1e-9);
    EXPECT_NEAR(o[2], o[1], 1e-9);
    if (e > -9.5) {  // below, the sigmoid's fit is < 0: black
      EXPECT_GT(o[1], prev) << e;
    }
    prev = o[1];
  }
  const double mid = linear_to_srgb(kernel_view(ViewTransform::agx, {0.18, 0.18, 0.18})[1]);
  EXPECT_NEAR(mid, 0.5, 0.01);
  const double t = 10.0 / 16.5;  // the log encoding of 0.18
  EXPECT_NEAR(std::log2(0.18), -12.47393 + t * 16.499999, 1e-5);
  EXPECT_NEAR(std::log2(0.18) - 10.0, -12.47393, 1e-5);
  EXPECT_NEAR(std::log2(0.18) + 6.5, 4.026069, 1e-5);
}

TEST(ViewTransforms, ParseNamesAndOcioForms) {
  for (auto v : {ViewTransform::standard, ViewTransform::filmic, ViewTransform::pbr_neutral, ViewTransform::agx, ViewTransform::aces}) {
    auto p = parse_view(view_name(v));
    ASSERT_TRUE(p) << view_name(v);
    EXPECT_EQ(p->transform, v);
  }
  auto o = parse_view("OCIO:/a:b/c.ocio:sRGB:AgX Base");
  ASSERT_TRUE(o);
  EXPECT_EQ(o->transform, ViewTransform::ocio);
  EXPECT_EQ(o->ocio_config, "/a:b/c.ocio");
  EXPECT_EQ(o->ocio_display, "sRGB");
  EXPECT_EQ(o->ocio_view, "AgX Base");
  auto e = parse_view("OCIO::sRGB:Standard");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->ocio_config, "");
  for (const char* bad : {"agx ", "AgX", "", "OCIO:", "OCIO:x", "OCIO:x:y", "OCIO:x::v", "OCIO:x:d:"}) {
    auto b = parse_view(bad);
    EXPECT_FALSE(b) << bad;
  }
}

TEST(ViewTransforms, ApplyViewMatchesTheToneCurves) {
  Image img(3, 1);
  img.set(0, 0, Rgb{0.5, 2.0, -1.0});
  img.set(1, 0, Rgb::gray(0.18));
  img.set(2, 0, Rgb{std::nan(""), 0.0, 1.0});
  for (auto curve : {ToneCurve::clamp, ToneCurve::filmic}) {
    const Image a = tonemap(img, 0.5, curve);
    const auto b = apply_view(img, 0.5, view_of(curve));
    ASSERT_TRUE(b);
    for (std::size_t i = 0; i < a.data.size(); ++i) {
      EXPECT_EQ(linear_to_srgb8(a.data[i]), linear_to_srgb8(b->data[i])) << i;
    }
  }
}

}  // namespace
}  // namespace shadelab
