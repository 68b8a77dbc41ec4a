#include "shadelab/light/units.h"

#include <gtest/gtest.h>

#include "shadelab/brdf/registry.h"
#include "shadelab/light/punctual.h"

namespace shadelab {
namespace {

TEST(LightUnits, WhiteGameLightOnWhiteLambertGivesOne) {
  // The definition of the game unit: colour 1 facing a white Lambert surface shows exit radiance 1.
  const auto lambert = make_brdf("lambert", {{"kd", "1"}}).value();
  const DirectionalLight sun{{0.0, 0.0, 1.0}, irradiance_from_game(Rgb::gray(1.0))};
  const auto in = incident(sun, {});
  const Vec3 wo{0.3, 0.0, 0.9539392014169457};
  const Rgb lo = lambert->eval(in.wi, wo) * in.irradiance_perp * in.wi.z;  // L_o = f E_perp cos
  EXPECT_NEAR(lo.r, 1.0, 1e-15);
  EXPECT_NEAR(irradiance_from_game(Rgb::gray(1)).g, pi, 1e-15);
}

TEST(LightUnits, GameRoundTrip) {
  const Rgb c{0.2, 0.5, 3.0};
  const Rgb back = game_from_irradiance(irradiance_from_game(c));
  EXPECT_DOUBLE_EQ(back.b, 3.0);
  EXPECT_DOUBLE_EQ(game_from_intensity(intensity_from_game(c)).r, 0.2);
}

TEST(LightUnits, PhotometricUses683LumensPerWatt) {
  // 1 W/sr of white light is 683 cd; 683 lux of white light is 1 W/m^2.
  EXPECT_DOUBLE_EQ(photometric_from_radiometric(Rgb::gray(1.0)), 683.0);
  const Rgb w = radiometric_from_photometric(Rgb::gray(1.0), 683.0);
  EXPECT_NEAR(w.r, 1.0, 1e-15);
  // A coloured light keeps its chromaticity and its photometric value.
  const Rgb red = radiometric_from_photometric({1.0, 0.1, 0.1}, 100.0);
  EXPECT_NEAR(photometric_from_radiometric(red), 100.0, 1e-12);
  EXPECT_NEAR(red.g / red.r, 0.1, 1e-15);
  EXPECT_TRUE(radiometric_from_photometric({}, 100.0).is_black());
}

TEST(LightUnits, PowerAndIntensity) {
  // Isotropic point light: Phi = 4 pi I.
  EXPECT_NEAR(point_intensity_from_power(Rgb::gray(4 * pi)).r, 1.0, 1e-15);
  // A spot whose cone is the hemisphere (cos_outer = 0): Phi = 2 pi I.
  EXPECT_NEAR(spot_intensity_from_power(Rgb::gray(2 * pi), 0.0).r, 1.0, 1e-15);
  // Blender: P watts give P / (4 pi) W/sr, so 4 pi W is 683 cd (glTF-Blender-IO exporter).
  EXPECT_NEAR(photometric_from_radiometric(intensity_from_blender_watts(Rgb::gray(4 * pi))), 683.0, 1e-12);
}

TEST(LightUnits, NamedConversions) {
  EXPECT_NEAR(convert_light(Rgb::gray(1), "game", "W/m2").value().r, pi, 1e-15);
  EXPECT_NEAR(convert_light(Rgb::gray(1), "game", "lux").value().r, 683 * pi, 1e-9);
  EXPECT_NEAR(convert_light(Rgb::gray(1), "W/sr", "cd").value().r, 683, 1e-12);
  EXPECT_NEAR(convert_light(Rgb::gray(1), "W/sr", "W").value().r, 4 * pi, 1e-12);
  EXPECT_NEAR(convert_light(Rgb::gray(1), "W/sr", "W", 0.5).value().r, pi, 1e-12);  // cone of 60 degrees
  EXPECT_NEAR(convert_light(Rgb::gray(100), "blender-W", "W/sr").value().r, 100 / (4 * pi), 1e-12);
  EXPECT_NEAR(convert_light(Rgb::gray(1), "game-point", "cd").value().r, 683 * pi, 1e-9);
  EXPECT_NEAR(convert_light(Rgb::gray(2), "nit", "W/m2/sr").value().r, 2 / 683.0, 1e-15);
  EXPECT_NEAR(convert_light(Rgb::gray(2), "game-radiance", "W/m2/sr").value().r, 2, 1e-15);
  // Every unit converts to itself unchanged and round-trips through every unit of its quantity.
  for (const auto& a : light_units()) {
    for (const auto& b : light_units()) {
      if (a.quantity != b.quantity) {
        EXPECT_FALSE(convert_light(Rgb::gray(1), a.name, b.name).has_value()) << a.name << " " << b.name;
        continue;
      }
      const Rgb there = convert_light({0.3, 1.0, 2.0}, a.name, b.name, 0.2).value();
      const Rgb back = convert_light(there, b.name, a.name, 0.2).value();
      EXPECT_NEAR(back.b, 2.0, 1e-12) << a.name << " " << b.name;
    }
  }
  EXPECT_FALSE(convert_light(Rgb::gray(1), "candles", "cd").has_value());
  EXPECT_FALSE(convert_light(Rgb::gray(1), "W/sr", "W", 1.0).has_value());
}

}  // namespace
}  // namespace shadelab
