#include "shadelab/envmap/prefilter.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "shadelab/core/constants.h"

namespace shadelab {

double prefilter_exponent(int level, int mip_count, double gloss_scale, double gloss_bias) {
  const double t = mip_count > 1 ? static_cast<double>(level) / (mip_count - 1) : 0.0;
  return std::exp2(gloss_scale * (1.0 - t) + gloss_bias);  // cmft-style gloss scale and bias
}

Rgb prefilter_brute_force(const CubeMap& radiance, const Vec3& r, double n) {
  const CubeTexelTable& t = CubeTexelTable::get(radiance.size);
  const auto size = static_cast<std::size_t>(radiance.size);
  Rgb sum;
  double weight = 0.0;
  for (std::size_t k = 0; k < t.direction.size(); ++k) {
    const double c = dot(r, t.direction[k]);
    if (c <= 0.0) continue;
    const double w = std::pow(c, n) * t.solid_angle[k];  // (n+1)/(2pi) cancels in the ratio
    const std::size_t face = k / (size * size);
    const std::size_t p = k % (size * size);
    sum += radiance.faces[face].at(static_cast<int>(p % size), static_cast<int>(p / size)) * w;
    weight += w;
  }
  return weight > 0.0 ? sum / weight : Rgb{};
}

namespace {

// An input level prepared for culling: tiles of T x T texels with a bounding cone each.
struct Tile {
  Vec3 axis;
  double radius = 0.0;        // every texel centre of the tile is within this angle (radians) of the axis
  double cos_reach = -1.0;    // cos(radius + cutoff angle) for the level being filtered, -1 past pi
  int face = 0, x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct Level {
  const CubeMap* cube = nullptr;
  std::vector<Tile> tiles;
};

Level prepare_level(const CubeMap& cube) {
  Level lv;
  lv.cube = &cube;
  const int n = cube.size;
  const int tile = std::min(16, n);
  for (int f = 0; f < 6; ++f) {
    for (int ty = 0; ty < n; ty += tile) {
      for (int tx = 0; tx < n; tx += tile) {
        Tile t;
        t.face = f;
        t.x0 = tx;
        t.y0 = ty;
        t.x1 = std::min(n, tx + tile);
        t.y1 = std::min(n, ty + tile);
        t.axis = cube_direction(f, 0.5 * (t.x0 + t.x1) / n, 0.5 * (t.y0 + t.y1) / n);
        double c = 1.0;
        for (int y = t.y0; y < t.y1; ++y)
          for (int x = t.x0; x < t.x1; ++x) c = std::min(c, dot(t.axis, texel_direction(f, x, y, n)));
        t.radius = std::acos(std::clamp(c, -1.0, 1.0));
        lv.tiles.push_back(t);
      }
    }
  }
  return lv;
}

Rgb convolve(const Level& lv, const Vec3& r, double n, double cos_cutoff) {
  const CubeMap& cube = *lv.cube;
  const auto& table = cube_face_table(cube.size);
  Rgb sum;
  double weight = 0.0;
  for (const Tile& t : lv.tiles) {
    // Skip the tile if even its nearest possible texel is beyond the cutoff angle from r.
    // Every texel of the tile is at least angle(r, axis) - radius from r: skip the tile when that exceeds
    // the cutoff angle, i.e. when r.axis < cos(radius + cutoff) (precomputed per level, no acos here).
    if (dot(r, t.axis) < t.cos_reach) continue;
    const Image& img = cube.faces[static_cast<std::size_t>(t.face)];
    for (int y = t.y0; y < t.y1; ++y) {
      for (int x = t.x0; x < t.x1; ++x) {
        const Vec3 d = texel_direction(t.face, x, y, cube.size);
        const double c = dot(r, d);
        if (c < cos_cutoff) continue;
        const double w = std::pow(c, n) *
                         static_cast<double>(table[static_cast<std::size_t>(y) * static_cast<std::size_t>(cube.size) +
                                                   static_cast<std::size_t>(x)].w);
        sum += img.at(x, y) * w;
        weight += w;
      }
    }
  }
  return weight > 0.0 ? sum / weight : Rgb{};
}

}  // namespace

Result<PrefilteredCube> prefilter_specular(const CubeMap& radiance, const PrefilterOptions& o) {
  if (o.size < 1 || (o.size & (o.size - 1)) != 0) {
    return make_error("prefilter: size " + std::to_string(o.size) + " is not a power of two");
  }
  int max_levels = 1;
  while ((o.size >> (max_levels - 1)) > 1) ++max_levels;
  const int levels = o.mip_count == 0 ? max_levels : o.mip_count;
  if (levels < 1 || levels > max_levels) {
    return make_error("prefilter: mip count " + std::to_string(o.mip_count) + " is out of range [1, " +
                      std::to_string(max_levels) + "] for size " + std::to_string(o.size));
  }
  if (!std::isfinite(o.gloss_scale) || !std::isfinite(o.gloss_bias) || o.gloss_scale < 0.0) {
    return make_error("prefilter: gloss scale must be finite and >= 0, gloss bias finite");
  }
  if (radiance.size < 1) return make_error("prefilter: the input cube map is empty");

  // The input pyramid, finest first.
  std::vector<CubeMap> pyramid{radiance};
  while (pyramid.back().size % 2 == 0 && pyramid.back().size > 1) pyramid.push_back(downsample_cube(pyramid.back()));
  std::vector<Level> prepared(pyramid.size());

  PrefilteredCube out;
  long long total_rows = 0;
  for (int i = 0; i < levels; ++i) total_rows += 6LL * std::max(1, o.size >> i);
  long long rows_done = 0;
  for (int i = 0; i < levels; ++i) {
    const int size = std::max(1, o.size >> i);
    const double n = prefilter_exponent(i, levels, o.gloss_scale, o.gloss_bias);
    // Coarsest input whose texel angle (about (pi/2)/N) is at most half the lobe width 1/sqrt(n).
    std::size_t pick = 0;
    for (std::size_t k = 0; k < pyramid.size(); ++k) {
      if ((pi / 2.0) / pyramid[k].size <= 0.5 / std::sqrt(n)) pick = k;
    }
    if (prepared[pick].cube == nullptr) prepared[pick] = prepare_level(pyramid[pick]);
    Level& lv = prepared[pick];
    const double cos_cutoff = std::pow(1e-9, 1.0 / n);  // lobe below 1e-9 of its peak beyond this
    const double cutoff = std::acos(cos_cutoff);
    for (Tile& t : lv.tiles) t.cos_reach = t.radius + cutoff >= pi ? -2.0 : std::cos(t.radius + cutoff);
    CubeMap level(size);
    const int rows = 6 * size;
    const int chunk = std::max(1, rows / 20);
    for (int start = 0; start < rows; start += chunk) {
      const int end = std::min(rows, start + chunk);
      tbb::parallel_for(tbb::blocked_range<int>(start, end), [&](const tbb::blocked_range<int>& range) {
        for (int row = range.begin(); row != range.end(); ++row) {
          const int face = row / size;
          const int y = row % size;
          for (int x = 0; x < size; ++x) level.set(face, x, y, convolve(lv, texel_direction(face, x, y, size), n, cos_cutoff));
        }
      });
      rows_done += end - start;
      if (o.progress) o.progress(static_cast<double>(rows_done) / static_cast<double>(total_rows));
    }
    out.levels.push_back(std::move(level));
    out.exponents.push_back(n);
  }
  return out;
}

}  // namespace shadelab
