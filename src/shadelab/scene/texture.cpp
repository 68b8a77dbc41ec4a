// sample_texture (scene.h): bilinear interpolation between texel centres, wrapping around in u and v.
// Texel (x, y) covers u in [x / W, (x + 1) / W] and v in [y / H, (y + 1) / H]; its centre is at
// ((x + 0.5) / W, (y + 0.5) / H), where the lookup returns the texel's value exactly.
#include <cmath>

#include "shadelab/scene/scene.h"

namespace shadelab {

namespace {

// Integer part of x modulo n, in [0, n), for any finite x.
int wrap(double x, int n) {
  double m = std::fmod(x, static_cast<double>(n));
  if (m < 0.0) m += n;
  const int i = static_cast<int>(m);
  return i >= n ? 0 : i;  // fmod may round up to n for tiny negative x
}

}  // namespace

Rgb sample_texture(const Texture& texture, Vec2 uv) {
  const Image& image = texture.image;
  if (!image.is_valid()) return {};
  // A non-finite coordinate (a degenerate uv upstream) reads the first texel rather than NaN.
  const double u = std::isfinite(uv.x) ? uv.x : 0.0;
  const double v = std::isfinite(uv.y) ? uv.y : 0.0;
  const double x = u * image.width - 0.5;  // continuous texel coordinate; centres at integers
  const double y = v * image.height - 0.5;
  const double x0 = std::floor(x);
  const double y0 = std::floor(y);
  const double fx = x - x0;
  const double fy = y - y0;
  const int ix0 = wrap(x0, image.width);
  const int iy0 = wrap(y0, image.height);
  const int ix1 = ix0 + 1 == image.width ? 0 : ix0 + 1;
  const int iy1 = iy0 + 1 == image.height ? 0 : iy0 + 1;
  const Rgb top = image.at(ix0, iy0) * (1.0 - fx) + image.at(ix1, iy0) * fx;
  const Rgb bottom = image.at(ix0, iy1) * (1.0 - fx) + image.at(ix1, iy1) * fx;
  return top * (1.0 - fy) + bottom * fy;
}

}  // namespace shadelab
