// shadelab layering-error MODEL [--param K=V ...] [--theta LIST] [--walks N] [--samples N] [--seed N] [--json]:
// a layered material's shortcut against the `layered` ground truth (analysis/layering_error.h): directional albedo
// over theta and the lobe's RMSE, for the specification's form and the albedo-scaled one.
#include <fmt/core.h>

#include <chrono>

#include "cli_common.h"
#include "shadelab/analysis/layering_error.h"

namespace shadelab::cli {

namespace {

struct LayeringOptions {
  std::string model;
  std::vector<std::string> params;
  std::string thetas;
  int walks = 64;
  int samples = 100000;
  std::uint64_t seed = 1;
  bool json = false;
};

nlohmann::json params_json(const ParamAssignments& p) {
  nlohmann::json o = nlohmann::json::object();
  for (const auto& [k, v] : p) o[k] = v;
  return o;
}

void add_layering_error_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<LayeringOptions>();
  auto* sub = app.add_subcommand(
      "layering-error", "a layered material's shortcut (glTF's clearcoat) against the layered ground truth");
  sub->add_option("model", o->model, "the material model (gltf)")->required();
  sub->add_option("--param", o->params, "model parameter NAME=VALUE (repeatable)");
  sub->add_option("--theta", o->thetas, "viewing angles in degrees, comma-separated (default 0,15,30,45,60,75,85)");
  sub->add_option("--walks", o->walks, "random walks per ground-truth eval on the lobe grid")->capture_default_str();
  sub->add_option("--samples", o->samples, "ground-truth samples per directional albedo")->capture_default_str();
  sub->add_option("--seed", o->seed, "seed of the ground truth's walks")->capture_default_str();
  sub->add_flag("--json", o->json, "machine-readable output");
  sub->callback([o, &command] {
    command.run = [o] {
      LayeringErrorOptions opt;
      if (!o->thetas.empty()) {
        auto t = parse_numbers(o->thetas);
        if (!t || t->empty()) throw UsageError("--theta: expected degrees separated by commas, got '" + o->thetas + "'");
        for (double v : *t) {
          if (!(v >= 0.0 && v < 90.0)) throw UsageError(fmt::format("--theta: {} is out of range [0, 90) degrees", v));
        }
        opt.thetas_deg = *t;
      }
      if (o->walks < 2 || o->walks > 65536) throw UsageError(fmt::format("--walks: {} is out of range [2, 65536]", o->walks));
      if (o->samples < 100 || o->samples > 100000000) {
        throw UsageError(fmt::format("--samples: {} is out of range [100, 1e8]", o->samples));
      }
      if (o->seed > 4294967295ULL) throw UsageError("--seed: must be below 2^32");
      opt.walks = o->walks;
      opt.albedo_samples = o->samples;
      opt.seed = o->seed;
      const auto start = std::chrono::steady_clock::now();
      auto r = layering_error(o->model, parse_assignments(o->params), opt);
      if (!r) throw UsageError(r.error().message);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (o->json) {
        nlohmann::json albedo = nlohmann::json::array();
        for (const auto& a : r->albedo) {
          albedo.push_back({{"theta", a.theta_deg}, {"truth", a.truth}, {"truth_error", a.truth_error},
                            {"model", a.model}, {"albedo_scaled", a.albedo_scaled}, {"truth_furnace", a.truth_furnace}});
        }
        nlohmann::json lobe = nlohmann::json::array();
        for (const auto& l : r->lobe) {
          lobe.push_back({{"theta", l.theta_deg}, {"truth_rms", l.truth_rms}, {"truth_noise_rms", l.truth_noise_rms},
                          {"model_rmse", l.model_rmse}, {"albedo_scaled_rmse", l.albedo_scaled_rmse}});
        }
        print_json({{"model", r->model},
                    {"params", params_json(r->params)},
                    {"truth", {{"model", "layered"}, {"params", params_json(r->truth_params)}, {"samples", opt.albedo_samples}}},
                    {"albedo", albedo},
                    {"lobe", lobe},
                    {"max_albedo_difference", r->max_albedo_difference},
                    {"max_albedo_scaled_difference", r->max_albedo_scaled_difference},
                    {"seconds", seconds}});
        return;
      }
      std::string truth;
      for (const auto& [k, v] : r->truth_params) truth += " " + k + "=" + v;
      fmt::print("{}: the specification's layering against the ground truth (layered{})\n", r->model, truth);
      fmt::print("directional albedo (green channel)\n");
      fmt::print("  theta   truth (+- se)          {:<10} albedo-scaled   truth's white furnace\n", r->model);
      for (const auto& a : r->albedo) {
        fmt::print("  {:5.1f}   {:.5f} (+- {:.5f})   {:+.5f}   {:+.5f}       {:.4f}\n", a.theta_deg, a.truth, a.truth_error,
                   a.model - a.truth, a.albedo_scaled - a.truth, a.truth_furnace);
      }
      fmt::print("lobe RMSE of (f - f_true) cos over a 16 x 32 grid (the truth's own noise beside it)\n");
      fmt::print("  theta   truth rms   noise rms   {:<10}  albedo-scaled\n", r->model);
      for (const auto& l : r->lobe) {
        fmt::print("  {:5.1f}   {:.5f}     {:.5f}     {:.5f}     {:.5f}\n", l.theta_deg, l.truth_rms, l.truth_noise_rms,
                   l.model_rmse, l.albedo_scaled_rmse);
      }
      fmt::print("max |albedo - truth|: {} {:.5f}, albedo-scaled {:.5f} ({:.1f} s)\n", r->model, r->max_albedo_difference,
                 r->max_albedo_scaled_difference, seconds);
    };
  });
}

}  // namespace

const CommandRegistration registration_layering_error(35, add_layering_error_command);

}  // namespace shadelab::cli
