// shadelab envmap internals (lobe_sum.h): the input planes and the cap geometry of the lobe sums.
#include "shadelab/envmap/specular/lobe_sum.h"

#include <algorithm>

namespace shadelab::lobe_sum {

Input make_input(const CubeMap& cube) {
  Input in;
  in.cube = &cube;
  in.n = cube.size;
  const auto nn = static_cast<std::size_t>(cube.size) * static_cast<std::size_t>(cube.size);
  const auto n = static_cast<std::size_t>(cube.size);
  for (std::size_t f = 0; f < 6; ++f) {
    for (auto& plane : in.rgb[f]) plane.assign(nn + 8, 0.0f);
    for (auto& plane : in.rgb_reversed[f]) plane.assign(nn + 8, 0.0f);
    const auto& data = cube.faces[f].data;
    for (std::size_t i = 0; i < nn; ++i)
      for (std::size_t ch = 0; ch < 3; ++ch) {
        in.rgb[f][ch][i] = data[3 * i + ch];
        in.rgb_reversed[f][ch][i - i % n + (n - 1 - i % n)] = data[3 * i + ch];
      }
  }
  const std::vector<double>& omega = cube_face_solid_angles(cube.size);
  for (auto* v : {&in.a, &in.b, &in.c, &in.w}) v->assign(nn + 8, 0.0f);
  for (int y = 0; y < cube.size; ++y) {
    for (int x = 0; x < cube.size; ++x) {
      const double sc = (2.0 * x + 1.0) / cube.size - 1.0;
      const double tc = (2.0 * y + 1.0) / cube.size - 1.0;
      const double inv = 1.0 / std::sqrt(1.0 + sc * sc + tc * tc);
      const auto i = static_cast<std::size_t>(y) * static_cast<std::size_t>(cube.size) + static_cast<std::size_t>(x);
      in.a[i] = static_cast<float>(sc * inv);
      in.b[i] = static_cast<float>(tc * inv);
      in.c[i] = static_cast<float>(inv);
      in.w[i] = static_cast<float>(omega[i]);
    }
  }
  return in;
}

int face_axis_of_local(int face, int local) {
  for (int i = 0; i < 3; ++i)
    if (face_perm[face][i] == local) return i;
  return 0;
}
// The image of texel p's partner under the reflection of world axis `axis`.
Partner reflect(int axis, const Partner& p) {
  const int g = p.face;
  Partner m = p;
  m.face = face_axis_of_local(g, 2) == axis ? (g ^ 1) : g;  // faces +X -X +Y -Y +Z -Z: g ^ 1 is the opposite face, same perm
  const int ia = face_axis_of_local(g, 0);
  const bool flips_x = face_sign[m.face][ia] * face_sign[g][ia] * (ia == axis ? -1.0 : 1.0) < 0.0;
  (flips_x ? m.flip_x : m.flip_y) ^= true;
  return m;
}
// The texel index range [lo, hi] whose centres (2k + 1)/N - 1 can lie where the quadratic
// q2 s^2 + 2 q1 s + q0 <= 0 (s in [-1, 1]); false if none. Conservative: one texel of margin.
bool index_range(double q2, double q1, double q0, int n, int& lo, int& hi) {
  double s0 = -1.0, s1 = 1.0;
  if (q2 > 1e-12) {
    const double disc = q1 * q1 - q2 * q0;
    if (disc < 0.0) return false;
    const double root = std::sqrt(disc);
    s0 = std::max(-1.0, (-q1 - root) / q2);
    s1 = std::min(1.0, (-q1 + root) / q2);
    if (s0 > s1) return false;
  }
  lo = std::max(0, static_cast<int>(std::floor(((s0 + 1.0) * n - 1.0) * 0.5)) - 1);
  hi = std::min(n - 1, static_cast<int>(std::ceil(((s1 + 1.0) * n - 1.0) * 0.5)) + 1);
  return lo <= hi;
}

// The x range of row tc inside the cap r.p >= kappa |p|, p = (sc, tc, 1) (face-local): squaring,
// (ra^2 - kappa^2) sc^2 + 2 ra beta sc + beta^2 - kappa^2 (1 + tc^2) >= 0 with beta = rb tc + rc. When
// ra^2 < kappa^2 that is one interval (the cap's side is where ra sc + beta > 0); otherwise the row can meet
// the cap in a ray, and the face-wide column range is kept. Narrows [lo, hi]; false if the row misses.
bool row_range(double ra, double rb, double rc, double kappa, double tc, int n, int& lo, int& hi) {
  const double beta = rb * tc + rc;
  const double a2 = ra * ra - kappa * kappa;
  if (a2 >= -1e-9) return true;
  const double b1 = ra * beta;
  const double c0 = beta * beta - kappa * kappa * (1.0 + tc * tc);
  const double disc = b1 * b1 - a2 * c0;
  if (disc < 0.0) return false;
  const double root = std::sqrt(disc);
  const double s0 = (-b1 + root) / a2, s1 = (-b1 - root) / a2;  // a2 < 0: s0 <= s1
  if (ra * 0.5 * (s0 + s1) + beta <= 0.0) return false;          // the antipodal nappe
  lo = std::max(lo, static_cast<int>(std::floor(((s0 + 1.0) * n - 1.0) * 0.5)) - 1);
  hi = std::min(hi, static_cast<int>(std::ceil(((s1 + 1.0) * n - 1.0) * 0.5)) + 1);
  return lo <= hi;
}

LevelJob level_job(const Input& in, CubeMap& out, double kappa) {
  LevelJob job;
  job.in = &in;
  job.out = &out;
  job.kappa = kappa;
  job.cap_angle = std::acos(kappa);
  job.sin2_cap = 1.0 - kappa * kappa;
  job.d_max = static_cast<float>(1.0 - kappa);
  return job;
}

}  // namespace shadelab::lobe_sum
