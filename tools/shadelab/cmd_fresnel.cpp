// shadelab fresnel (--ior N[,K] | --material NAME) --theta DEG [--json]
#include <fmt/core.h>

#include <cmath>

#include "cli_common.h"
#include "shadelab/brdf/fresnel.h"
#include "shadelab/brdf/fresnel_materials.h"
#include "shadelab/core/constants.h"

namespace shadelab::cli {

namespace {
struct FresnelOptions {
  std::string ior;
  std::string material;
  double theta = 0.0;
  bool json = false;
  bool list = false;
};
}  // namespace

namespace {
void add_fresnel_command(CLI::App& app, Command& command) {
  auto opts = std::make_shared<FresnelOptions>();
  auto* sub = app.add_subcommand("fresnel", "Fresnel reflectance of a smooth interface (exact, unpolarized)");
  auto* ior = sub->add_option("--ior", opts->ior, "relative IOR N (dielectric) or N,K (conductor, n + ik)");
  auto* mat = sub->add_option("--material", opts->material, "a named material (see --list)");
  ior->excludes(mat);
  sub->add_option("--theta", opts->theta, "angle of incidence in degrees, 0 = normal incidence")->capture_default_str();
  sub->add_flag("--list", opts->list, "list the named materials and their sources");
  sub->add_flag("--json", opts->json, "machine-readable output: {\"F\": ...}");
  sub->callback([opts, &command] {
    command.run = [opts] {
      if (opts->list) {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& m : fresnel_materials()) {
          list.push_back({{"name", m.name}, {"conductor", m.conductor}, {"n", to_json(m.n)}, {"k", to_json(m.k)},
                          {"F0", to_json(fresnel_f0(m))}, {"wavelengths", m.wavelengths}, {"source", m.source}});
          if (!opts->json) {
            const Rgb f0 = fresnel_f0(m);
            fmt::print("{:<10} F0 = {:.4f} {:.4f} {:.4f}   {}\n", m.name, f0.r, f0.g, f0.b, m.source);
          }
        }
        if (opts->json) print_json({{"materials", list}});
        return;
      }
      if (!std::isfinite(opts->theta) || opts->theta < 0.0 || opts->theta > 90.0) {
        throw UsageError(fmt::format("--theta: {} is out of range [0, 90] degrees", opts->theta));
      }
      const double cos_i = std::cos(deg_to_rad(opts->theta));
      nlohmann::json out;
      if (!opts->material.empty()) {
        const FresnelMaterial* m = find_fresnel_material(opts->material);
        if (m == nullptr) throw UsageError("--material: unknown material '" + opts->material + "' (see fresnel --list)");
        const Rgb f = fresnel_reflectance(*m, cos_i);
        out = {{"F", to_json(f)}, {"material", m->name}, {"theta", opts->theta}};
        if (!opts->json) fmt::print("F = {:.6f} {:.6f} {:.6f}  ({} at {} degrees)\n", f.r, f.g, f.b, m->name, opts->theta);
      } else if (!opts->ior.empty()) {
        auto nums = parse_numbers(opts->ior);
        if (!nums) throw UsageError("--ior: " + nums.error().message);
        if (nums->empty() || nums->size() > 2) throw UsageError("--ior: expected N or N,K, got '" + opts->ior + "'");
        const double n = (*nums)[0];
        const double k = nums->size() == 2 ? (*nums)[1] : 0.0;
        if (!(n > 0.0)) throw UsageError(fmt::format("--ior: N = {} must be positive", n));
        if (k < 0.0) throw UsageError(fmt::format("--ior: K = {} must not be negative", k));
        const double f = nums->size() == 2 ? F_conductor(cos_i, n, k) : F_dielectric(cos_i, n);
        out = {{"F", f}, {"theta", opts->theta}};
        if (!opts->json) fmt::print("F = {:.8f}\n", f);
      } else {
        throw UsageError("fresnel: give --ior N[,K] or --material NAME");
      }
      if (opts->json) print_json(out);
    };
  });
}

}  // namespace

const CommandRegistration registration_fresnel(40, add_fresnel_command);

}  // namespace shadelab::cli
