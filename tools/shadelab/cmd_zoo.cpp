// shadelab zoo [--n N ...] [--json]: the normalization zoo table, numeric against closed form.
#include <fmt/core.h>

#include <cmath>

#include "cli_common.h"
#include "shadelab/analysis/zoo.h"

namespace shadelab::cli {

namespace {

nlohmann::json row_json(const ZooRow& r) {
  nlohmann::json j = {{"model", r.model},
                      {"table", r.table},
                      {"function", r.function_text},
                      {"integrand", r.integrand_text},
                      {"n", r.n},
                      {"closed_form", r.closed_form_text},
                      {"closed_form_value", r.closed_form},
                      {"numeric", r.numeric},
                      {"numeric_error", r.numeric_error},
                      {"relative_error", r.relative_error},
                      {"literature", r.literature}};
  j["lower"] = r.lower ? nlohmann::json(*r.lower) : nlohmann::json(nullptr);
  j["upper"] = r.upper ? nlohmann::json(*r.upper) : nlohmann::json(nullptr);
  j["lower_text"] = r.lower_text;
  j["upper_text"] = r.upper_text;
  return j;
}

void run_zoo(const std::vector<double>& exponents, bool json) {
  for (double n : exponents) {
    if (!std::isfinite(n) || n < 0.0) throw UsageError(fmt::format("--n: {} must be a finite number >= 0", n));
  }
  work_begins();
  nlohmann::json rows = nlohmann::json::array();
  for (double n : exponents) {
    const auto table = unwrap(zoo_table(n));
    if (!json) {
      fmt::print("n = {}\n", n);
      fmt::print("  {:<24} {:<28} {:<38} {:>14} {:>14} {:>9}  {:<26} {}\n", "model", "integrand", "closed form",
                 "closed value", "numeric", "rel.err", "bounds", "literature");
    }
    for (const auto& r : table) {
      rows.push_back(row_json(r));
      if (!json) {
        const std::string bounds =
            r.lower && r.upper ? fmt::format("{:.6g} .. {:.6g}", *r.lower, *r.upper) : std::string("-");
        fmt::print("  {:<24} {:<28} {:<38} {:>14.9g} {:>14.9g} {:>9.1e}  {:<26} {}\n", r.model, r.integrand_text,
                   r.closed_form_text, r.closed_form, r.numeric, r.relative_error, bounds, r.literature);
      }
    }
    if (!json) fmt::print("\n");
  }
  if (json) print_json({{"rows", rows}});
}

}  // namespace

namespace {
void add_zoo_command(CLI::App& app, Command& command) {
  auto exponents = std::make_shared<std::vector<double>>();
  auto json = std::make_shared<bool>(false);
  auto* sub = app.add_subcommand("zoo", "the Blinn-Phong normalization zoo: closed forms against quadrature");
  sub->add_option("--n", *exponents, "specular exponents (default 1 10 100 1000)");
  sub->add_flag("--json", *json, "machine-readable output: {\"rows\": [...]}");
  sub->callback([exponents, json, &command] {
    command.run = [exponents, json] {
      run_zoo(exponents->empty() ? std::vector<double>{1, 10, 100, 1000} : *exponents, *json);
    };
  });
}

}  // namespace

const CommandRegistration registration_zoo(20, add_zoo_command);

}  // namespace shadelab::cli
