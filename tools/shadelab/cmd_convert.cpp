// shadelab convert shininess --from phong|blinn-phong|blinn-phong-modified --to ggx|beckmann --n N
//   [--metric cosine-l2|cube-root|log] [--json]
// The best-fit roughness for a Phong-family exponent and what the published mappings give beside it, each with its
// residual and its excess over the best fit (fit/shininess.h; docs/conversions.md).
#include <fmt/core.h>

#include <chrono>
#include <cmath>

#include "cli_common.h"
#include "shadelab/fit/shininess.h"

namespace shadelab::cli {

namespace {

struct ShininessOptions {
  std::string from;
  std::string to = "ggx";
  double n = 0.0;
  std::string metric = "cosine-l2";
  bool json = false;
};

std::string shadowing_text(const ShininessConversion& c) {
  const std::string target = c.to == "ggx" ? "the target's Smith height-correlated G (GGX)" : "the target's Smith G (Beckmann)";
  return target + (c.from == "blinn-phong-microfacet" ? ", the source's Smith G (Blinn-Phong D)" : ", none in the source");
}

void run_shininess(const ShininessOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const FitMetric metric = unwrap(parse_fit_metric(o.metric));
  if (!std::isfinite(o.n)) throw UsageError("--n: not a finite number");
  work_begins();
  const ShininessConversion c = unwrap(convert_shininess(o.from, o.to, o.n, metric));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.json) {
    nlohmann::json maps = nlohmann::json::array();
    for (const auto& m : c.mappings) {
      nlohmann::json j = {{"name", m.name}, {"source", m.source}};
      if (m.alpha) {
        j["alpha"] = *m.alpha;
        j["roughness"] = std::sqrt(*m.alpha);
        j["residual"] = m.residual;
        j["relative_residual"] = m.relative_residual;
        j["excess"] = m.excess;
      } else {
        j["alpha"] = nullptr;
        j["roughness"] = nullptr;
        j["residual"] = nullptr;
        j["relative_residual"] = nullptr;
        j["excess"] = nullptr;
      }
      maps.push_back(j);
    }
    print_json({{"from", c.from},
                {"to", c.to},
                {"n", c.n},
                {"metric", fit_metric_name(c.metric)},
                {"alpha", c.alpha},
                {"roughness", std::sqrt(c.alpha)},
                {"residual", c.residual},
                {"relative_residual", c.relative_residual},
                {"at_bound", c.at_bound},
                {"fresnel", "none (F = 1) on both"},
                {"shadowing", shadowing_text(c)},
                {"mappings", maps},
                {"seconds", seconds}});
    return;
  }
  fmt::print("{} n = {:g} -> {}: best alpha {:.6g} (roughness {:.6g}), residual {:.6g} ({}; {:.1f}% of the lobe's own){}\n",
             c.from, c.n, c.to, c.alpha, std::sqrt(c.alpha), c.residual, fit_metric_name(c.metric), 100.0 * c.relative_residual,
             c.at_bound ? " [at the range's end]" : "");
  fmt::print("  Fresnel off (F = 1) on both; masking-shadowing: {}\n", shadowing_text(c));
  for (const auto& m : c.mappings) {
    if (!m.alpha) {
      fmt::print("  {:<8} undefined at n = {:g}   ({})\n", m.name, c.n, m.source);
      continue;
    }
    fmt::print("  {:<8} alpha {:<10.5g} residual {:<10.5g} ({:.1f}% of the lobe's own; excess {:+.1f}%)   ({})\n", m.name,
               *m.alpha, m.residual, 100.0 * m.relative_residual, 100.0 * m.excess, m.source);
  }
}

void add_convert_command(CLI::App& app, Command& command) {
  auto* sub = app.add_subcommand("convert", "convert legacy material parameters, with the conversion's error");
  sub->require_subcommand(1);
  auto o = std::make_shared<ShininessOptions>();
  auto* sh = sub->add_subcommand("shininess", "the best-fit roughness for a Phong-family exponent, beside the published mappings");
  sh->add_option("--from", o->from, "phong, blinn-phong, blinn-phong-modified or blinn-phong-microfacet")->required();
  sh->add_option("--to", o->to, "ggx or beckmann")->capture_default_str();
  sh->add_option("--n", o->n, "the exponent, in [1, 1e6]")->required();
  sh->add_option("--metric", o->metric, "cosine-l2, cube-root or log (fit/metric.h)")->capture_default_str();
  sh->add_flag("--json", o->json, "machine-readable output");
  sh->callback([o, &command] { command.run = [o] { run_shininess(*o); }; });
}

}  // namespace

const CommandRegistration registration_convert(38, add_convert_command);

}  // namespace shadelab::cli
