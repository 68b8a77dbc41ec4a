#include "cli_common.h"

#include <fmt/core.h>

#include <cmath>
#include <iostream>

namespace shadelab::cli {

Vec3 parse_direction(const std::string& option, const std::string& text) {
  auto nums = parse_numbers(text);
  if (!nums) throw UsageError(option + ": " + nums.error().message);
  if (nums->size() != 3) throw UsageError(option + ": expected X,Y,Z, got '" + text + "'");
  const Vec3 v{(*nums)[0], (*nums)[1], (*nums)[2]};
  const double len = length(v);
  if (!(len > 0.0) || !std::isfinite(len)) throw UsageError(option + ": the vector '" + text + "' has zero length");
  return v / len;  // directions are normalized; docs/cli.md says so
}

ParamAssignments parse_assignments(const std::vector<std::string>& params) {
  ParamAssignments out;
  for (const auto& p : params) out.push_back(unwrap(split_assignment(p)));
  return out;
}

BrdfPtr build_brdf(const std::string& model, const std::vector<std::string>& params) {
  return unwrap(make_brdf(model, parse_assignments(params)));
}

nlohmann::json to_json(const Rgb& c) { return nlohmann::json::array({c.r, c.g, c.b}); }

void print_json(const nlohmann::json& j) { std::cout << j.dump(2) << "\n"; }

std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> entries;
  return entries;
}

}  // namespace shadelab::cli
