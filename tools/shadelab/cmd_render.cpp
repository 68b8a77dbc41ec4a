// shadelab render [SCENE] [--out FILE.exr] [--png FILE.png] ...: the reference path tracer.
// Without SCENE it renders the built-in default scene. Ctrl-C stops after the current pass and writes the
// image accumulated so far (exit code 130).
#include <fmt/core.h>

#include <atomic>
#include <csignal>
#include <cmath>
#include <filesystem>

#include "cli_common.h"
#include "progress.h"
#include "shadelab/render/film.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/scene/default_scene.h"
#include "shadelab/scene/scene_json.h"

namespace shadelab::cli {

namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void on_interrupt(int) { g_interrupted.store(true); }

struct RenderCliOptions {
  std::string scene;
  std::string out = "render.exr";
  std::string png;
  int spp = -1;
  int threads = -1;
  int max_depth = -1;
  long long seed = -1;
  double exposure = 0.0;
  bool filmic = false;
  bool aov = false;
  bool no_png = false;
  std::string mode = "reference";
  std::string sampling = "mis";
  std::string sampler = "sobol";
  std::string ambient = "sh9";
  bool no_shadows = false;
  bool no_specular_ambient = false;
  bool drop_pi = false;
  bool json = false;
  bool progress = false;
};

void run_render(const RenderCliOptions& o) {
  Scene scene = o.scene.empty() ? default_scene() : unwrap(load_scene(o.scene));
  if (o.seed >= 0) scene.settings.seed = static_cast<std::uint64_t>(o.seed);
  RenderOptions ro;
  if (o.spp != -1 && o.spp < 1) throw UsageError(fmt::format("--spp: {} must be >= 1", o.spp));
  if (o.max_depth != -1 && o.max_depth < 1) throw UsageError(fmt::format("--max-depth: {} must be >= 1", o.max_depth));
  if (o.threads != -1 && o.threads < 0) throw UsageError(fmt::format("--threads: {} must be >= 0", o.threads));
  if (!std::isfinite(o.exposure)) throw UsageError("--exposure: must be finite");
  ro.spp = o.spp;
  ro.max_depth = o.max_depth;
  ro.threads = o.threads;
  ro.aovs = o.aov;
  if (o.sampling == "mis") ro.mode = SamplingMode::mis;
  else if (o.sampling == "brdf") ro.mode = SamplingMode::brdf;
  else if (o.sampling == "light") ro.mode = SamplingMode::light;
  else throw UsageError("--sampling: '" + o.sampling + "' is not one of mis | brdf | light");
  if (o.sampler == "sobol") ro.sampler = SamplerKind::owen_sobol;
  else if (o.sampler == "independent") ro.sampler = SamplerKind::independent;
  else throw UsageError("--sampler: '" + o.sampler + "' is not one of sobol | independent");
  if (o.mode != "reference" && o.mode != "game") throw UsageError("--mode: '" + o.mode + "' is not one of reference | game");
  GameOptions go;
  if (o.ambient == "sh9") go.diffuse = GameAmbient::sh9;
  else if (o.ambient == "irradiance") go.diffuse = GameAmbient::irradiance_map;
  else if (o.ambient == "none") go.diffuse = GameAmbient::none;
  else throw UsageError("--ambient: '" + o.ambient + "' is not one of sh9 | irradiance | none");
  go.shadows = !o.no_shadows;
  go.specular_ambient = !o.no_specular_ambient;
  go.drop_pi = o.drop_pi;
  go.threads = o.threads;
  if (o.spp != -1) go.spp = o.spp;
  const std::filesystem::path exr(o.out);
  std::string ext = exr.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".exr") throw UsageError("--out: the linear image is written as .exr, got '" + o.out + "'");
  FilmOutputs film;
  film.exr = exr;
  film.png = o.no_png ? std::filesystem::path() : (o.png.empty() ? exr.parent_path() / (exr.stem().string() + ".png") : std::filesystem::path(o.png));
  film.exposure_stops = o.exposure;
  film.curve = o.filmic ? ToneCurve::filmic : ToneCurve::clamp;
  film.aovs = o.aov;

  ProgressBar bar("render", o.progress);
  ro.progress = [&](double f, int) { bar.update(f); };
  g_interrupted.store(false);
  ro.cancel = &g_interrupted;
  const auto previous = std::signal(SIGINT, on_interrupt);
  auto result = o.mode == "game" ? render_game(scene, go) : render_scene(scene, ro);
  std::signal(SIGINT, previous);
  bar.finish();
  if (!result) throw UsageError(scene.source + ": " + result.error().message);
  const auto written = unwrap(write_film(*result, film));
  const RenderStats& st = result->stats;
  const double pixels = static_cast<double>(scene.camera.width) * scene.camera.height;
  if (o.json) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& p : written) files.push_back(p.string());
    print_json({{"scene", scene.source}, {"mode", o.mode}, {"outputs", files}, {"width", scene.camera.width},
                {"height", scene.camera.height}, {"spp", st.spp_done}, {"interrupted", st.cancelled},
                {"seconds", st.seconds}, {"render_seconds", st.render_seconds}, {"rays", st.rays},
                {"samples_per_second", pixels * st.spp_done / std::max(1e-9, st.seconds)},
                {"rays_per_second", static_cast<double>(st.rays) / std::max(1e-9, st.seconds)}});
  } else {
    fmt::print("{}: {} x {}, {} spp in {:.2f} s ({:.3g} samples/s, {:.3g} rays/s){}\n", scene.source,
               scene.camera.width, scene.camera.height, st.spp_done, st.seconds,
               pixels * st.spp_done / std::max(1e-9, st.seconds), static_cast<double>(st.rays) / std::max(1e-9, st.seconds),
               st.cancelled ? " - interrupted" : "");
    for (const auto& p : written) fmt::print("wrote {}\n", p.string());
  }
  if (st.cancelled) std::exit(130);
}

}  // namespace

namespace {
void add_render_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<RenderCliOptions>();
  auto* sub = app.add_subcommand("render", "path-trace a scene (the built-in default scene without SCENE)");
  sub->add_option("SCENE", o->scene, "scene file (JSON, docs/scene-format.md)");
  sub->add_option("--out", o->out, "linear EXR output")->capture_default_str();
  sub->add_option("--png", o->png, "tone-mapped PNG output (default: the EXR's name with .png)");
  sub->add_flag("--no-png", o->no_png, "write no PNG");
  sub->add_option("--spp", o->spp, "samples per pixel (default: the scene's; game mode: antialiasing, default 4)");
  sub->add_option("--threads", o->threads, "threads, 0 = all cores (default: the scene's)");
  sub->add_option("--max-depth", o->max_depth, "path vertices after the camera (default: the scene's)");
  sub->add_option("--seed", o->seed, "random seed (default: the scene's)");
  sub->add_option("--exposure", o->exposure, "PNG exposure in stops")->capture_default_str();
  sub->add_flag("--filmic", o->filmic, "PNG through the ACES filmic curve instead of clamping");
  sub->add_flag("--aov", o->aov, "also write albedo, normal and depth EXRs");
  sub->add_option("--mode", o->mode, "reference (the path tracer) or game (the game shading equation)")->capture_default_str();
  sub->add_option("--sampling", o->sampling, "reference mode: mis, brdf or light sampling")->capture_default_str();
  sub->add_option("--sampler", o->sampler, "reference mode: sobol (Owen-scrambled, stratified) or independent (plain Monte Carlo)")->capture_default_str();
  sub->add_option("--ambient", o->ambient, "game mode: diffuse ambient from sh9, irradiance (cube map) or none")->capture_default_str();
  sub->add_flag("--no-shadows", o->no_shadows, "game mode: no shadow rays for punctual lights");
  sub->add_flag("--no-specular-ambient", o->no_specular_ambient, "game mode: no prefiltered specular");
  sub->add_flag("--drop-pi", o->drop_pi, "game mode, debug: forget the pi of the game light unit");
  sub->add_flag("--json", o->json, "machine-readable summary");
  sub->add_flag("--progress", o->progress, "show the progress bar even when stderr is not a terminal");
  sub->callback([o, &command] { command.run = [o] { run_render(*o); }; });
}

}  // namespace

const CommandRegistration registration_render(10, add_render_command);

}  // namespace shadelab::cli
