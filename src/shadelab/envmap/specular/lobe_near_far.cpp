// shadelab envmap internals (lobe_near_far.h): the coarse cells of the far field.
#include "shadelab/envmap/specular/lobe_near_far.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shadelab::lobe_sum {

FarInput make_far_input(const CubeMap& cube, int block) {
  if (block < 1 || cube.size % block != 0) throw std::invalid_argument("block: must divide the face size");
  FarInput far;
  far.block = block;
  far.n = cube.size / block;
  const int n = cube.size;
  const auto nc = static_cast<std::size_t>(far.n);
  const std::size_t cells = nc * nc;
  const std::vector<double>& omega = cube_face_solid_angles(n);
  const auto dir = [&](int x, int y) {
    const double sc = (2.0 * x + 1.0) / n - 1.0;
    const double tc = (2.0 * y + 1.0) / n - 1.0;
    const double inv = 1.0 / std::sqrt(1.0 + sc * sc + tc * tc);
    return Vec3{sc * inv, tc * inv, inv};  // face-local (a, b, c), as make_input's tables
  };
  for (auto* v : {&far.ga, &far.gb, &far.gc, &far.omega}) v->assign(cells + 8, 0.0f);
  for (std::size_t f = 0; f < 6; ++f)
    for (int c = 0; c < 3; ++c) {
      far.flux[f][c].assign(cells + 8, 0.0f);
      far.flux_reversed[f][c].assign(cells + 8, 0.0f);
      far.cen[f][c].assign(cells + 8, 0.0f);
      far.cen_reversed[f][c].assign(cells + 8, 0.0f);
    }
  for (int cy = 0; cy < far.n; ++cy)
    for (int cx = 0; cx < far.n; ++cx) {
      const std::size_t q = static_cast<std::size_t>(cy) * nc + static_cast<std::size_t>(cx);
      const std::size_t q_reversed = static_cast<std::size_t>(cy) * nc + (nc - 1 - static_cast<std::size_t>(cx));
      Vec3 g;
      double om = 0.0;
      for (int y = cy * block; y < (cy + 1) * block; ++y)
        for (int x = cx * block; x < (cx + 1) * block; ++x) {
          const double w = omega[static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x)];
          g += dir(x, y) * w;
          om += w;
        }
      g = normalize(g);
      far.ga[q] = static_cast<float>(g.x);
      far.gb[q] = static_cast<float>(g.y);
      far.gc[q] = static_cast<float>(g.z);
      far.omega[q] = static_cast<float>(om);
      for (std::size_t f = 0; f < 6; ++f) {
        Rgb phi;
        Vec3 m;
        for (int y = cy * block; y < (cy + 1) * block; ++y)
          for (int x = cx * block; x < (cx + 1) * block; ++x) {
            const double w = omega[static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x)];
            const Rgb& l = cube.texel(static_cast<int>(f), x, y);
            phi += l * w;
            m += dir(x, y) * (std::max(0.0, l.r + l.g + l.b) * w);
          }
        const double len = std::sqrt(dot(m, m));
        const Vec3 cq = len > 0.0 && std::isfinite(len) ? m / len : g;  // a black cell: any direction serves
        const double values[3] = {phi.r, phi.g, phi.b};
        const double centroid[3] = {cq.x, cq.y, cq.z};
        for (int c = 0; c < 3; ++c) {
          far.flux[f][c][q] = far.flux_reversed[f][c][q_reversed] = static_cast<float>(values[c]);
          far.cen[f][c][q] = far.cen_reversed[f][c][q_reversed] = static_cast<float>(centroid[c]);
        }
      }
    }
  return far;
}

bool cap_cells(double ra, double rb, double rc, double cos_t, int n, int y, int& lo, int& hi) {
  const double tc = (2.0 * y + 1.0) / n - 1.0;
  const auto inside = [&](int x) {
    const double sc = (2.0 * x + 1.0) / n - 1.0;
    return ra * sc + rb * tc + rc >= cos_t * std::sqrt(1.0 + sc * sc + tc * tc);
  };
  // Below 90 degrees the qualifying centres lie between the roots of lobe_sum.cpp's row quadratic (one cell
  // of margin each side); above it, or where the quadratic leaves the row unbounded, the whole row is scanned.
  int x0 = 0, x1 = n - 1;
  if (cos_t > 0.0 && !row_range(ra, rb, rc, cos_t, tc, n, x0, x1)) return false;
  while (x0 <= x1 && !inside(x0)) ++x0;
  while (x1 >= x0 && !inside(x1)) --x1;
  lo = x0;
  hi = x1;
  return x0 <= x1;
}

}  // namespace shadelab::lobe_sum
