// --view, --look, --ocio-config on the commands that write PNGs (docs/color.md): the PNG is the EXR through the
// view (checked against render/film.h's apply_view of the EXR the command wrote), the repo's OCIO config gives the
// kernel's AgX within 1 code, bad values are one line naming the option and exit 2 before any rendering.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <utility>
#include <string>

#include "cli_run.h"
#include "shadelab/image/image_io.h"
#include "shadelab/image/srgb.h"
#include "shadelab/render/film.h"

namespace {

namespace fs = std::filesystem;
using shadelab::testing::expect_usage_error;
using shadelab::testing::run;
using shadelab::testing::temp_dir;

const std::string kConfig = (fs::path(SHADELAB_SCENES_DIR) / ".." / "share" / "ocio" / "shadelab.ocio").lexically_normal().string();

// The largest difference of 8-bit codes between a PNG and the EXR through `view` at `stops`.
int max_code_difference(const fs::path& png, const fs::path& exr, const std::string& view, double stops) {
  auto shown = shadelab::read_image(png);
  auto hdr = shadelab::read_image(exr);
  EXPECT_TRUE(shown && hdr);
  if (!shown || !hdr) return 999;
  auto v = shadelab::parse_view(view);
  EXPECT_TRUE(v);
  auto want = shadelab::apply_view(*hdr, stops, *v);
  EXPECT_TRUE(want);
  int worst = 0;
  for (std::size_t i = 0; i < want->data.size(); ++i) {
    worst = std::max(worst, std::abs(int(shadelab::linear_to_srgb8(shown->data[i])) - int(shadelab::linear_to_srgb8(want->data[i]))));
  }
  return worst;
}

// A 64 x 64 saturated orange sphere under a bright point light and a blue sky: highlights above 1 in every view.
std::string scene(const std::string& name = "view_scene", const std::string& kd = "[0.9, 0.35, 0.05]",
                  const std::string& sky = "[0.1, 0.2, 0.6]") {
  const fs::path p = temp_dir() / (name + ".json");
  std::ofstream(p) << R"({"units": "radiometric",
  "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40, "width": 64, "height": 64},
  "render": {"spp": 1, "max_depth": 2},
  "materials": {"m": {"model": "blinn-phong", "params": {"kd": )" << kd << R"(, "ks": 0.3, "n": 40}}},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
  "lights": [{"type": "point", "position": [2, 2, 3], "color": [1, 1, 1], "power": 2000}],
  "environment": {"uniform": )" << sky << "}}";
  return p.string();
}

TEST(CliView, RenderPngIsTheExrThroughTheView) {
  for (const char* view : {"agx", "pbr-neutral", "aces"}) {
    const fs::path exr = temp_dir() / (std::string(view) + ".exr"), png = temp_dir() / (std::string(view) + ".png");
    const auto r = run("render " + scene() + " --out " + exr.string() + " --view " + view + " --exposure 1.5");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(max_code_difference(png, exr, view, 1.5), 0) << view;
  }
  // The repo's OCIO config, by OCIO:<config>:... and by --ocio-config: AgX within 1 code of the kernel's.
  for (const std::string& args : {" --view 'OCIO:" + kConfig + ":sRGB:AgX'", std::string(" --view OCIO::sRGB:AgX --ocio-config ") + kConfig}) {
    const fs::path png = temp_dir() / "ocio.png";
    const auto s = run("render " + scene() + " --out " + (temp_dir() / "o.exr").string() + " --png " + png.string() + args + " --exposure 1.5");
    ASSERT_EQ(s.code, 0) << s.err;
    EXPECT_LE(max_code_difference(png, temp_dir() / "o.exr", "agx", 1.5), 1) << args;
  }
}

// --working-space acescg: a scene of greys (grey material, grey lights, grey environment) renders the same in both
// spaces (greys are the same in both and their products commute with the conversion), a coloured one does not (the
// products of colours differ by space), and the files stay linear Rec.709.
TEST(CliView, WorkingSpaceAcescg) {
  const std::string grey = scene("grey", "0.6", "0.3"), colour = scene();
  const auto max_abs = [](const fs::path& a, const fs::path& b) {
    auto x = shadelab::read_image(a), y = shadelab::read_image(b);
    EXPECT_TRUE(x && y);
    double m = 0.0;
    for (std::size_t i = 0; x && y && i < x->data.size(); ++i) m = std::max(m, double(std::abs(x->data[i] - y->data[i])));
    return m;
  };
  for (const auto& [name, file] : {std::pair{"grey", grey}, std::pair{"colour", colour}}) {
    const fs::path a = temp_dir() / (std::string(name) + "_rec709.exr"), b = temp_dir() / (std::string(name) + "_acescg.exr");
    ASSERT_EQ(run("render " + file + " --no-png --out " + a.string()).code, 0);
    const auto r = run("render " + file + " --no-png --working-space acescg --out " + b.string());
    ASSERT_EQ(r.code, 0) << r.err;
    const double d = max_abs(a, b);
    if (std::string(name) == "grey") {
      EXPECT_LT(d, 1e-5) << "greys differ by working space";
    } else {
      EXPECT_GT(d, 1e-3) << "the working space changed nothing";
      // A corner sees the sky alone: converted in and back, it is the scene's (0.1, 0.2, 0.6) in the file.
      const auto img = shadelab::read_image(b);
      ASSERT_TRUE(img);
      const shadelab::Rgb c = img->at(0, 0);
      EXPECT_NEAR(c.r, 0.1, 1e-5);
      EXPECT_NEAR(c.g, 0.2, 1e-5);
      EXPECT_NEAR(c.b, 0.6, 1e-5);
    }
  }
  expect_usage_error("render " + grey + " --working-space p3", "--working-space");
  expect_usage_error("render " + grey + " --working-space acescg --shard 1/2 --out p.exr", "--working-space");
}

TEST(CliView, BadValuesNameTheOption) {
  expect_usage_error("render --spp 1 --view agX", "--view: 'agX': not a view");
  expect_usage_error("render --spp 1 --view agx --filmic", "--filmic: conflicts with --view agx");
  expect_usage_error("render --spp 1 --look punchy", "--look");
  expect_usage_error("render --spp 1 --ocio-config " + kConfig, "--ocio-config");
  expect_usage_error("render --spp 1 --view OCIO:" + kConfig + ":sRGB:Nope", "view 'Nope': no such view");
  expect_usage_error("render --spp 1 --view OCIO:" + kConfig + ":sRGB:AgX --look punchy", "punchy");
  expect_usage_error("render --spp 1 --view OCIO:/no/such.ocio:sRGB:AgX", "/no/such.ocio");
  expect_usage_error("sheet lambert --view bogus", "--view");
  expect_usage_error("report --view bogus", "--view");
  expect_usage_error("merge a.exr --out m.exr --view bogus", "--view");
  ::unsetenv("OCIO");
  expect_usage_error("render --spp 1 --view OCIO::sRGB:AgX", "$OCIO");
}

}  // namespace
