// shadelab sheet MODEL... [--vary NAME=V1,V2,...]: a grid of lit spheres rendered by the reference path
// tracer, one row per model and one column per value of the varied parameter (an exponent, a roughness).
//
// Each cell is its own small scene built in code: a sphere of radius 1 at the origin, seen from +Z by a
// pinhole camera that frames it with a margin, lit by one light (--light directional or sphere; game light
// units: a directional light of intensity 1 has E_perp = pi W/m^2, so a white Lambert sphere facing it
// shows 1) and/or an environment (--hdri FILE, a lat-long EXR/HDR, or --ambient, a uniform radiance). Every
// cell has the same camera, light and seed, so the cells differ only by their material. The cells are
// rendered with render_scene, tone-mapped (film.h) and pasted into one PNG with thin grey gaps; --exr
// writes the linear sheet. The PNG carries no text: the layout (which model, parameters and value each
// cell shows, and its pixel rectangle) is printed with --json and written with --csv (docs/plots.md).
#include <fmt/core.h>

#include <chrono>
#include <iostream>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli_common.h"
#include "shadelab/render/threads.h"
#include "shadelab/analysis/plot_data.h"
#include "shadelab/core/constants.h"
#include "shadelab/image/image_io.h"
#include "shadelab/render/film.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/scene/scene.h"

namespace shadelab::cli {

namespace {

struct SheetOptions {
  std::vector<std::string> models;
  std::vector<std::string> params;
  std::string vary;
  std::string light;  // "": sphere, or none with --hdri
  std::string light_dir = "-1,1,1";
  double intensity = 1.0;
  std::string hdri;
  double hdri_rotation = 0.0;
  double ambient = 0.0;
  int cell = 128;
  int spp = 32;
  long long seed = 1;
  int threads = 0;
  double exposure = 0.0;
  ViewCliOptions view;  // --view, --look, --ocio-config, --filmic
  std::string out = "sheet.png";
  std::string exr;
  std::string csv;
  bool json = false;
};

inline constexpr int max_cell = 256;
inline constexpr int max_grid = 16;  // rows and columns
// The sphere light: radius 1 at distance 10, so sin(beta) = 0.1 and E = pi L sin^2(beta) (light/sphere_light.h);
// its radiance is intensity / sin^2(beta), which gives the same E_perp = pi x intensity as the directional light.
inline constexpr double sphere_light_distance = 10.0;
inline constexpr double sphere_light_radius = 1.0;
// The camera: distance 4.5 from the sphere's centre; the sphere fills 88% of the image height.
inline constexpr double camera_distance = 4.5;
inline constexpr double sphere_fill = 0.88;

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

void check_extension(const std::string& option, const std::string& path, const std::string& ext) {
  if (lower(std::filesystem::path(path).extension().string()) != ext) {
    throw UsageError(option + ": expected a " + ext + " file, got '" + path + "'");
  }
}

struct Vary {
  std::string name;
  std::vector<std::string> values;  // as typed, handed to the model's parameter parser
};

Vary parse_vary(const std::string& text) {
  if (text.empty()) return {};
  auto a = split_assignment(text);
  if (!a) throw UsageError("--vary: expected NAME=V1,V2,..., got '" + text + "'");
  Vary v;
  v.name = a->first;
  auto numbers = parse_numbers(a->second);
  if (!numbers || numbers->empty()) {
    throw UsageError("--vary: '" + a->second + "' is not a list of numbers V1,V2,...");
  }
  if (numbers->size() > static_cast<std::size_t>(max_grid)) {
    throw UsageError(fmt::format("--vary: {} values, at most {} columns", numbers->size(), max_grid));
  }
  for (double x : *numbers) v.values.push_back(fmt::format("{}", x));
  return v;
}

struct Cell {
  int row = 0;
  int column = 0;
  std::string model;
  ParamAssignments params;
  std::string label;
  std::shared_ptr<const Brdf> brdf;
  int x = 0;  // top-left pixel in the sheet
  int y = 0;
};

Scene cell_scene(const SheetOptions& o, const Vec3& to_light, const std::string& light, const Environment& env,
                 const Cell& cell) {
  Scene s;
  s.source = "sheet";
  s.camera.position = {0.0, 0.0, camera_distance};
  s.camera.look_at = {0.0, 0.0, 0.0};
  s.camera.up = {0.0, 1.0, 0.0};
  // The sphere subtends a half-angle asin(1/d); the image's half-height is that over sphere_fill (in tan).
  const double half = std::asin(1.0 / camera_distance);
  s.camera.vfov_deg = rad_to_deg(2.0 * std::atan(std::tan(half) / sphere_fill));
  s.camera.width = o.cell;
  s.camera.height = o.cell;
  Material m;
  m.name = cell.label;
  m.model = cell.model;
  m.params = cell.params;
  m.brdf = cell.brdf;
  s.materials.push_back(std::move(m));
  s.spheres.push_back({{0.0, 0.0, 0.0}, 1.0, 0});
  if (light == "directional") {
    s.lights.emplace_back(DirectionalLight{to_light, Rgb::gray(pi * o.intensity)});
  } else if (light == "sphere") {
    const double sin_beta = sphere_light_radius / sphere_light_distance;
    s.lights.emplace_back(SphereLight{to_light * sphere_light_distance, sphere_light_radius,
                                      Rgb::gray(o.intensity / (sin_beta * sin_beta))});
  }
  s.environment = env;
  s.settings.spp = o.spp;
  s.settings.max_depth = 2;  // a convex sphere alone: light, at most one bounce to the environment
  s.settings.seed = static_cast<std::uint64_t>(o.seed);
  s.settings.threads = o.threads;
  return s;
}

void run_sheet(const SheetOptions& o) {
  check_extension("--out", o.out, ".png");
  if (!o.exr.empty()) check_extension("--exr", o.exr, ".exr");
  if (o.cell < 16 || o.cell > max_cell) {
    throw UsageError(fmt::format("--cell: {} is out of range [16, {}]", o.cell, max_cell));
  }
  if (o.spp < 1 || o.spp > 65536) throw UsageError(fmt::format("--spp: {} is out of range [1, 65536]", o.spp));
  if (o.seed < 0) throw UsageError(fmt::format("--seed: {} must be >= 0", o.seed));
  if (o.threads < 0) throw UsageError(fmt::format("--threads: {} must be >= 0", o.threads));
  check_range("--threads", true, o.threads, 0, max_render_threads);
  check_outputs({{"--hdri", o.hdri}}, {{"--out", o.out}, {"--exr", o.exr}});
  if (!std::isfinite(o.exposure)) throw UsageError("--exposure: must be finite");
  const DisplayView view = parse_view_options(o.view, ViewTransform::standard);
  if (!std::isfinite(o.intensity) || o.intensity < 0.0) {
    throw UsageError(fmt::format("--intensity: {} must be finite and >= 0", o.intensity));
  }
  if (!std::isfinite(o.ambient) || o.ambient < 0.0) {
    throw UsageError(fmt::format("--ambient: {} must be finite and >= 0", o.ambient));
  }
  if (!std::isfinite(o.hdri_rotation)) throw UsageError("--hdri-rotation: must be finite");
  if (o.models.size() > static_cast<std::size_t>(max_grid)) {
    throw UsageError(fmt::format("{} models, at most {} rows", o.models.size(), max_grid));
  }
  const std::string light = o.light.empty() ? (o.hdri.empty() ? "sphere" : "none") : o.light;
  if (light != "sphere" && light != "directional" && light != "none") {
    throw UsageError("--light: '" + light + "' is not one of sphere | directional | none");
  }
  if (!o.hdri.empty() && o.ambient > 0.0) throw UsageError("--ambient: give --ambient or --hdri, not both");
  const Vec3 to_light = parse_direction("--light-dir", o.light_dir);
  const Vary vary = parse_vary(o.vary);

  // Every BRDF is built before anything is rendered, so a bad parameter costs no render time.
  const auto models = unwrap(assign_model_params(o.models, o.params));
  const int columns = vary.values.empty() ? 1 : static_cast<int>(vary.values.size());
  std::vector<Cell> cells;
  for (std::size_t r = 0; r < models.size(); ++r) {
    for (const auto& [name, value] : models[r].params) {
      if (!vary.name.empty() && name == vary.name) {
        throw UsageError("--vary: '" + vary.name + "' is also given with --param for " + models[r].model);
      }
    }
    for (int c = 0; c < columns; ++c) {
      Cell cell;
      cell.row = static_cast<int>(r);
      cell.column = c;
      cell.model = models[r].model;
      cell.params = models[r].params;
      if (!vary.values.empty()) cell.params.emplace_back(vary.name, vary.values[static_cast<std::size_t>(c)]);
      auto brdf = make_brdf(cell.model, cell.params);
      if (!brdf) throw UsageError(vary.name.empty() ? brdf.error().message : "--vary: " + brdf.error().message);
      cell.brdf = std::shared_ptr<const Brdf>(std::move(brdf).value());
      cell.label = models[r].label + (vary.values.empty() ? "" : ", " + vary.name + "=" + cell.params.back().second);
      cells.push_back(std::move(cell));
    }
  }

  work_begins();
  Environment env;
  if (!o.hdri.empty()) {
    ReadInfo info;
    auto image = read_radiance_image(o.hdri, &info);  // NaN, Inf or negative: exit 2
    if (!image) throw UsageError("--hdri: " + image.error().message);
    if (image->width != 2 * image->height) {
      throw UsageError(fmt::format("--hdri: '{}' is {} x {}; a lat-long map is twice as wide as it is high", o.hdri,
                                   image->width, image->height));
    }
    env.kind = Environment::Kind::image;
    env.latlong = std::move(image).value();
    env.source = o.hdri;
    env.rotation_deg = o.hdri_rotation;
  } else if (o.ambient > 0.0) {
    env.kind = Environment::Kind::uniform;
    env.uniform = Rgb::gray(o.ambient);
    env.source = "uniform";
  }

  // The sheet: cells of o.cell pixels with a gap between them and around them.
  const int gap = std::max(2, o.cell / 32);
  const int rows = static_cast<int>(models.size());
  const int width = columns * o.cell + (columns + 1) * gap;
  const int height = rows * o.cell + (rows + 1) * gap;
  Image linear(width, height);
  Image display(width, height);
  const Rgb gap_colour = Rgb::gray(0.18);  // linear mid grey, distinct from a black background
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) display.set(x, y, gap_colour);
  }
  const auto start = std::chrono::steady_clock::now();
  RenderOptions ro;
  std::uint64_t nonfinite = 0;
  for (auto& cell : cells) {
    cell.x = gap + cell.column * (o.cell + gap);
    cell.y = gap + cell.row * (o.cell + gap);
    const Scene scene = cell_scene(o, to_light, light, env, cell);
    auto result = render_scene(scene, ro);
    if (!result) throw UsageError("sheet: " + cell.label + ": " + result.error().message);
    nonfinite += result->stats.nonfinite_samples;
    const Image shown = unwrap(apply_view(result->beauty, o.exposure, view));
    for (int y = 0; y < o.cell; ++y) {
      for (int x = 0; x < o.cell; ++x) {
        linear.set(cell.x + x, cell.y + y, result->beauty.at(x, y));
        display.set(cell.x + x, cell.y + y, shown.at(x, y));
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The sheet, its EXR and its CSV are one output set (issue 40, finding 7): published together below.
  std::vector<std::pair<std::filesystem::path, std::vector<char>>> files;
  files.emplace_back(o.out, unwrap(encode_image(display, o.out)));
  if (!o.exr.empty()) files.emplace_back(o.exr, unwrap(encode_image(linear, o.exr)));

  const auto params_text = [](const ParamAssignments& params) {
    std::string out;
    for (const auto& [name, value] : params) out += (out.empty() ? "" : ";") + name + "=" + value;
    return out;
  };
  if (!o.csv.empty()) {
    std::string csv = "row,column,model,params,x,y,width,height\n";
    for (const auto& c : cells) {
      const std::string p = params_text(c.params);
      csv += fmt::format("{},{},{},{},{},{},{},{}\n", c.row, c.column, c.model,
                         p.find_first_of(",\"") == std::string::npos ? p : "\"" + p + "\"", c.x, c.y, o.cell, o.cell);
    }
    files.emplace_back(o.csv, std::vector<char>(csv.begin(), csv.end()));
  }
  unwrap(write_files_atomically(files));
  if (o.json) {
    nlohmann::json jrows = nlohmann::json::array();
    for (const auto& m : models) {
      nlohmann::json p = nlohmann::json::object();
      for (const auto& [name, value] : m.params) p[name] = value;
      jrows.push_back({{"model", m.model}, {"params", p}, {"label", m.label}});
    }
    nlohmann::json jcells = nlohmann::json::array();
    for (const auto& c : cells) {
      nlohmann::json p = nlohmann::json::object();
      for (const auto& [name, value] : c.params) p[name] = value;
      jcells.push_back({{"row", c.row},
                        {"column", c.column},
                        {"model", c.model},
                        {"params", p},
                        {"label", c.label},
                        {"x", c.x},
                        {"y", c.y},
                        {"width", o.cell},
                        {"height", o.cell}});
    }
    nlohmann::json light_json = {
        {"type", light}, {"to_light", {to_light.x, to_light.y, to_light.z}}, {"intensity", o.intensity}};
    print_json({{"out", o.out},
                {"exr", o.exr.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.exr)},
                {"width", width},
                {"height", height},
                {"cell", o.cell},
                {"gap", gap},
                {"rows", jrows},
                {"vary", vary.name.empty() ? nlohmann::json(nullptr)
                                           : nlohmann::json({{"name", vary.name}, {"values", vary.values}})},
                {"cells", jcells},
                {"light", light_json},
                {"hdri", o.hdri.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.hdri)},
                {"ambient", o.ambient},
                {"spp", o.spp},
                {"seed", o.seed},
                {"nonfinite_samples", nonfinite},
                {"seconds", seconds}});
  } else {
    fmt::print("{} x {} cells of {} px, {} spp in {:.2f} s\nwrote {}\n", rows, columns, o.cell, o.spp, seconds, o.out);
    if (!o.exr.empty()) fmt::print("wrote {}\n", o.exr);
  }
  if (nonfinite > 0) {
    std::fflush(stdout);
    std::cerr << "shadelab: sheet: " << nonfinite << " samples were NaN or infinite (kept in the image); the sheet is wrong\n";
    std::exit(1);
  }
}

void add_sheet_command(CLI::App& app, Command& command) {
  auto o = std::make_shared<SheetOptions>();
  auto* sub = app.add_subcommand("sheet", "a grid of lit spheres: one row per model, one column per --vary value");
  sub->add_option("MODEL", o->models, "one model per row (see brdf list)")->required();
  sub->add_option("-p,--param", o->params,
                  "NAME=VALUE for every model that has NAME; MODEL:NAME=VALUE or K:NAME=VALUE for one row; "
                  "repeatable")
      ->allow_extra_args(false);  // one value per --param, so MODELs may follow it
  sub->add_option("--vary", o->vary,
                  "NAME=V1,V2,...: one column per value of a numeric parameter (e.g. n=10,100,1000)");
  sub->add_option("--light", o->light, "sphere (default), directional, or none (the default with --hdri)");
  sub->add_option("--light-dir", o->light_dir, "direction toward the light, X,Y,Z, world space (+Y up, camera on +Z)")
      ->capture_default_str();
  sub->add_option("--intensity", o->intensity, "light colour in game units: E_perp = pi x intensity W/m^2")
      ->capture_default_str();
  sub->add_option("--hdri", o->hdri, "lat-long environment map (.exr or .hdr), radiance");
  sub->add_option("--hdri-rotation", o->hdri_rotation, "rotation of the map about +Y, degrees")->capture_default_str();
  sub->add_option("--ambient", o->ambient, "uniform environment radiance (without --hdri)")->capture_default_str();
  sub->add_option("--cell", o->cell, "cell size in pixels, [16, 256]")->capture_default_str();
  sub->add_option("--spp", o->spp, "samples per pixel")->capture_default_str();
  sub->add_option("--seed", o->seed, "random seed")->capture_default_str();
  sub->add_option("--threads", o->threads, "threads, 0 = all cores")->capture_default_str();
  sub->add_option("--exposure", o->exposure, "PNG exposure in stops")->capture_default_str();
  add_view_options(sub, o->view, "standard", true);
  sub->add_option("--out", o->out, "tone-mapped sheet, .png")->capture_default_str();
  sub->add_option("--exr", o->exr, "also write the linear sheet, .exr");
  sub->add_option("--csv", o->csv, "write the layout (cell, model, parameters, pixel rectangle) as CSV");
  sub->add_flag("--json", o->json, "print the layout and settings as JSON");
  sub->callback([o, &command] { command.run = [o] { run_sheet(*o); }; });
}

}  // namespace

const CommandRegistration registration_sheet(80, add_sheet_command);

}  // namespace shadelab::cli
