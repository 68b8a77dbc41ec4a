// Uses one function from each layer of an installed shadelab, so that linking needs every library and
// every dependency the package finds for its user: BRDF + analysis, light units, scene + render (Embree,
// TBB), image files (OpenEXR), plots (Cairo). Prints "shadelab consumer ok" and exits 0 when all work.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "shadelab/analysis/albedo.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/image/image_io.h"
#include "shadelab/light/units.h"
#include "shadelab/plot/plot.h"
#include "shadelab/render/path_tracer.h"
#include "shadelab/scene/default_scene.h"

int main(int argc, char** argv) {
  using namespace shadelab;
  const std::filesystem::path dir = argc > 1 ? argv[1] : ".";
  auto f = make_brdf("lambert", {{"kd", "1"}});
  if (!f) return std::fprintf(stderr, "%s\n", f.error().message.c_str()), 1;
  const double albedo = directional_albedo(**f, 0.5).albedo.g;  // a white Lambert surface reflects 1
  const auto lux = convert_light(Rgb::gray(1.0), "game", "lux");
  Scene scene = default_scene();
  scene.camera.width = 8;
  scene.camera.height = 4;
  RenderOptions options;
  options.spp = 1;
  options.threads = 1;
  const auto image = render_scene(scene, options);
  if (!image) return std::fprintf(stderr, "%s\n", image.error().message.c_str()), 1;
  const auto written = write_image(image->beauty, dir / "consumer.exr");
  LinePlot plot;
  plot.series.push_back({"albedo", {0.0, 1.0}, {albedo, albedo}, {}, 1.5, false});
  const auto png = render_plot(plot, PlotFormat::png, 64, 64);
  const bool ok = std::abs(albedo - 1.0) < 1e-9 && lux && std::abs(lux->g - 683.0 * pi) < 1e-9 && written &&
                  png && !png->empty() && read_image(dir / "consumer.exr");
  std::printf("shadelab consumer %s: albedo %.12f, %zu plot bytes\n", ok ? "ok" : "FAILED", albedo,
              png ? png->size() : std::size_t{0});
  return ok ? 0 : 1;
}
