#include "shadelab/envmap/base/environment.h"

#include <gtest/gtest.h>

#include <string>

namespace shadelab {
namespace {

Image filled(int w, int h, Rgb c) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set(x, y, c);
  return img;
}

TEST(EnvironmentCube, DefaultFaceSizeIsThePowerOfTwoNearAQuarterOfTheWidth) {
  EXPECT_EQ(default_latlong_face_size(8192), 512);  // capped
  EXPECT_EQ(default_latlong_face_size(2048), 512);
  EXPECT_EQ(default_latlong_face_size(1024), 256);
  EXPECT_EQ(default_latlong_face_size(100), 16);    // 25 -> 16
  EXPECT_EQ(default_latlong_face_size(64), 16);
  EXPECT_EQ(default_latlong_face_size(7), 1);
  EXPECT_EQ(default_latlong_face_size(0), 1);
}

TEST(EnvironmentCube, LatLongIsResampledAndAConstantStaysConstant) {
  const Image env = filled(64, 32, {0.25, 0.5, 2.0});
  const auto cube = environment_cube(env);
  ASSERT_TRUE(cube) << cube.error().message;
  EXPECT_EQ(cube->size, 16);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const Rgb t = cube->texel(f, x, y);
        EXPECT_NEAR(t.r, 0.25, 1e-6);
        EXPECT_NEAR(t.g, 0.5, 1e-6);
        EXPECT_NEAR(t.b, 2.0, 1e-6);
      }
  const auto small = environment_cube(env, 4);
  ASSERT_TRUE(small);
  EXPECT_EQ(small->size, 4);
}

TEST(EnvironmentCube, HorizontalCrossFacesLandOnTheirCubeFaces) {
  // Horizontal cross (latlong.h): row 1 holds -X +Z +X -Z; +Y above +Z, -Y below it.
  const int s = 4;
  Image cross(4 * s, 3 * s);
  const auto paint = [&](int col, int row, Rgb c) {
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x) cross.set(col * s + x, row * s + y, c);
  };
  paint(2, 1, {1, 0, 0});  // +X
  paint(1, 0, {0, 1, 0});  // +Y
  paint(3, 1, {0, 0, 1});  // -Z
  const auto cube = environment_cube(cross);
  ASSERT_TRUE(cube) << cube.error().message;
  EXPECT_EQ(cube->size, s);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      EXPECT_EQ(cube->texel(static_cast<int>(CubeFace::pos_x), x, y).r, 1.0);
      EXPECT_EQ(cube->texel(static_cast<int>(CubeFace::pos_y), x, y).g, 1.0);
      EXPECT_EQ(cube->texel(static_cast<int>(CubeFace::neg_z), x, y).b, 1.0);
      const Rgb pz = cube->texel(static_cast<int>(CubeFace::pos_z), x, y);
      EXPECT_EQ(pz.r + pz.g + pz.b, 0.0);
    }
}

TEST(EnvironmentCube, OtherShapesAndSizesAreErrors) {
  const auto bad_shape = environment_cube(filled(30, 20, {1, 1, 1}));
  ASSERT_FALSE(bad_shape);
  EXPECT_NE(bad_shape.error().message.find("expected a 2:1 lat-long or a cube cross"), std::string::npos)
      << bad_shape.error().message;
  const auto too_big = environment_cube(filled(64, 32, {1, 1, 1}), 4096);
  ASSERT_FALSE(too_big);
  EXPECT_EQ(too_big.error().message, "face size 4096 is out of range [1, 2048]");
  EXPECT_FALSE(environment_cube(Image{}));
}

}  // namespace
}  // namespace shadelab
