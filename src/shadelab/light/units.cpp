#include "shadelab/light/units.h"

#include <array>

#include "shadelab/core/text.h"

namespace shadelab {

Rgb radiometric_from_photometric(const Rgb& colour, double value) {
  const double y = luminance(colour);
  // A black colour carries no light whatever the value; avoid 0/0.
  if (y <= 0.0) return {};
  return colour * (value / (luminous_efficacy_lm_per_w * y));
}

std::span<const LightUnit> light_units() {
  static const std::array<LightUnit, 13> units = {{
      {"game", LightQuantity::irradiance, "game light colour of a directional light: E = pi x colour"},
      {"W/m2", LightQuantity::irradiance, "irradiance at normal incidence, W m^-2"},
      {"lux", LightQuantity::irradiance, "illuminance at normal incidence, lm m^-2 (683 lm/W)"},
      {"blender-sun", LightQuantity::irradiance, "Blender sun strength, W m^-2"},
      {"game-point", LightQuantity::intensity, "game light colour of a point/spot light at 1 m: I = pi x colour"},
      {"W/sr", LightQuantity::intensity, "radiant intensity, W sr^-1"},
      {"cd", LightQuantity::intensity, "luminous intensity, candela = lm sr^-1 (683 lm/W)"},
      {"W", LightQuantity::intensity, "radiant power over the sphere (point) or the cone (spot)"},
      {"lm", LightQuantity::intensity, "luminous power over the sphere (point) or the cone (spot)"},
      {"blender-W", LightQuantity::intensity, "Blender point/spot power: I = P / (4 pi) for any cone"},
      {"W/m2/sr", LightQuantity::radiance, "radiance"},
      {"nit", LightQuantity::radiance, "luminance, cd m^-2 (683 lm/W)"},
      {"game-radiance", LightQuantity::radiance, "environment or area light value in game units (= radiance)"},
  }};
  return units;
}

const LightUnit* find_light_unit(std::string_view name) {
  for (const auto& u : light_units()) {
    if (u.name == name) return &u;
  }
  return nullptr;
}

namespace {

// To the radiometric base of the quantity: W/m2, W/sr or W/m2/sr.
Rgb to_base(const Rgb& v, std::string_view unit, double cone_sr) {
  if (unit == "game") return irradiance_from_game(v);
  if (unit == "game-point") return intensity_from_game(v);
  if (unit == "lux" || unit == "cd" || unit == "nit") return v / luminous_efficacy_lm_per_w;
  if (unit == "W") return v / cone_sr;
  if (unit == "lm") return v / (cone_sr * luminous_efficacy_lm_per_w);
  if (unit == "blender-W") return intensity_from_blender_watts(v);
  return v;  // W/m2, blender-sun, W/sr, W/m2/sr, game-radiance
}

Rgb from_base(const Rgb& v, std::string_view unit, double cone_sr) {
  if (unit == "game") return game_from_irradiance(v);
  if (unit == "game-point") return game_from_intensity(v);
  if (unit == "lux" || unit == "cd" || unit == "nit") return v * luminous_efficacy_lm_per_w;
  if (unit == "W") return v * cone_sr;
  if (unit == "lm") return v * (cone_sr * luminous_efficacy_lm_per_w);
  if (unit == "blender-W") return blender_watts_from_intensity(v);
  return v;
}

}  // namespace

Result<Rgb> convert_light(const Rgb& value, std::string_view from, std::string_view to, double cos_outer) {
  const LightUnit* a = find_light_unit(from);
  const LightUnit* b = find_light_unit(to);
  if (a == nullptr) return make_error("light: unknown unit '" + printable(from) + "'");
  if (b == nullptr) return make_error("light: unknown unit '" + printable(to) + "'");
  if (a->quantity != b->quantity) {
    return make_error("light: cannot convert '" + std::string(from) + "' to '" + std::string(to) +
                      "': they measure different quantities");
  }
  if (!(cos_outer >= -1.0 && cos_outer < 1.0)) {
    return make_error("light: the cone's cos_outer must be in [-1, 1)");
  }
  // Solid angle of the emitting cone: 2 pi (1 - cos_outer); 4 pi for a point light (cos_outer = -1).
  const double cone_sr = two_pi * (1.0 - cos_outer);
  return from_base(to_base(value, from, cone_sr), to, cone_sr);
}

}  // namespace shadelab
