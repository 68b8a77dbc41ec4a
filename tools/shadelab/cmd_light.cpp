// shadelab light VALUE --from UNIT --to UNIT [--cone DEG] [--json]: light unit conversions.
//
// An r,g,b VALUE is converted per channel (each channel alone, as scene files and engines store colours).
// A photometric quantity of an RGB light is not a vector: it is 683 x the Rec.709 luminance Y of the
// radiometric vector (illuminance in lux, luminous intensity in cd, luminance in nit; light/units.h). So the
// command also prints the luminance Y of the converted vector and that photometric value, named.
#include <fmt/core.h>

#include <cmath>
#include <utility>

#include "cli_common.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/text.h"
#include "shadelab/light/units.h"

namespace shadelab::cli {

namespace {

struct LightOptions {
  std::string value;
  std::string from;
  std::string to;
  double cone_deg = 180.0;
  bool list = false;
  bool json = false;
};

void run_light(const LightOptions& o) {
  if (o.list) {
    nlohmann::json units = nlohmann::json::array();
    for (const auto& u : light_units()) {
      units.push_back({{"name", u.name}, {"quantity", light_quantity_name(u.quantity)}, {"description", u.description}});
      if (!o.json) fmt::print("{:<14} {:<38} {}\n", u.name, light_quantity_name(u.quantity), u.description);
    }
    if (o.json) print_json({{"units", units}});
    return;
  }
  if (o.value.empty() || o.from.empty() || o.to.empty()) throw UsageError("light: give VALUE --from UNIT --to UNIT (units: light --list)");
  auto nums = parse_numbers(o.value);
  if (!nums) throw UsageError("VALUE: " + nums.error().message);
  if (nums->size() != 1 && nums->size() != 3) throw UsageError("VALUE: expected a number or r,g,b, got '" + o.value + "'");
  for (double v : *nums) {
    if (v < 0.0) throw UsageError(fmt::format("VALUE: {} is negative", v));
  }
  if (!std::isfinite(o.cone_deg) || o.cone_deg <= 0.0 || o.cone_deg > 180.0) {
    throw UsageError(fmt::format("--cone: {} is out of range (0, 180] degrees", o.cone_deg));
  }
  // Each unit named by its option (the library's line says only "light: unknown unit").
  for (const auto& [option, unit] : {std::pair<const char*, const std::string*>{"--from", &o.from}, {"--to", &o.to}}) {
    if (find_light_unit(*unit) == nullptr) {
      throw UsageError(std::string(option) + ": unknown unit '" + printable(*unit) + "' (units: shadelab light --list)");
    }
  }
  const Rgb in = nums->size() == 3 ? Rgb{(*nums)[0], (*nums)[1], (*nums)[2]} : Rgb::gray((*nums)[0]);
  // --cone is the half-angle of the outer cone; 180 degrees is the whole sphere, a point light.
  const double cos_outer = std::cos(deg_to_rad(o.cone_deg));
  const Rgb out = unwrap(convert_light(in, o.from, o.to, std::max(-1.0, cos_outer)));
  // The photometric unit of the quantity, and the value of the light in it: 683 Y of the radiometric vector.
  const LightQuantity quantity = find_light_unit(o.from)->quantity;
  const char* photometric_unit = quantity == LightQuantity::irradiance ? "lux" : quantity == LightQuantity::intensity ? "cd" : "nit";
  const char* photometric_name = quantity == LightQuantity::irradiance   ? "illuminance"
                                 : quantity == LightQuantity::intensity ? "luminous intensity"
                                                                        : "luminance";
  const double photometric = luminance(unwrap(convert_light(in, o.from, photometric_unit, std::max(-1.0, cos_outer))));
  const double y = luminance(out);
  // A finite VALUE whose conversion overflows (1e308 game units in W/m2: x pi) is bad input, not "inf" (issue 40, 8).
  if (!std::isfinite(out.r) || !std::isfinite(out.g) || !std::isfinite(out.b)) {
    throw UsageError(fmt::format("VALUE: '{}' {} overflows when converted to {} (the result exceeds the largest double, "
                                 "about 1.8e308)", o.value, o.from, o.to));
  }
  if (!std::isfinite(y) || !std::isfinite(photometric)) {  // printed beside the result: as much an answer
    throw UsageError(fmt::format("VALUE: '{}' {} overflows: its {} in {} (683 x the luminance Y) exceeds the largest "
                                 "double, about 1.8e308", o.value, o.from, photometric_name, photometric_unit));
  }
  if (o.json) {
    print_json({{"value", to_json(out)}, {"unit", o.to}, {"from", {{"value", to_json(in)}, {"unit", o.from}}},
                {"per_channel", true},
                {"luminance", y},
                {"luminance_note", "Rec.709 Y = 0.2126 R + 0.7152 G + 0.0722 B of value, in unit"},
                {"photometric", {{"quantity", photometric_name}, {"value", photometric}, {"unit", photometric_unit},
                                 {"note", "683 x Y of the radiometric vector"}}}});
  } else if (nums->size() == 1) {
    fmt::print("{} {} = {:.10g} {}\n", in.r, o.from, out.r, o.to);
  } else {
    fmt::print("{},{},{} {} = {:.10g},{:.10g},{:.10g} {} (per channel: each channel converted alone)\n", in.r, in.g, in.b,
               o.from, out.r, out.g, out.b, o.to);
    fmt::print("luminance Y (Rec.709) of that vector: {:.10g} {}; the light's {}: {:.10g} {} (683 lm/W x the Y of the radiometric vector)\n", y,
               o.to, photometric_name, photometric, photometric_unit);
  }
}
}  // namespace

namespace {
void add_light_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<LightOptions>();
  auto* sub = app.add_subcommand("light", "convert light values between game, radiometric and photometric units");
  sub->add_option("VALUE", o->value, "a number or r,g,b");
  sub->add_option("--from", o->from, "unit of VALUE (see --list)");
  sub->add_option("--to", o->to, "unit to convert to");
  sub->add_option("--cone", o->cone_deg, "spot light: half-angle of the outer cone in degrees, for W and lm (180 = point light)")
      ->capture_default_str();
  sub->add_flag("--list", o->list, "list the units");
  sub->add_flag("--json", o->json, "machine-readable output: {\"value\": [r, g, b], \"unit\": ...}");
  sub->callback([o, &command] { command.run = [o] { run_light(*o); }; });
}

}  // namespace

const CommandRegistration registration_light(50, add_light_command);

}  // namespace shadelab::cli
