#include "shadelab/envmap/base/cubemap.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

namespace shadelab {

kernel::CubeTexels cube_texels(const CubeMap& cube) {
  kernel::CubeTexels t;
  for (std::size_t f = 0; f < 6; ++f) t.faces[f] = cube.faces[f].data.data();
  t.size = cube.size;
  return t;
}

Rgb sample_cube_seamless(const CubeMap& cube, const Vec3& dir) {
  if (cube.size < 1) return {};
  const kernel::CubeTexels c = cube_texels(cube);
  const kernel::IblTexels texels{&c, 1, nullptr, 0};
  const kernel::IblBinding bind(texels);
  return kernel::cube_sample_seamless(0, dir);
}

Rgb texel_across_edges(const CubeMap& c, int face, int x, int y) {
  const kernel::CubeTexels cube = cube_texels(c);
  const kernel::IblTexels texels{&cube, 1, nullptr, 0};
  const kernel::IblBinding bind(texels);
  return kernel::cube_texel_across_edges(0, c.size, face, x, y);
}

namespace {
// Solid angle of the face-plane rectangle [0, x] x [0, y] (signed), at distance 1.
double area_element(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }
}  // namespace

double cube_texel_solid_angle(int x, int y, int size) {
  const double inv = 2.0 / size;
  const double x0 = x * inv - 1.0;
  const double x1 = (x + 1) * inv - 1.0;
  const double y0 = y * inv - 1.0;
  const double y1 = (y + 1) * inv - 1.0;
  return area_element(x1, y1) - area_element(x0, y1) - area_element(x1, y0) + area_element(x0, y0);
}

CubeMap::CubeMap(int n) : size(n) {
  for (auto& f : faces) f = Image(n, n);
}

Rgb CubeMap::sample(const Vec3& dir) const {
  const CubeCoord c = cube_coord(dir);
  const Image& img = faces[static_cast<std::size_t>(c.face)];
  const double fx = std::clamp(c.s * size - 0.5, 0.0, size - 1.0);
  const double fy = std::clamp(c.t * size - 0.5, 0.0, size - 1.0);
  const int x0 = std::min(static_cast<int>(fx), size - 1);
  const int y0 = std::min(static_cast<int>(fy), size - 1);
  const int x1 = std::min(x0 + 1, size - 1);
  const int y1 = std::min(y0 + 1, size - 1);
  const double ax = fx - x0;
  const double ay = fy - y0;
  return (img.at(x0, y0) * (1 - ax) + img.at(x1, y0) * ax) * (1 - ay) +
         (img.at(x0, y1) * (1 - ax) + img.at(x1, y1) * ax) * ay;
}

const CubeTexelTable& CubeTexelTable::get(int size) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<CubeTexelTable>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& entry = cache[size];
  if (!entry) {
    auto t = std::make_unique<CubeTexelTable>();
    t->size = size;
    const auto n = static_cast<std::size_t>(size);
    t->direction.resize(6 * n * n);
    t->solid_angle.resize(6 * n * n);
    for (int f = 0; f < 6; ++f) {
      for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
          const std::size_t i = (static_cast<std::size_t>(f) * n + static_cast<std::size_t>(y)) * n + static_cast<std::size_t>(x);
          t->direction[i] = texel_direction(f, x, y, size);
          t->solid_angle[i] = cube_texel_solid_angle(x, y, size);
        }
      }
    }
    entry = std::move(t);
  }
  return *entry;
}

const std::vector<CubeFaceTexel>& cube_face_table(int size) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<std::vector<CubeFaceTexel>>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& entry = cache[size];
  if (!entry) {
    auto table = std::make_unique<std::vector<CubeFaceTexel>>(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const double sc = 2.0 * (x + 0.5) / size - 1.0;
        const double tc = 2.0 * (y + 0.5) / size - 1.0;
        const double inv_len = 1.0 / std::sqrt(1.0 + sc * sc + tc * tc);
        (*table)[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)] = {
            static_cast<float>(sc * inv_len), static_cast<float>(tc * inv_len), static_cast<float>(inv_len),
            static_cast<float>(cube_texel_solid_angle(x, y, size))};
      }
    }
    entry = std::move(table);
  }
  return *entry;
}

const std::vector<double>& cube_face_solid_angles(int size) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<std::vector<double>>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& entry = cache[size];
  if (!entry) {
    const auto n = static_cast<std::size_t>(size);
    std::vector<double> corner((n + 1) * (n + 1));
    for (std::size_t j = 0; j <= n; ++j)
      for (std::size_t i = 0; i <= n; ++i)
        corner[j * (n + 1) + i] = area_element(2.0 * static_cast<double>(i) / size - 1.0, 2.0 * static_cast<double>(j) / size - 1.0);
    auto table = std::make_unique<std::vector<double>>(n * n);
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x)
        (*table)[y * n + x] = corner[(y + 1) * (n + 1) + x + 1] - corner[(y + 1) * (n + 1) + x] - corner[y * (n + 1) + x + 1] +
                              corner[y * (n + 1) + x];
    entry = std::move(table);
  }
  return *entry;
}

}  // namespace shadelab
