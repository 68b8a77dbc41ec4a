// shadelab brdf list | eval | albedo | check
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include "cli_common.h"
#include "shadelab/analysis/albedo.h"
#include "shadelab/analysis/check.h"
#include "shadelab/core/constants.h"

namespace shadelab::cli {

namespace {

struct BrdfOptions {
  std::string model;
  std::vector<std::string> params;
  std::string wi;
  std::string wo;
  std::vector<double> theta;
  bool json = false;
};

void add_model_options(CLI::App* sub, BrdfOptions& o) {
  sub->add_option("MODEL", o.model, "model name (see brdf list)")->required();
  sub->add_option("-p,--param", o.params, "parameter NAME=VALUE (value: a number, r,g,b or a word); repeatable");
  sub->add_flag("--json", o.json, "machine-readable output");
}

void run_list(bool json) {
  nlohmann::json models = nlohmann::json::array();
  for (const auto& m : brdf_models()) {
    nlohmann::json params = nlohmann::json::array();
    for (const auto& p : m.params) {
      nlohmann::json jp = {{"name", p.name}, {"kind", param_kind_name(p.kind)}, {"default", p.default_value},
                           {"description", p.description}};
      if (p.kind == ParamKind::choice) {
        jp["choices"] = p.choices;
      } else if (p.kind == ParamKind::file) {
        jp["required"] = is_required(p);  // a path: no range
      } else {
        jp["min"] = p.min;
        jp["max"] = p.max;
      }
      params.push_back(jp);
    }
    models.push_back({{"name", m.name}, {"formula", m.summary}, {"source", m.source}, {"params", params}});
    if (!json) {
      fmt::print("{}\n  f_r = {}\n  source: {}\n", m.name, m.summary, m.source);
      for (const auto& p : m.params) {
        const std::string range = p.kind == ParamKind::choice ? fmt::format("{}", fmt::join(p.choices, " | "))
                                  : p.kind == ParamKind::file ? std::string("a path")
                                                              : fmt::format("[{}, {}]", p.min, p.max);
        fmt::print("  {:<14} {:<7} default {:<14} {:<28} {}\n", p.name, param_kind_name(p.kind),
                   is_required(p) ? std::string("(required)") : p.default_value, range, p.description);
      }
    }
  }
  if (json) print_json({{"models", models}});
}

void run_eval(const BrdfOptions& o) {
  const BrdfPtr f = build_brdf(o.model, o.params);
  const Vec3 wi = parse_direction("--wi", o.wi);
  const Vec3 wo = parse_direction("--wo", o.wo);
  const Rgb v = f->eval(wi, wo);
  // A stochastic model (the layered ground truth) states the standard error of the estimate it returned.
  const std::optional<Rgb> se = f->eval_standard_error(wi, wo);
  if (o.json) {
    nlohmann::json j = {{"f", to_json(v)}};
    if (f->is_stochastic()) j["standard_error"] = se ? to_json(*se) : nlohmann::json(nullptr);
    print_json(j);
  } else {
    fmt::print("f = {:.10g} {:.10g} {:.10g}  (1/sr, without the cosine)\n", v.r, v.g, v.b);
    if (se) {
      fmt::print("standard error {:.3g} {:.3g} {:.3g}  (a Monte Carlo estimate: raise walk_samples to reduce it)\n",
                 se->r, se->g, se->b);
    } else if (f->is_stochastic()) {
      fmt::print("standard error unknown from one walk (a Monte Carlo estimate: give walk_samples >= 2)\n");
    }
  }
}

void run_albedo(const BrdfOptions& o) {
  const BrdfPtr f = build_brdf(o.model, o.params);
  std::vector<double> thetas = o.theta;
  if (thetas.empty()) thetas = {0, 15, 30, 45, 60, 75, 85, 89};
  nlohmann::json albedo = nlohmann::json::array();
  for (double t : thetas) {
    if (!std::isfinite(t) || t < 0.0 || t >= 90.0) {
      throw UsageError(fmt::format("--theta: {} is out of range [0, 90) degrees", t));
    }
  }
  work_begins();
  if (!o.json) fmt::print("{:>8}  {:>12} {:>12} {:>12}\n", "theta", "albedo r", "g", "b");
  for (double t : thetas) {
    const Rgb a = directional_albedo(*f, deg_to_rad(t)).albedo;
    albedo.push_back(to_json(a));
    if (!o.json) fmt::print("{:>8.3f}  {:>12.8f} {:>12.8f} {:>12.8f}\n", t, a.r, a.g, a.b);
  }
  if (o.json) print_json({{"theta", thetas}, {"albedo", albedo}});
}

void run_check(const BrdfOptions& o) {
  (void)build_brdf(o.model, o.params);  // a bad model or parameter is refused before the checks run
  work_begins();
  const CheckReport report = unwrap(check_brdf(o.model, parse_assignments(o.params)));
  nlohmann::json items = nlohmann::json::array();
  for (const auto& item : report.items) {
    items.push_back({{"name", item.name}, {"passed", item.passed}, {"figure", item.figure},
                     {"threshold", std::isfinite(item.threshold) ? nlohmann::json(item.threshold) : nlohmann::json(nullptr)},
                     {"detail", item.detail}});
  }
  if (o.json) {
    print_json({{"model", report.model}, {"params", report.params}, {"passed", report.passed()}, {"checks", items}});
  } else {
    fmt::print("{} {}\n", report.model, report.params);
    for (const auto& item : report.items) {
      fmt::print("  {:<4} {:<22} {:>12.4g}  {}\n", item.passed ? "ok" : "FAIL", item.name, item.figure, item.detail);
    }
    fmt::print("{}\n", report.passed() ? "all checks passed" : "some checks failed");
  }
  if (!report.passed()) std::exit(1);  // documented: a check that ran and failed
}

}  // namespace

namespace {
void add_brdf_command(CLI::App& app, Command& command) {
  auto* brdf = app.add_subcommand("brdf", "BRDF models: list, evaluate, directional albedo, checks");
  brdf->require_subcommand(1);

  auto list_json = std::make_shared<bool>(false);
  auto* list = brdf->add_subcommand("list", "models, parameters, defaults and valid ranges");
  list->add_flag("--json", *list_json, "machine-readable output");
  list->callback([list_json, &command] { command.run = [list_json] { run_list(*list_json); }; });

  auto eval_opts = std::make_shared<BrdfOptions>();
  auto* eval = brdf->add_subcommand("eval", "f_r(wi, wo) in the local frame (normal +Z), RGB, without the cosine");
  add_model_options(eval, *eval_opts);
  eval->add_option("--wi", eval_opts->wi, "direction toward the light, X,Y,Z (normalized)")->required();
  eval->add_option("--wo", eval_opts->wo, "direction toward the viewer, X,Y,Z (normalized)")->required();
  eval->callback([eval_opts, &command] { command.run = [eval_opts] { run_eval(*eval_opts); }; });

  auto albedo_opts = std::make_shared<BrdfOptions>();
  auto* albedo = brdf->add_subcommand("albedo", "directional albedo: integral of f cos over the hemisphere");
  add_model_options(albedo, *albedo_opts);
  albedo->add_option("--theta", albedo_opts->theta, "viewing angles in degrees (default 0 15 30 45 60 75 85 89)");
  albedo->callback([albedo_opts, &command] { command.run = [albedo_opts] { run_albedo(*albedo_opts); }; });

  auto check_opts = std::make_shared<BrdfOptions>();
  auto* check = brdf->add_subcommand("check", "normalization, energy, reciprocity, pdf and chi-square checks (exit 1 on failure)");
  add_model_options(check, *check_opts);
  check->callback([check_opts, &command] { command.run = [check_opts] { run_check(*check_opts); }; });

}

}  // namespace

const CommandRegistration registration_brdf(30, add_brdf_command);

}  // namespace shadelab::cli
