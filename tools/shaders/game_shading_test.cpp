// The game-shading pieces of every export, run on lavapipe in each language against independent oracles: a
// light of game colour c on a white Lambert surface shows c N.L (pi f c N.L with f = 1/pi), the radiometric
// form f E N.L; the D3DX-normalized SH of a directional light of colour 1 gives exit radiance 1 facing it; a
// constant environment L gives L in game units and pi L radiometric; and random SH agree with the C++
// envmap evaluation. The C++ SH functions' band factors equal the kernel's (envmap/sh.h keeps its constants).
#include <gtest/gtest.h>

#include <cmath>

#include "export.h"
#include "glslang.h"
#include "shadelab/core/constants.h"
#include "shadelab/envmap/diffuse/sh.h"
#include "shadelab/kernels/kernels.h"
#include "shadelab/sampling/rng.h"
#include "verify.h"
#include "vulkan_compute.h"

namespace shadelab::shaders {
namespace {

constexpr Lang kLangs[] = {Lang::glsl, Lang::essl, Lang::hlsl};

// Runs `expression` over the pairs with `code` on lavapipe; 4 floats per case.
std::vector<float> run_on_lavapipe(Lang lang, const std::string& code, const std::string& expression,
                                   const std::vector<float>& pairs) {
  auto spirv = compile_compute(lang, compute_harness(lang, code, expression), "test");
  EXPECT_TRUE(spirv.has_value()) << (spirv ? "" : spirv.error().message);
  if (!spirv) return {};
  static auto dev = VulkanDevice::open();
  EXPECT_TRUE(dev.has_value()) << (dev ? "" : dev.error().message);
  if (!dev) return {};
  auto out = (*dev)->run(*spirv, pairs, {});
  EXPECT_TRUE(out.has_value()) << (out ? "" : out.error().message);
  return out ? *out : std::vector<float>{};
}

std::string export_text(const std::string& model, const ParamAssignments& params, Lang lang) {
  ExportOptions o;
  o.lang = lang;
  auto ex = export_model(model, params, o);
  EXPECT_TRUE(ex.has_value());
  return ex ? ex->text : std::string();
}

// A shader function returning the coefficients as constants.
std::string sh_function(const Sh9& sh, Lang lang) {
  const std::string v = type_name("rgb", lang);
  std::string s = "Sh9Coefficients test_sh() {\n  Sh9Coefficients s;\n";
  for (std::size_t i = 0; i < 9; ++i) {
    s += "  s.c[" + std::to_string(i) + "] = " + v + "(" + float_literal(sh.c[i].r) + ", " + float_literal(sh.c[i].g) +
         ", " + float_literal(sh.c[i].b) + ");\n";
  }
  return s + "  return s;\n}\n";
}

TEST(GameShading, PunctualLightInBothUnitConventions) {
  const std::vector<float> pairs = verification_pairs(4096, kDefaultSeed);
  for (Lang lang : kLangs) {
    SCOPED_TRACE(lang_name(lang));
    const std::string code = export_text("lambert", {{"kd", "1"}}, lang);
    const std::string v3 = type_name("rgb", lang);
    const auto game = run_on_lavapipe(lang, code, "brdf_lambert_punctual_game(wi, wo, " + v3 + "(0.25, 0.5, 2.0))", pairs);
    const auto radiometric =
        run_on_lavapipe(lang, code, "brdf_lambert_punctual_radiometric(wi, wo, " + v3 + "(0.25, 0.5, 2.0))", pairs);
    ASSERT_EQ(game.size(), 4 * 4096u);
    ASSERT_EQ(radiometric.size(), 4 * 4096u);
    const double c[3] = {0.25, 0.5, 2.0};
    for (std::size_t i = 0; i < 4096; ++i) {
      const double zi = pairs[8 * i + 2], zo = pairs[8 * i + 6];
      const double lit = (zi > 0.0 && zo > 0.0) ? zi : 0.0;  // white Lambert: pi (1/pi) c N.L = c N.L
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_NEAR(game[4 * i + k], c[k] * lit, 1e-6 * c[k]) << i;
        EXPECT_NEAR(radiometric[4 * i + k], c[k] * lit * inv_pi, 1e-6 * c[k]) << i;  // f E N.L, E = c
      }
    }
  }
}

TEST(GameShading, Sh9IrradianceOracles) {
  Pcg32 rng(7, 11);
  std::vector<float> pairs;  // wi = a unit normal n; wo unused
  for (int i = 0; i < 1024; ++i) {
    const double z = 2.0 * rng.next_double() - 1.0, phi = two_pi * rng.next_double();
    const double r = std::sqrt(1.0 - z * z);
    pairs.insert(pairs.end(), {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                               static_cast<float>(z), 0.0f, 0.0f, 0.0f, 1.0f, 0.0f});
  }
  const Vec3 light = normalize(Vec3{0.3, -0.5, 0.8});
  const Sh9 directional = sh9_directional_light(light, Rgb{1.0, 1.0, 1.0}, true);
  const Sh9 constant = project_sh9([](const Vec3&) { return Rgb{0.5, 0.5, 0.5}; }, 16);
  // A smooth sky-like environment with all nine coefficients non-zero.
  const Sh9 sky = project_sh9(
      [](const Vec3& d) { return Rgb{1.0 + d.z + 0.5 * d.x * d.y, 0.4 + 0.3 * d.x * d.x, 0.2 + 0.6 * std::max(0.0, d.y)}; }, 32);
  for (Lang lang : kLangs) {
    SCOPED_TRACE(lang_name(lang));
    const std::string code = export_text("lambert", {}, lang);
    const std::string v3 = type_name("rgb", lang);
    // Facing the light: exit radiance 1 (D3DXSHEvalDirectionalLight semantics).
    std::vector<float> facing = {static_cast<float>(light.x), static_cast<float>(light.y), static_cast<float>(light.z), 0.0f,
                                 0.0f, 0.0f, 1.0f, 0.0f};
    const auto d = run_on_lavapipe(lang, code + sh_function(directional, lang), "sh9_irradiance_game(test_sh(), wi)", facing);
    ASSERT_EQ(d.size(), 4u);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(d[k], 1.0, 1e-6);
    // A constant environment 0.5: 0.5 in game units, pi 0.5 radiometric, everywhere.
    const auto g = run_on_lavapipe(lang, code + sh_function(constant, lang), "sh9_irradiance_game(test_sh(), wi)", pairs);
    const auto e = run_on_lavapipe(lang, code + sh_function(constant, lang), "sh9_irradiance(test_sh(), wi)", pairs);
    ASSERT_EQ(g.size(), 4 * 1024u);
    ASSERT_EQ(e.size(), 4 * 1024u);
    for (std::size_t i = 0; i < 1024; ++i) {
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_NEAR(g[4 * i + k], 0.5, 1e-6);
        EXPECT_NEAR(e[4 * i + k], pi * 0.5, 3e-6);
      }
    }
    // Random normals under the sky: the shader against the C++ envmap evaluation (radiometric, game, wrapped).
    for (const char* fn : {"sh9_irradiance", "sh9_irradiance_game", "sh9_irradiance_game_wrapped"}) {
      const std::string expr = std::string(fn) + "(test_sh(), wi" + (std::string(fn).find("wrapped") != std::string::npos ? ", 0.4)" : ")");
      const auto s = run_on_lavapipe(lang, code + sh_function(sky, lang), expr, pairs);
      ASSERT_EQ(s.size(), 4 * 1024u);
      for (std::size_t i = 0; i < 1024; ++i) {
        const Vec3 n{pairs[8 * i], pairs[8 * i + 1], pairs[8 * i + 2]};
        const Rgb ref = std::string(fn) == "sh9_irradiance"        ? sh9_irradiance(sky, n)
                        : std::string(fn) == "sh9_irradiance_game" ? sh9_irradiance_game(sky, n)
                                                                    : sh9_evaluate(sky, n, wrapped_band_factors_over_pi(0.4));
        for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(s[4 * i + k], ref[static_cast<int>(k)], 2e-6 * std::max(1.0, std::abs(ref[static_cast<int>(k)]))) << fn;
      }
    }
  }
}

void expect_same(const Rgb& a, const Rgb& b) {
  EXPECT_EQ(a.r, b.r);
  EXPECT_EQ(a.g, b.g);
  EXPECT_EQ(a.b, b.b);
}

// envmap/sh.h keeps its band-factor constants; the kernel's functions use the same numbers, bit for bit.
TEST(GameShading, KernelBandFactorsEqualTheCppConstants) {
  Pcg32 rng(3, 5);
  Sh9 sh;
  kernel::Sh9Coefficients k;
  for (std::size_t i = 0; i < 9; ++i) {
    sh.c[i] = {rng.next_double() - 0.5, rng.next_double(), 2.0 * rng.next_double()};
    k.c[i] = sh.c[i];
  }
  for (int j = 0; j < 200; ++j) {
    const Vec3 n = normalize(Vec3{rng.next_double() - 0.5, rng.next_double() - 0.5, rng.next_double() - 0.5});
    expect_same(kernel::sh9_irradiance(k, n), sh9_irradiance(sh, n));
    expect_same(kernel::sh9_irradiance_game(k, n), sh9_irradiance_game(sh, n));
    const double w = rng.next_double();
    expect_same(kernel::sh9_irradiance_game_wrapped(k, n, w), sh9_evaluate(sh, n, wrapped_band_factors_over_pi(w)));
  }
}

}  // namespace
}  // namespace shadelab::shaders
