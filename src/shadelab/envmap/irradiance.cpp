#include "shadelab/envmap/irradiance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/latlong.h"

namespace shadelab {

CubeMap downsample_cube(const CubeMap& cube) {
  if (cube.size % 2 != 0 || cube.size < 2) return cube;
  const int n = cube.size / 2;
  CubeMap out(n);
  for (int f = 0; f < 6; ++f) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        Rgb sum;
        double w = 0.0;
        for (int j = 0; j < 2; ++j) {
          for (int i = 0; i < 2; ++i) {
            const double a = cube_texel_solid_angle(2 * x + i, 2 * y + j, cube.size);
            sum += cube.texel(f, 2 * x + i, 2 * y + j) * a;
            w += a;
          }
        }
        out.set(f, x, y, sum / w);
      }
    }
  }
  return out;
}

namespace {

// The input as flat arrays: unit directions and L dOmega, in float for a vectorizable inner loop.
struct Emitters {
  std::vector<float> x, y, z, r, g, b;
};

Emitters make_emitters(const CubeMap& cube) {
  const CubeTexelTable& t = CubeTexelTable::get(cube.size);
  Emitters e;
  const std::size_t count = t.direction.size();
  for (auto* v : {&e.x, &e.y, &e.z, &e.r, &e.g, &e.b}) v->resize(count);
  const auto n = static_cast<std::size_t>(cube.size);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t face = k / (n * n);
    const std::size_t p = 3 * (k % (n * n));
    const auto& data = cube.faces[face].data;
    const double w = t.solid_angle[k];
    e.x[k] = static_cast<float>(t.direction[k].x);
    e.y[k] = static_cast<float>(t.direction[k].y);
    e.z[k] = static_cast<float>(t.direction[k].z);
    e.r[k] = static_cast<float>(static_cast<double>(data[p]) * w);
    e.g[k] = static_cast<float>(static_cast<double>(data[p + 1]) * w);
    e.b[k] = static_cast<float>(static_cast<double>(data[p + 2]) * w);
  }
  return e;
}

// E(n) over all emitters: blocks of 1024 summed in float, blocks summed in double.
Rgb convolve(const Emitters& e, const Vec3& n) {
  const auto nx = static_cast<float>(n.x);
  const auto ny = static_cast<float>(n.y);
  const auto nz = static_cast<float>(n.z);
  const std::size_t count = e.x.size();
  double r = 0.0, g = 0.0, b = 0.0;
  for (std::size_t start = 0; start < count; start += 1024) {
    const std::size_t end = std::min(count, start + 1024);
    float sr = 0.0f, sg = 0.0f, sb = 0.0f;
    for (std::size_t k = start; k < end; ++k) {
      const float c = std::max(0.0f, nx * e.x[k] + ny * e.y[k] + nz * e.z[k]);
      sr += c * e.r[k];
      sg += c * e.g[k];
      sb += c * e.b[k];
    }
    r += static_cast<double>(sr);
    g += static_cast<double>(sg);
    b += static_cast<double>(sb);
  }
  return {r, g, b};
}

CubeMap prepared_input(const CubeMap& radiance, int max_size) {
  CubeMap in = radiance;
  while (in.size > max_size && in.size % 2 == 0) in = downsample_cube(in);
  return in;
}

// Runs body(row) for rows [0, rows) in parallel, in chunks, reporting progress between chunks.
void for_rows(int rows, const ProgressFn& progress, const std::function<void(int)>& body) {
  const int chunk = std::max(1, rows / 50);
  for (int start = 0; start < rows; start += chunk) {
    const int end = std::min(rows, start + chunk);
    tbb::parallel_for(tbb::blocked_range<int>(start, end), [&](const tbb::blocked_range<int>& r) {
      for (int row = r.begin(); row != r.end(); ++row) body(row);
    });
    if (progress) progress(static_cast<double>(end) / rows);
  }
}

}  // namespace

Rgb irradiance_brute_force(const CubeMap& radiance, const Vec3& n) {
  const CubeTexelTable& t = CubeTexelTable::get(radiance.size);
  Rgb sum;
  const auto size = static_cast<std::size_t>(radiance.size);
  for (std::size_t k = 0; k < t.direction.size(); ++k) {
    const double c = dot(n, t.direction[k]);
    if (c <= 0.0) continue;
    const std::size_t face = k / (size * size);
    const std::size_t p = k % (size * size);
    sum += radiance.faces[face].at(static_cast<int>(p % size), static_cast<int>(p / size)) * (c * t.solid_angle[k]);
  }
  return sum;
}

CubeMap irradiance_cube(const CubeMap& radiance, int size, RadianceUnits units, const ConvolveOptions& options) {
  const Emitters e = make_emitters(prepared_input(radiance, options.max_input_size));
  const double scale = units == RadianceUnits::game ? inv_pi : 1.0;  // game: E / pi
  CubeMap out(size);
  for_rows(6 * size, options.progress, [&](int row) {
    const int face = row / size;
    const int y = row % size;
    for (int x = 0; x < size; ++x) out.set(face, x, y, convolve(e, texel_direction(face, x, y, size)) * scale);
  });
  return out;
}

Image irradiance_latlong(const CubeMap& radiance, int width, RadianceUnits units, const ConvolveOptions& options) {
  const Emitters e = make_emitters(prepared_input(radiance, options.max_input_size));
  const double scale = units == RadianceUnits::game ? inv_pi : 1.0;
  const int height = std::max(1, width / 2);
  Image out(width, height);
  for_rows(height, options.progress, [&](int y) {
    for (int x = 0; x < width; ++x) {
      out.set(x, y, convolve(e, latlong_direction((x + 0.5) / width, (y + 0.5) / height)) * scale);
    }
  });
  return out;
}

}  // namespace shadelab
