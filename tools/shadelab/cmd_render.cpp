// shadelab render [SCENE] [--out FILE.exr] [--png FILE.png] ...: the reference path tracer.
// Without SCENE it renders the built-in default scene. Ctrl-C (or SIGTERM) stops after the current pass and
// writes the image accumulated so far (exit code 130, 143 for SIGTERM); the handler stays installed through
// the write, so a signal then still ends in complete files. A render with NaN or infinite samples says so on
// stderr and in --json ("nonfinite_samples") and exits with 1. With --shard I/N [--split samples|tiles] it
// renders one part for `shadelab merge` (cmd_merge.cpp, docs/scale-out.md) and skips a part already done.
#include <fmt/core.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <variant>

#include "cli_common.h"
#include "progress.h"
#include "shadelab/brdf/params.h"
#include "shadelab/color/ocio.h"
#include "shadelab/core/text.h"
#include "shadelab/envmap/specular/split_sum_taps.h"
#include "shadelab/render/film.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/render/shard_file.h"
#include "shadelab/render/threads.h"
#include "shadelab/scene/scene_json.h"

namespace shadelab::cli {

namespace {

namespace fs = std::filesystem;

// The repo's OpenColorIO config (share/ocio/shadelab.ocio): installed beside the binary
// (<prefix>/share/shadelab/ocio), else the source tree this binary was built from.
std::string repo_ocio_config() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path() / ".." / "share" / "shadelab" / "ocio" / "shadelab.ocio";
    if (fs::is_regular_file(installed, ec)) return installed.lexically_normal().string();
  }
  return SHADELAB_REPO_OCIO_CONFIG;
}

// Converts every colour of the scene between OCIO colour spaces of `config` (--working-space acescg: Linear Rec.709
// -> ACEScg): the environment (uniform, lat-long, sky), the colour textures (not the data ones), the materials'
// colour parameters (not `ior` and `k`: per-channel optical constants, not tristimulus values) and emission, the
// lights. Materials are built again from their converted parameters.
class SpaceConversion {
 public:
  SpaceConversion(std::string config, std::string from, std::string to)
      : m_config(std::move(config)), m_from(std::move(from)), m_to(std::move(to)) {}
  void image(Image& img) const {
    unwrap(ocio::convert(m_config, m_from, m_to, img.data.data(), img.pixel_count()));
  }
  Rgb rgb(const Rgb& c) const {
    float p[3] = {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)};
    unwrap(ocio::convert(m_config, m_from, m_to, p, 1));
    return {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])};
  }
  void scene(Scene& s) const {
    Environment& e = s.environment;
    e.uniform = rgb(e.uniform);
    if (!e.latlong.empty()) image(e.latlong);
    e.sky.sun_irradiance = rgb(e.sky.sun_irradiance);
    e.sky.zenith = rgb(e.sky.zenith);
    e.sky.horizon = rgb(e.sky.horizon);
    e.sky.ground = rgb(e.sky.ground);
    for (Texture& t : s.textures) {
      if (!t.data) image(t.image);
    }
    for (Material& m : s.materials) {
      m.emission = rgb(m.emission);
      if (m.model.empty()) continue;
      const ModelInfo* info = find_brdf_model(m.model);
      if (info == nullptr) continue;
      for (auto& [name, value] : m.params) {
        if (name == "ior" || name == "k") continue;
        for (const ParamSpec& spec : info->params) {
          if (spec.name != name || spec.kind != ParamKind::color) continue;
          double v[3] = {0, 0, 0};
          if (std::sscanf(value.c_str(), "%lf,%lf,%lf", &v[0], &v[1], &v[2]) == 3) {
            const Rgb c = rgb(Rgb{v[0], v[1], v[2]});
            value = fmt::format("{:.9g},{:.9g},{:.9g}", c.r, c.g, c.b);
          }  // a single number is a grey, which both spaces share
        }
      }
      m.brdf = unwrap(make_brdf(m.model, m.params));
    }
    for (SceneLight& l : s.lights) {
      std::visit([&](auto& light) { convert_light(light); }, l);
    }
  }

 private:
  void convert_light(DirectionalLight& l) const { l.irradiance = rgb(l.irradiance); }
  void convert_light(PointLight& l) const { l.intensity = rgb(l.intensity); }
  void convert_light(SpotLight& l) const { l.intensity = rgb(l.intensity); }
  void convert_light(SphereLight& l) const { l.radiance = rgb(l.radiance); }
  void convert_light(HemisphereLight& l) const {
    l.sky = rgb(l.sky);
    l.ground = rgb(l.ground);
  }
  std::string m_config, m_from, m_to;
};

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};
extern "C" void on_interrupt(int sig) {
  g_signal.store(sig);
  g_interrupted.store(true);
}

// Installs on_interrupt for SIGINT and SIGTERM for its lifetime.
class InterruptHandler {
 public:
  InterruptHandler() : m_int(std::signal(SIGINT, on_interrupt)), m_term(std::signal(SIGTERM, on_interrupt)) {}
  ~InterruptHandler() {
    std::signal(SIGINT, m_int);
    std::signal(SIGTERM, m_term);
  }
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

 private:
  void (*m_int)(int);
  void (*m_term)(int);
};

struct RenderCliOptions {
  std::string scene;
  std::string out = "render.exr";
  std::string png;
  int spp = -1;
  int threads = -1;
  int max_depth = -1;
  std::string seed;  // parsed by parse_seed: CLI11 would wrap "-5" and saturate 2^64
  // Which of the four were given (a value given is checked against its range; there is no sentinel value).
  bool spp_given = false, threads_given = false, max_depth_given = false, seed_given = false;
  double exposure = 0.0;
  ViewCliOptions view;  // --view, --look, --ocio-config, --filmic
  bool aov = false;
  bool no_png = false;
  std::string mode = "reference";
  std::string sampling = "mis";
  std::string sampler = "sobol";
  std::string ambient = "sh9";
  bool no_shadows = false;
  bool no_specular_ambient = false;
  bool drop_pi = false;
  bool sh_lights = false;
  int env_size = 64;       // game mode: face size the environment is baked at (GameOptions::environment_size)
  int specular_size = 64;  // game mode: face size of the prefiltered cube's level 0
  bool env_size_given = false, specular_size_given = false;
  std::string ggx_specular = "split-sum";  // game mode: GameOptions::ggx_specular
  std::string split_sum_lookup = "lobes";  // game mode: GameOptions::split_sum_lookup
  bool ggx_specular_given = false, split_sum_lookup_given = false;
  int split_sum_taps = 64;  // game mode, --split-sum-lookup filtered: GameOptions::split_sum_taps
  bool split_sum_taps_given = false;
  bool json = false;
  bool progress = false;
  std::string shard;  // "I/N": render one part for `shadelab merge` (docs/scale-out.md)
  std::string working_space = "linear-rec709";  // or acescg (docs/color.md)
  std::string split = "samples";
  bool split_given = false;
};

// "I/N" with 0 <= I < N <= max_shards; anything else names --shard.
constexpr int max_shards = 100000;
ShardSpec parse_shard(const std::string& text, const std::string& split) {
  ShardSpec spec;
  const auto slash = text.find('/');
  auto number = [&](const std::string& part) -> long long {
    if (part.empty() || part.size() > 9 || part.find_first_not_of("0123456789") != std::string::npos) {
      throw UsageError("--shard: '" + text + "' is not I/N (shard I of N, 0 <= I < N)");
    }
    return std::stoll(part);
  };
  if (slash == std::string::npos) throw UsageError("--shard: '" + text + "' is not I/N (shard I of N, 0 <= I < N)");
  const long long i = number(text.substr(0, slash));
  const long long n = number(text.substr(slash + 1));
  if (n < 1 || n > max_shards) throw UsageError(fmt::format("--shard: N = {} must be in [1, {}]", n, max_shards));
  if (i >= n) throw UsageError(fmt::format("--shard: I = {} must be below N = {} (shards are 0 .. N-1)", i, n));
  spec.index = static_cast<int>(i);
  spec.count = static_cast<int>(n);
  if (split == "samples") spec.split = ShardSplit::samples;
  else if (split == "tiles") spec.split = ShardSplit::tiles;
  else throw UsageError("--split: '" + split + "' is not one of samples | tiles");
  return spec;
}

// render --shard: one part, written atomically, or skipped when --out already holds this very part (resume).
// An interrupted shard writes nothing (a part is all of its samples or absent).
void run_shard(const RenderCliOptions& o, const Scene& scene, RenderOptions ro) {
  if (o.mode != "reference") throw UsageError("--shard: only the path tracer (--mode reference) renders in parts");
  if (o.aov) throw UsageError("--shard: AOVs are not split; render them in one piece (without --shard)");
  if (!o.png.empty()) throw UsageError("--shard: a part has no PNG; give --png to shadelab merge");
  const std::filesystem::path out(o.out);
  check_outputs(scene_inputs(scene), {{"--out", out}});
  const int spp = ro.spp > 0 ? ro.spp : scene.settings.spp;
  const int max_depth = ro.max_depth > 0 ? ro.max_depth : scene.settings.max_depth;
  ShardInfo info = make_shard_info(scene, ro, spp, max_depth);
  const std::string label = fmt::format("shard {}/{}", info.index, info.count);
  std::error_code ec;
  if (std::filesystem::exists(out, ec)) {
    auto old = read_shard_info(out);
    if (old && same_shard(*old, info) && read_shard_sums(out, *old)) {
      if (o.json) {
        print_json({{"scene", scene.source}, {"shard", info.index}, {"count", info.count}, {"split", info.split},
                    {"outputs", nlohmann::json::array({out.string()})}, {"skipped", true}, {"nonfinite_samples", old->nonfinite_samples}});
      } else {
        fmt::print("{}: {} already in {}, skipped\n", scene.source, label, out.string());
      }
      std::fflush(stdout);
      if (old->nonfinite_samples > 0) {
        std::cerr << "shadelab: " << out.string() << ": " << label << " holds " << old->nonfinite_samples
                  << " samples that were NaN or infinite (NaN pixels in the part); the render is wrong\n";
        std::exit(1);
      }
      return;
    }
    std::string why;
    if (!old) why = old.error().message;
    else if (const std::string d = identity_difference(*old, info); !d.empty()) why = "from another render: " + d;
    else if (old->index != info.index) why = "shard " + std::to_string(old->index) + "/" + std::to_string(old->count);
    else why = "an unreadable or altered part";
    warn("'" + out.string() + "' exists but is not " + label + " of this render (" + why + "): rendering it again");
  }
  ProgressBar bar(label, o.progress);
  ro.progress = [&](double f, int) { bar.update(f); };
  g_interrupted.store(false);
  g_signal.store(0);
  ro.cancel = &g_interrupted;
  auto handler = std::make_unique<InterruptHandler>();  // (std::optional trips GCC 12 -Wmaybe-uninitialized here)
  auto result = render_scene(scene, ro);
  bar.finish();
  if (!result) throw UsageError(scene.source + ": " + result.error().message);
  const RenderStats& st = result->stats;
  if (st.cancelled || g_interrupted.load()) {
    std::cerr << "shadelab: " << label << " interrupted: nothing written (run it again to render the part)\n";
    std::exit(128 + (g_signal.load() != 0 ? g_signal.load() : SIGINT));
  }
  info.nonfinite_samples = st.nonfinite_samples;
  unwrap(write_shard(out, info, *result));
  handler.reset();
  if (o.json) {
    print_json({{"scene", scene.source}, {"shard", info.index}, {"count", info.count}, {"split", info.split},
                {"outputs", nlohmann::json::array({out.string()})}, {"skipped", false}, {"sample_begin", info.sample_begin},
                {"sample_end", info.sample_end}, {"nonfinite_samples", st.nonfinite_samples}, {"seconds", st.seconds},
                {"render_seconds", st.render_seconds}, {"rays", st.rays}});
  } else {
    fmt::print("{}: {} ({} split, samples [{}, {})) in {:.2f} s\nwrote {}\n", scene.source, label, info.split,
               info.sample_begin, info.sample_end, st.seconds, out.string());
  }
  std::fflush(stdout);
  if (st.nonfinite_samples > 0) {
    std::cerr << "shadelab: " << scene.source << ": " << st.nonfinite_samples
              << " samples were NaN or infinite (NaN pixels in the part); the render is wrong\n";
    std::exit(1);
  }
}

void run_render(const RenderCliOptions& o) {
  // The scene format's ranges (docs/scene-format.md), so an option never accepts what a scene refuses.
  if (o.spp_given && o.spp < 1) throw UsageError(fmt::format("--spp: {} must be >= 1", o.spp));
  check_range("--spp", o.spp_given, o.spp, 1, 1'000'000);
  if (o.max_depth_given && o.max_depth < 1) throw UsageError(fmt::format("--max-depth: {} must be >= 1", o.max_depth));
  check_range("--max-depth", o.max_depth_given, o.max_depth, 1, 1000);
  if (o.threads_given && o.threads < 0) throw UsageError(fmt::format("--threads: {} must be >= 0", o.threads));
  check_range("--threads", o.threads_given, o.threads, 0, max_render_threads);
  if (!std::isfinite(o.exposure)) throw UsageError("--exposure: must be finite");
  if (o.working_space != "linear-rec709" && o.working_space != "acescg") {
    throw UsageError("--working-space: '" + printable(o.working_space) + "' is not one of linear-rec709 | acescg");
  }
  const bool acescg = o.working_space == "acescg";
  if (acescg && !o.shard.empty()) throw UsageError("--working-space acescg: not with --shard (merge would not convert back)");
  const std::string space_config = acescg ? repo_ocio_config() : std::string();
  const DisplayView view = parse_view_options(o.view, ViewTransform::standard);
  Scene scene = o.scene.empty() ? built_in_scene() : unwrap(load_scene(o.scene));
  for (const std::string& w : scene.warnings) std::cerr << "shadelab: warning: " << w << '\n';  // one line each
  if (o.seed_given) scene.settings.seed = parse_seed("--seed", o.seed);
  if (acescg) {
    try {
      SpaceConversion(space_config, "Linear Rec.709", "ACEScg").scene(scene);
    } catch (const UsageError& e) {
      throw UsageError(std::string("--working-space acescg: ") + e.what());
    }
  }
  RenderOptions ro;
  ro.spp = o.spp_given ? o.spp : -1;
  ro.max_depth = o.max_depth_given ? o.max_depth : -1;
  ro.threads = o.threads_given ? o.threads : -1;
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
  go.directional_in_sh = o.sh_lights;
  {
    bool marked = o.sh_lights;
    for (const auto& l : scene.lights) {
      if (const auto* d = std::get_if<DirectionalLight>(&l)) marked = marked || d->game_sh;
    }
    if (o.mode == "game" && marked && go.diffuse != GameAmbient::sh9) {
      throw UsageError("--ambient " + o.ambient + ": directional lights added to the SH9 ambient (--sh-lights or \"game\": "
                       "\"sh\" in the scene) need --ambient sh9");
    }
    if (o.sh_lights && o.mode != "game") throw UsageError("--sh-lights applies to --mode game");
  }
  if ((o.env_size_given || o.specular_size_given) && o.mode != "game") {
    throw UsageError(std::string(o.env_size_given ? "--env-size" : "--specular-size") + " applies to --mode game");
  }
  if (o.env_size < 1 || o.env_size > 1024) throw UsageError(fmt::format("--env-size: {} is out of range [1, 1024]", o.env_size));
  if (o.specular_size < 1 || o.specular_size > 1024 || (o.specular_size & (o.specular_size - 1)) != 0) {
    throw UsageError(fmt::format("--specular-size: {} is not a power of two in [1, 1024]", o.specular_size));
  }
  if ((o.ggx_specular_given || o.split_sum_lookup_given) && o.mode != "game") {
    throw UsageError(std::string(o.ggx_specular_given ? "--ggx-specular" : "--split-sum-lookup") + " applies to --mode game");
  }
  if (o.ggx_specular == "phong") go.ggx_specular = GameGgxSpecular::phong;
  else if (o.ggx_specular == "split-sum") go.ggx_specular = GameGgxSpecular::split_sum;
  else throw UsageError("--ggx-specular: '" + o.ggx_specular + "' is not one of phong | split-sum");
  if (o.split_sum_lookup == "lobes") go.split_sum_lookup = GameSplitSumLookup::lobes;
  else if (o.split_sum_lookup == "dominant") go.split_sum_lookup = GameSplitSumLookup::dominant;
  else if (o.split_sum_lookup == "mirror") go.split_sum_lookup = GameSplitSumLookup::mirror;
  else if (o.split_sum_lookup == "filtered") go.split_sum_lookup = GameSplitSumLookup::filtered;
  else throw UsageError("--split-sum-lookup: '" + o.split_sum_lookup + "' is not one of lobes | dominant | mirror | filtered");
  if (o.split_sum_lookup_given && go.ggx_specular != GameGgxSpecular::split_sum) {
    throw UsageError("--split-sum-lookup applies to --ggx-specular split-sum");
  }
  if (o.split_sum_taps_given && go.split_sum_lookup != GameSplitSumLookup::filtered) {
    throw UsageError("--split-sum-taps applies to --split-sum-lookup filtered");
  }
  if (o.split_sum_taps < 1 || o.split_sum_taps > split_sum_taps_max) {
    throw UsageError(fmt::format("--split-sum-taps: {} is out of range [1, {}]", o.split_sum_taps, split_sum_taps_max));
  }
  go.split_sum_taps = o.split_sum_taps;
  go.environment_size = o.env_size;
  go.specular_size = o.specular_size;
  go.threads = ro.threads;
  if (o.spp_given) go.spp = o.spp;
  if (!o.shard.empty() || o.split_given) {
    if (o.shard.empty()) throw UsageError("--split applies to --shard I/N");
    ro.shard = parse_shard(o.shard, o.split);
    const std::filesystem::path part(o.out);
    std::string part_ext = part.extension().string();
    for (auto& c : part_ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (part_ext != ".exr") throw UsageError("--out: a part is written as .exr, got '" + o.out + "'");
    run_shard(o, scene, ro);
    return;
  }
  const std::filesystem::path exr(o.out);
  std::string ext = exr.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".exr") throw UsageError("--out: the linear image is written as .exr, got '" + o.out + "'");
  FilmOutputs film;
  film.exr = exr;
  film.png = o.no_png ? std::filesystem::path() : (o.png.empty() ? exr.parent_path() / (exr.stem().string() + ".png") : std::filesystem::path(o.png));
  if (!o.png.empty()) require_extension("--png", o.png, {".png"}, "the tone-mapped image");
  {
    std::vector<NamedPath> outputs{{"--out", film.exr}, {o.png.empty() ? "the PNG beside --out" : "--png", film.png}};
    if (o.aov) {
      for (const char* aov : {"albedo", "normal", "depth"}) {
        outputs.push_back({std::string("the ") + aov + " AOV", exr.parent_path() / (exr.stem().string() + "." + aov + ".exr")});
      }
    }
    check_outputs(scene_inputs(scene), outputs);
  }
  film.exposure_stops = o.exposure;
  film.view = view;
  film.aovs = o.aov;
  work_begins();

  ProgressBar bar("render", o.progress);
  ro.progress = [&](double f, int) { bar.update(f); };
  g_interrupted.store(false);
  g_signal.store(0);
  ro.cancel = &g_interrupted;
  auto handler = std::make_unique<InterruptHandler>();  // (std::optional trips GCC 12 -Wmaybe-uninitialized here)
  auto result = o.mode == "game" ? render_game(scene, go) : render_scene(scene, ro);
  bar.finish();
  if (!result) throw UsageError(scene.source + ": " + result.error().message);
  if (acescg) {  // the files stay in shadelab's working space, linear Rec.709
    const SpaceConversion back(space_config, "ACEScg", "Linear Rec.709");
    back.image(result->beauty);
    if (!result->albedo.empty()) back.image(result->albedo);
  }
  const auto written = unwrap(write_film(*result, film));
  handler.reset();  // after the files are complete
  const RenderStats& st = result->stats;
  const bool interrupted = st.cancelled || g_interrupted.load();
  const double pixels = static_cast<double>(scene.camera.width) * scene.camera.height;
  if (o.json) {
    nlohmann::json files = nlohmann::json::array();
    for (const auto& p : written) files.push_back(p.string());
    nlohmann::json summary{{"scene", scene.source}, {"mode", o.mode}, {"outputs", files}, {"width", scene.camera.width},
                           {"height", scene.camera.height}, {"spp", st.spp_done}, {"interrupted", interrupted},
                           {"nonfinite_samples", st.nonfinite_samples},
                           {"seconds", st.seconds}, {"render_seconds", st.render_seconds}, {"rays", st.rays},
                           {"samples_per_second", pixels * st.spp_done / std::max(1e-9, st.seconds)},
                           {"rays_per_second", static_cast<double>(st.rays) / std::max(1e-9, st.seconds)}};
    if (o.mode == "game") {
      // Per material, the specular ambient it was shaded with (and the split sum's lookup).
      const auto ambients = unwrap(game_specular_ambients(scene, go));
      nlohmann::json materials = nlohmann::json::array();
      for (std::size_t i = 0; i < ambients.size(); ++i) {
        nlohmann::json m{{"material", scene.materials[i].name}, {"model", scene.materials[i].model},
                         {"specular_ambient", game_specular_ambient_name(ambients[i])}};
        if (ambients[i] == GameSpecularAmbient::split_sum) m["split_sum_lookup"] = o.split_sum_lookup;
        materials.push_back(std::move(m));
      }
      summary["materials"] = std::move(materials);
    }
    print_json(summary);
  } else {
    fmt::print("{}: {} x {}, {} spp in {:.2f} s ({:.3g} samples/s, {:.3g} rays/s){}\n", scene.source,
               scene.camera.width, scene.camera.height, st.spp_done, st.seconds,
               pixels * st.spp_done / std::max(1e-9, st.seconds), static_cast<double>(st.rays) / std::max(1e-9, st.seconds),
               interrupted ? " - interrupted" : "");
    for (const auto& p : written) fmt::print("wrote {}\n", p.string());
  }
  std::fflush(stdout);
  if (interrupted) std::exit(128 + (g_signal.load() != 0 ? g_signal.load() : SIGINT));
  if (st.nonfinite_samples > 0) {
    std::cerr << "shadelab: " << scene.source << ": " << st.nonfinite_samples
              << " samples were NaN or infinite (kept in the image); the render is wrong\n";
    std::exit(1);
  }
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
  sub->add_option("--threads", o->threads, "threads, 0 = all cores, at most 4096; more than the cores uses all cores (default: the scene's)");
  sub->add_option("--max-depth", o->max_depth, "path vertices after the camera (default: the scene's)");
  sub->add_option("--seed", o->seed, "random seed, 0 to 2^64 - 1 (default: the scene's)");
  sub->add_option("--exposure", o->exposure, "PNG exposure in stops")->capture_default_str();
  add_view_options(sub, o->view, "standard", true);
  sub->add_option("--working-space", o->working_space,
                  "linear-rec709, or acescg: the scene's colours (HDRIs, colour textures, material colours, lights) "
                  "converted to ACEScg by OpenColorIO (share/ocio/shadelab.ocio), rendered there, and the outputs "
                  "converted back to linear Rec.709 (docs/color.md)")->capture_default_str();
  sub->add_flag("--aov", o->aov, "also write albedo, normal and depth EXRs");
  sub->add_option("--mode", o->mode, "reference (the path tracer) or game (the game shading equation)")->capture_default_str();
  sub->add_option("--sampling", o->sampling, "reference mode: mis, brdf or light sampling")->capture_default_str();
  sub->add_option("--sampler", o->sampler, "reference mode: sobol (Owen-scrambled, stratified) or independent (plain Monte Carlo)")->capture_default_str();
  sub->add_option("--ambient", o->ambient, "game mode: diffuse ambient from sh9, irradiance (cube map) or none")->capture_default_str();
  sub->add_flag("--no-shadows", o->no_shadows, "game mode: no shadow rays for punctual lights");
  sub->add_flag("--no-specular-ambient", o->no_specular_ambient, "game mode: no prefiltered specular");
  sub->add_flag("--drop-pi", o->drop_pi, "game mode, debug: forget the pi of the game light unit");
  sub->add_flag("--sh-lights", o->sh_lights,
                "game mode: add every directional light to the SH9 ambient (D3DX-style) instead of shading it per pixel");
  sub->add_option("--env-size", o->env_size, "game mode: face size the environment is baked at (SH9 and the cube)")->capture_default_str();
  sub->add_option("--specular-size", o->specular_size, "game mode: face size of the prefiltered specular cube's level 0 (a power of two)")
      ->capture_default_str();
  sub->add_option("--ggx-specular", o->ggx_specular,
                  "game mode: the specular ambient of ggx and filament materials: split-sum (GGX chain x DFG "
                  "table, the default) or phong (the Phong chain, as the explorer still shades them)")
      ->capture_default_str();
  sub->add_option("--split-sum-lookup", o->split_sum_lookup,
                  "game mode, --ggx-specular split-sum: lobes (each part at its lobe's first moments), dominant "
                  "(normalize(mix(R, n, alpha^2))), mirror (R) or filtered (each part the mean of "
                  "--split-sum-taps reads over its own lobe)")
      ->capture_default_str();
  sub->add_option("--split-sum-taps", o->split_sum_taps,
                  "game mode, --split-sum-lookup filtered: chain reads per pixel, in [1, 1024]")
      ->capture_default_str();
  sub->add_flag("--json", o->json, "machine-readable summary");
  sub->add_flag("--progress", o->progress, "show the progress bar even when stderr is not a terminal");
  sub->add_option("--shard", o->shard, "I/N: render part I of N (0 <= I < N) into --out, for shadelab merge (docs/scale-out.md)");
  sub->add_option("--split", o->split, "with --shard: samples (a range of every pixel's samples) or tiles (every N-th 16 x 16 tile)")
      ->capture_default_str();
  sub->callback([o, sub, &command] {
    o->spp_given = sub->count("--spp") > 0;
    o->threads_given = sub->count("--threads") > 0;
    o->max_depth_given = sub->count("--max-depth") > 0;
    o->seed_given = sub->count("--seed") > 0;
    o->split_given = sub->count("--split") > 0;
    o->env_size_given = sub->count("--env-size") > 0;
    o->specular_size_given = sub->count("--specular-size") > 0;
    o->ggx_specular_given = sub->count("--ggx-specular") > 0;
    o->split_sum_lookup_given = sub->count("--split-sum-lookup") > 0;
    o->split_sum_taps_given = sub->count("--split-sum-taps") > 0;
    command.run = [o] { run_render(*o); };
  });
}

}  // namespace

const CommandRegistration registration_render(10, add_render_command);

}  // namespace shadelab::cli
