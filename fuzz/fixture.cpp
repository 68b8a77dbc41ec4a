#include "fixture.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include "harness.h"
#include "shadelab/image/image_io.h"

#ifndef SHADELAB_SCENES_DIR
#error "SHADELAB_SCENES_DIR must name the scenes folder"
#endif

namespace shadelab::fuzz {

namespace {

void write(const std::filesystem::path& path, const Image& image) {
  auto r = write_image(image, path);
  if (!r) finding("setup", r.error().message);
}

Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      img.set(x, y, {0.1 + 0.8 * x / w, 0.2 + 0.5 * y / h, 0.3 + 0.1 * ((x + y) % 3)});
    }
  }
  return img;
}

}  // namespace

void write_fixture(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir / "meshes", ec);
  for (const char* mesh : {"box.gltf", "icosahedron.obj"}) {
    std::filesystem::copy_file(std::filesystem::path(SHADELAB_SCENES_DIR) / "meshes" / mesh, dir / "meshes" / mesh,
                               std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) finding("setup", std::string("cannot copy the example mesh ") + mesh + ": " + ec.message());
  }
  const Image env = gradient(32, 16);
  write(dir / "env.hdr", env);
  write(dir / "env.exr", env);
  write(dir / "env.png", env);
  write(dir / "tex.png", gradient(8, 8));
  write(dir / "cross.exr", gradient(16, 12));
  write_file(dir / "small.json",
             R"({"camera": {"width": 8, "height": 6}, "render": {"spp": 1, "max_depth": 2},)"
             R"( "materials": {"m": {"model": "lambert"}},)"
             R"( "shapes": [{"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "m"}],)"
             R"( "environment": {"uniform": 0.5}})");
}

}  // namespace shadelab::fuzz
