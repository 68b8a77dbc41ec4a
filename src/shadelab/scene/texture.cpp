// sample_texture (scene.h): bilinear interpolation between texel centres, wrapping around in u and v.
// Texel (x, y) covers u in [x / W, (x + 1) / W] and v in [y / H, (y + 1) / H]; its centre is at
// ((x + 0.5) / W, (y + 0.5) / H), where the lookup returns the texel's value exactly.
#include <algorithm>
#include <cmath>

#include "shadelab/scene/scene.h"

namespace shadelab {

namespace {

// The fractional part of x, in [0, 1): where a coordinate lands after wrapping around. 0 for a non-finite x
// (a degenerate uv upstream) and for |x| >= 2^52, which has no fraction left. Taken before scaling by the
// image size, so no coordinate (uv_scale 1e308 included) can overflow into a wild index.
double fraction(double x) {
  if (!std::isfinite(x)) return 0.0;
  const double f = x - std::floor(x);
  return f < 1.0 ? f : 0.0;  // x just below an integer: the difference rounds up to 1
}

}  // namespace

Rgb sample_texture(const Texture& texture, Vec2 uv) {
  const Image& image = texture.image;
  if (!image.is_valid()) return {};
  const double x = fraction(uv.x) * image.width - 0.5;  // continuous texel coordinate; centres at integers
  const double y = fraction(uv.y) * image.height - 0.5;  // in [-0.5, size - 0.5]
  const double x0 = std::floor(x);
  const double y0 = std::floor(y);
  const double fx = x - x0;
  const double fy = y - y0;
  // x0 is in [-1, width - 1]: -1 is the last column, wrapped.
  const int ix0 = x0 < 0.0 ? image.width - 1 : std::min(static_cast<int>(x0), image.width - 1);
  const int iy0 = y0 < 0.0 ? image.height - 1 : std::min(static_cast<int>(y0), image.height - 1);
  const int ix1 = ix0 + 1 == image.width ? 0 : ix0 + 1;
  const int iy1 = iy0 + 1 == image.height ? 0 : iy0 + 1;
  const Rgb top = image.at(ix0, iy0) * (1.0 - fx) + image.at(ix1, iy0) * fx;
  const Rgb bottom = image.at(ix0, iy1) * (1.0 - fx) + image.at(ix1, iy1) * fx;
  return top * (1.0 - fy) + bottom * fy;
}

UvTransform make_gltf_uv_transform(Vec2 offset, double rotation_rad, Vec2 scale) {
  const double c = std::cos(rotation_rad);
  const double s = std::sin(rotation_rad);
  UvTransform t;
  t.m00 = c * scale.x;
  t.m01 = s * scale.y;
  t.m02 = offset.x;
  t.m10 = -s * scale.x;
  t.m11 = c * scale.y;
  t.m12 = offset.y;
  return t;
}

}  // namespace shadelab
