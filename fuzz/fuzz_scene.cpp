// Fuzz harness: the scene JSON parser (load_scene) and, for every scene it accepts, both renderers at a
// few pixels. Contract checked: an error is one printable line naming the file; an accepted scene passes the
// renderers' limits check (check_scene_limits) and renders without a crash, an abort in Embree or an
// internal error; a render error is one printable line.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "fixture.h"
#include "harness.h"
#include "shadelab/render/game_renderer.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/scene/limits.h"
#include "shadelab/scene/scene_json.h"

using namespace shadelab;

namespace {

void check_image(const Image& image, const Scene& scene, const char* what) {
  if (!image.is_valid() || image.width != scene.camera.width || image.height != scene.camera.height) {
    fuzz::finding(what, "the image is " + std::to_string(image.width) + " x " + std::to_string(image.height));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    const auto d = fuzz::work_dir("scene");
    fuzz::write_fixture(d);
    return d;
  }();
  const std::filesystem::path file = dir / "scene.json";
  fuzz::write_file(file, fuzz::as_text(data, size));
  auto scene = load_scene(file);
  if (!scene) {
    fuzz::require_one_line(scene.error().message, file.string());
    return 0;
  }
  if (auto limits = check_scene_limits(*scene); !limits) {
    fuzz::finding("an accepted scene breaks the renderers' limits", limits.error().message);
  }
  // A few pixels, one sample, a short path: the renderers see every value the parser let through.
  Scene small = std::move(scene).value();
  small.camera.width = std::min(small.camera.width, 3);
  small.camera.height = std::min(small.camera.height, 2);
  RenderOptions ro;
  ro.spp = 1;
  ro.max_depth = std::min(small.settings.max_depth, 3);
  ro.threads = 1;
  auto reference = render_scene(small, ro);
  if (!reference) {
    fuzz::require_one_line(reference.error().message, "");
  } else {
    check_image(reference->beauty, small, "reference render");
  }
  GameOptions go;
  go.spp = 1;
  go.threads = 1;
  go.environment_size = 4;
  go.specular_size = 4;
  auto game = render_game(small, go);
  if (!game) {
    fuzz::require_one_line(game.error().message, "");
  } else {
    check_image(game->beauty, small, "game render");
  }
  return 0;
}
