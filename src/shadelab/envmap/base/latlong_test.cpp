#include "shadelab/envmap/base/latlong.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shadelab/core/constants.h"

namespace shadelab {
namespace {

TEST(LatLong, MappingConventions) {
  // Row 0 is straight up (+Y); the centre looks along +X (Blender's convention turned Y-up).
  EXPECT_NEAR(latlong_direction(0.3, 0.0).y, 1.0, 1e-15);
  const Vec3 c = latlong_direction(0.5, 0.5);
  EXPECT_NEAR(c.x, 1.0, 1e-15);
  const Vec3 q = latlong_direction(0.75, 0.5);  // a quarter turn: +Z
  EXPECT_NEAR(q.z, 1.0, 1e-15);
  for (double u : {0.01, 0.4, 0.99}) {
    for (double v : {0.05, 0.5, 0.9}) {
      const Vec2 uv = latlong_uv(latlong_direction(u, v));
      EXPECT_NEAR(uv.x, u, 1e-14);
      EXPECT_NEAR(uv.y, v, 1e-14);
    }
  }
}

TEST(LatLong, RowSolidAnglesTotalFourPi) {
  for (int w : {4, 64, 1024}) {
    const int h = w / 2;
    double total = 0.0;
    for (int y = 0; y < h; ++y) total += w * latlong_texel_solid_angle(y, w, h);
    EXPECT_NEAR(total, 4.0 * pi, 1e-10) << w;
  }
}

Image constant_latlong(int w, Rgb c) {
  Image img(w, w / 2);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < w; ++x) img.set(x, y, c);
  return img;
}

TEST(LatLong, ConversionKeepsAConstant) {
  const CubeMap cube = latlong_to_cube(constant_latlong(64, {0.5, 1.0, 2.0}), 8);
  EXPECT_NEAR(cube.texel(3, 2, 5).g, 1.0, 1e-6);
  const Image back = cube_to_latlong(cube, 32);
  EXPECT_EQ(back.width, 32);
  EXPECT_EQ(back.height, 16);
  EXPECT_NEAR(back.at(7, 3).b, 2.0, 1e-6);
}

TEST(LatLong, ConversionFollowsDirections) {
  // A map whose value is the direction's y (up) component keeps it through the cube conversion.
  Image img(256, 128);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 256; ++x) {
      const Vec3 d = latlong_direction((x + 0.5) / 256, (y + 0.5) / 128);
      img.set(x, y, {d.x, d.y, d.z});
    }
  const CubeMap cube = latlong_to_cube(img, 16);
  for (int f = 0; f < 6; ++f) {
    const Vec3 d = texel_direction(f, 3, 12, 16);
    const Rgb v = cube.texel(f, 3, 12);
    EXPECT_NEAR(v.r, d.x, 0.02);
    EXPECT_NEAR(v.g, d.y, 0.02);
    EXPECT_NEAR(v.b, d.z, 0.02);
  }
}

TEST(LatLong, CrossLayoutsRoundTripAndEdgesMeet) {
  CubeMap cube(4);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const Vec3 d = texel_direction(f, x, y, 4);
        cube.set(f, x, y, {d.x, d.y, d.z});
      }
  for (auto layout : {CrossLayout::horizontal, CrossLayout::vertical}) {
    const Image cross = cube_to_cross(cube, layout);
    const auto back = cube_from_cross(cross);
    ASSERT_TRUE(back.has_value());
    for (int f = 0; f < 6; ++f) EXPECT_EQ(back->texel(f, 1, 2).r, cube.texel(f, 1, 2).r);
    // Neighbouring texels across every seam of the cross point in nearly the same direction.
    if (layout == CrossLayout::vertical) {
      // -Y (row 2) above -Z (row 3): column 4..7, rows 11 and 12.
      const Rgb a = cross.at(5, 11);
      const Rgb b = cross.at(5, 12);
      EXPECT_GT(a.r * b.r + a.g * b.g + a.b * b.b, 0.8);
    } else {
      // +X (column 2) next to -Z (column 3), row 5.
      const Rgb a = cross.at(11, 5);
      const Rgb b = cross.at(12, 5);
      EXPECT_GT(a.r * b.r + a.g * b.g + a.b * b.b, 0.8);
    }
  }
}

TEST(LatLong, WrongCrossLayoutIsAnError) {
  const auto r = cube_from_cross(Image(100, 60));
  ASSERT_FALSE(r.has_value());
  EXPECT_NE(r.error().message.find("100 x 60"), std::string::npos);
  EXPECT_FALSE(cube_from_cross(Image(10, 10)).has_value());
}

}  // namespace
}  // namespace shadelab
