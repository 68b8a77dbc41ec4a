// shadelab light units: explicit conversions between game light units, radiometry and photometry.
//
// Game light unit (Hoffman 2010, Lagarde 2012 "PI or not to PI"): a light's colour is the exit radiance a
// white Lambertian surface facing the light shows. Since L_o = (1/pi) E for such a surface, the light's
// irradiance at normal incidence is E_perp = pi x colour. For a point or spot light the colour is that at
// 1 m, so the radiant intensity is I = pi x colour (W/sr). Radiance (of an environment or an area light) is
// the same number in both conventions: only punctual lights carry the game unit.
//
// Photometry: 683 lm/W, the luminous efficacy of 540 THz (555 nm) radiation that defines the candela (SI
// brochure, 9th ed., 2019). An RGB radiometric quantity maps to the photometric one by 683 x its Rec.709
// luminance, as glTF KHR_lights_punctual (cd, lux) and Filament (lux, lm, cd, nit) use them.
// Blender: a point or spot light of power P watts has intensity P/(4 pi) W/sr whatever the cone, and a sun
// of strength S has irradiance S W/m^2 (the glTF-Blender-IO exporter: point and spot W/(4 pi) x 683 -> cd,
// sun W/m^2 x 683 -> lux).
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "shadelab/color/rgb.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/error.h"

namespace shadelab {

inline constexpr double luminous_efficacy_lm_per_w = 683.0;  // SI definition of the candela

// Game <-> radiometric for punctual lights.
constexpr Rgb irradiance_from_game(const Rgb& colour_game) { return colour_game * pi; }    // E_perp = pi c
constexpr Rgb game_from_irradiance(const Rgb& irradiance) { return irradiance * inv_pi; }
constexpr Rgb intensity_from_game(const Rgb& colour_game) { return colour_game * pi; }     // I = pi c (at 1 m)
constexpr Rgb game_from_intensity(const Rgb& intensity) { return intensity * inv_pi; }

// Power <-> intensity. An isotropic point light: I = Phi / (4 pi). A spot light of uniform intensity over
// a cone of half-angle theta_outer: I = Phi / (2 pi (1 - cos theta_outer)), the cone's solid angle.
constexpr Rgb point_intensity_from_power(const Rgb& power) { return power * inv_four_pi; }
constexpr Rgb point_power_from_intensity(const Rgb& intensity) { return intensity * four_pi; }
inline Rgb spot_intensity_from_power(const Rgb& power, double cos_outer) {
  return power / (two_pi * (1.0 - cos_outer));
}
// Blender's point and spot "Power" (watts): I = P / (4 pi), the cone does not concentrate it.
constexpr Rgb intensity_from_blender_watts(const Rgb& watts) { return watts * inv_four_pi; }
constexpr Rgb blender_watts_from_intensity(const Rgb& intensity) { return intensity * four_pi; }

// Photometric value (lux, cd, nit, lm: per the quantity) of a radiometric RGB quantity, and back for a
// colour (chromaticity; its luminance need not be 1) scaled so its photometric value is `value`.
constexpr double photometric_from_radiometric(const Rgb& radiometric) {
  return luminous_efficacy_lm_per_w * luminance(radiometric);
}
Rgb radiometric_from_photometric(const Rgb& colour, double value);

// Named units for the CLI and scene files. Each belongs to one quantity; conversions stay within it.
enum class LightQuantity {
  irradiance,  // directional lights: game, W/m2, lux, blender-sun
  intensity,   // point and spot lights: game, W/sr, cd, W, lm, blender-W
  radiance,    // area lights, environments: W/m2/sr, nit, game (same number as radiometric)
};

// The quantity's name as `light --list` and shadelab's Python unit list print it.
inline const char* light_quantity_name(LightQuantity q) {
  switch (q) {
    case LightQuantity::irradiance: return "irradiance (directional lights)";
    case LightQuantity::intensity: return "intensity (point and spot lights)";
    case LightQuantity::radiance: return "radiance (area lights, environments)";
  }
  return "";
}

struct LightUnit {
  std::string_view name;
  LightQuantity quantity;
  std::string_view description;
};

// All named units.
std::span<const LightUnit> light_units();
const LightUnit* find_light_unit(std::string_view name);

// Converts a colour from one named unit to another of the same quantity. For W and lm of a spot light,
// cos_outer gives the cone (1 - cos_outer is its solid angle / 2 pi); for a point light pass -1 (the sphere).
Result<Rgb> convert_light(const Rgb& value, std::string_view from, std::string_view to, double cos_outer = -1.0);

}  // namespace shadelab
