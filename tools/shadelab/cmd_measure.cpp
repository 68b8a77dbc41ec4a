// shadelab measure MODEL [--param K=V ...] [--format merl] --out FILE.binary [--json]: the virtual
// gonioreflectometer (brdf/merl.h, measure_merl): any model evaluated at the centre of each bin of the MERL 100
// layout and written as a MERL .binary file (bins whose centre is below the horizon hold -1, not measured), so
// that fitting and the measured model can be tested on data of known parameters. Written atomically.
#include <fmt/core.h>

#include <chrono>

#include "cli_common.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/image/image_io.h"

namespace shadelab::cli {

namespace fs = std::filesystem;

namespace {

struct MeasureOptions {
  std::string model;
  std::vector<std::string> params;
  std::string format = "merl";
  std::string out;
  bool json = false;
};

void run_measure(const MeasureOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (o.format != "merl") throw UsageError("--format: '" + o.format + "' is not one of merl");
  const ParamAssignments params = parse_assignments(o.params);
  auto brdf = make_brdf(o.model, params);
  if (!brdf) throw UsageError(brdf.error().message);
  const fs::path out(o.out);
  require_extension("--out", out, {".binary"}, "the MERL file");
  check_outputs({}, {{"--out", out}});
  work_begins();
  const MerlTable t = measure_merl(**brdf);
  std::size_t measured = 0;
  for (std::size_t i = 0; i < MerlTable::count; ++i) measured += t.stored[i] >= 0.0 ? 1 : 0;
  unwrap(write_file_atomically(out, encode_merl(t)));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.json) {
    nlohmann::json p = nlohmann::json::object();
    for (const auto& [k, v] : params) p[k] = v;
    print_json({{"file", out.string()},
                {"model", o.model},
                {"params", p},
                {"format", "merl"},
                {"bins", MerlTable::count},
                {"measured_bins", measured},
                {"bytes", MerlTable::file_bytes},
                {"seconds", seconds}});
    return;
  }
  fmt::print("wrote {} (MERL 90 x 90 x 180: {} of {} bins measured at their centres, the rest below the horizon; {:.1f} s)\n",
             out.string(), measured, MerlTable::count, seconds);
}

void add_measure_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<MeasureOptions>();
  auto* sub = app.add_subcommand("measure", "a virtual gonioreflectometer: write any model as a measured file (MERL)");
  sub->add_option("model", o->model, "the model (brdf list)")->required();
  sub->add_option("--param", o->params, "model parameter NAME=VALUE (repeatable)");
  sub->add_option("--format", o->format, "the file format: merl (MERL 100 .binary)")->capture_default_str();
  sub->add_option("--out", o->out, "the output file (.binary)")->required();
  sub->add_flag("--json", o->json, "machine-readable output");
  sub->callback([o, &command] { command.run = [o] { run_measure(*o); }; });
}

}  // namespace

const CommandRegistration registration_measure(36, add_measure_command);

}  // namespace shadelab::cli
