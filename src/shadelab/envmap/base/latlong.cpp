#include "shadelab/envmap/base/latlong.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "shadelab/core/constants.h"

namespace shadelab {

Vec3 latlong_direction(double u, double v) {
  const double theta = pi * v;
  const double phi = two_pi * (u - 0.5);
  const double st = std::sin(theta);
  return {st * std::cos(phi), std::cos(theta), st * std::sin(phi)};
}

Vec2 latlong_uv(const Vec3& d) {
  const double len = length(d);
  const double y = std::clamp(d.y / len, -1.0, 1.0);
  return {0.5 + std::atan2(d.z, d.x) * inv_two_pi, std::acos(y) * inv_pi};
}

double latlong_texel_solid_angle(int y, int width, int height) {
  // (2 pi / W) (cos theta0 - cos theta1): the ring between two polar angles, split into W texels.
  return two_pi / width * (std::cos(pi * y / height) - std::cos(pi * (y + 1) / height));
}

Rgb sample_latlong(const Image& map, const Vec3& dir) {
  const Vec2 uv = latlong_uv(dir);
  const double fx = uv.x * map.width - 0.5;
  const double fy = std::clamp(uv.y * map.height - 0.5, 0.0, map.height - 1.0);
  const double flx = std::floor(fx);
  const int x0 = static_cast<int>(flx);
  const double ax = fx - flx;
  const int y0 = std::min(static_cast<int>(fy), map.height - 1);
  const int y1 = std::min(y0 + 1, map.height - 1);
  const double ay = fy - y0;
  auto wrap = [&](int x) { return ((x % map.width) + map.width) % map.width; };
  const int xa = wrap(x0);
  const int xb = wrap(x0 + 1);
  return (map.at(xa, y0) * (1 - ax) + map.at(xb, y0) * ax) * (1 - ay) +
         (map.at(xa, y1) * (1 - ax) + map.at(xb, y1) * ax) * ay;
}

namespace {

CubeMap latlong_to_cube_bilinear(const Image& latlong, int size, int ss) {
  CubeMap cube(size);
  const double inv = 1.0 / (size * ss);
  tbb::parallel_for(0, 6 * size, [&](int row) {
    const int f = row / size;
    const int y = row % size;
    for (int x = 0; x < size; ++x) {
      Rgb sum;
      for (int j = 0; j < ss; ++j) {
        for (int i = 0; i < ss; ++i) {
          sum += sample_latlong(latlong, cube_direction(f, (x * ss + i + 0.5) * inv, (y * ss + j + 0.5) * inv));
        }
      }
      cube.set(f, x, y, sum / (ss * ss));
    }
  });
  return cube;
}

// The lat-long map as a function on the sphere: constant on each texel. In the equal-area coordinates
// (phi, u = cos theta) the solid angle is dphi du and texels are rectangles; F_j(u), the integral of L
// over u' in [-1, u] in column j, is piecewise linear in u. C holds F_j at the row boundaries.
struct Columns {
  int w = 0, h = 0;
  double dphi = 0.0;
  std::vector<double> u;           // h + 1 row boundaries cos(pi k / h), decreasing from 1 to -1
  std::vector<double> c;           // F_j(u_k): index (j (h + 1) + k) * 3 + channel
  std::vector<double> l;           // L: index (j h + i) * 3 + channel
  std::vector<double> cosb, sinb;  // cos, sin of the column boundaries phi_b = -pi + b dphi, b in [0, w)

  double col_total(int j, int ch) const { return c[(static_cast<std::size_t>(j) * static_cast<std::size_t>(h + 1)) * 3 + static_cast<std::size_t>(ch)]; }
};

Columns make_columns(const Image& ll) {
  Columns g;
  g.w = ll.width;
  g.h = ll.height;
  g.dphi = two_pi / g.w;
  const auto w = static_cast<std::size_t>(g.w);
  const auto h = static_cast<std::size_t>(g.h);
  g.u.resize(h + 1);
  for (std::size_t k = 0; k <= h; ++k) g.u[k] = std::cos(pi * static_cast<double>(k) / g.h);
  g.u[0] = 1.0;
  g.u[h] = -1.0;
  g.cosb.resize(w);
  g.sinb.resize(w);
  for (std::size_t b = 0; b < w; ++b) {
    const double phi = -pi + static_cast<double>(b) * g.dphi;
    g.cosb[b] = std::cos(phi);
    g.sinb[b] = std::sin(phi);
  }
  g.c.assign(w * (h + 1) * 3, 0.0);
  g.l.assign(w * h * 3, 0.0);
  tbb::parallel_for(std::size_t{0}, w, [&](std::size_t j) {
    double acc[3] = {0.0, 0.0, 0.0};
    for (std::size_t k = h; k-- > 0;) {  // from the bottom (u = -1) up
      const Rgb v = ll.at(static_cast<int>(j), static_cast<int>(k));
      const double du = g.u[k] - g.u[k + 1];
      for (int ch = 0; ch < 3; ++ch) {
        g.l[(j * h + k) * 3 + static_cast<std::size_t>(ch)] = v[ch];
        acc[ch] += v[ch] * du;
        g.c[(j * (h + 1) + k) * 3 + static_cast<std::size_t>(ch)] = acc[ch];
      }
    }
  });
  return g;
}

// asin for |x| <= 0.1 by its Taylor series to x^11 (the next term, 231/13312 x^13, is below 2e-15 x).
double asin_small(double x) {
  const double x2 = x * x;
  return x * (1.0 + x2 * (1.0 / 6.0 + x2 * (3.0 / 40.0 + x2 * (5.0 / 112.0 + x2 * (35.0 / 1152.0 + x2 * (63.0 / 2816.0))))));
}

struct Breakpoint {
  double key;  // position along the arc: p . a, decreasing from 1 at a (arcs are shorter than pi)
  Vec3 p;      // the point (unit)
};

// A grid vertex with its azimuth, computed once per vertex.
struct Vertex {
  Vec3 p;
  double phi;
};

double wrap_pi(double d) { return d > pi ? d - two_pi : (d < -pi ? d + two_pi : d); }

// The signed angle from azimuth (c0, s0) to (c1, s1) (cosine, sine pairs), for |angle| < pi.
double angle_between(double c0, double s0, double c1, double s1) {
  const double sn = c0 * s1 - s0 * c1;
  const double cs = c0 * c1 + s0 * s1;
  return (std::abs(sn) < 0.1 && cs > 0.0) ? asin_small(sn) : std::atan2(sn, cs);
}

// J = integral of F(phi, u(phi)) dphi along the great-circle arc from a to b (angle < pi), per channel:
// the line integral whose sum around a cube texel gives its flux (Green's theorem in the (phi, u) plane).
// On the arc's great circle (unit normal m = a x b / |a x b|, m_y != 0), cot(theta) = g(phi) =
// -(m_x cos phi + m_z sin phi) / m_y and u = g / sqrt(1 + g^2), whose antiderivative in phi is
// G(phi) = asin(sgn(m_y) (m_z cos phi - m_x sin phi)) (differentiate to check). Between consecutive
// breakpoints (column boundaries and row crossings) the lat-long texel (j, i) is fixed and
// F = C_j(i + 1) + L_ij (u - u_{i+1}), so each piece integrates in closed form:
//   (C_j(i + 1) - L_ij u_{i+1}) dphi + L_ij dG.
// Meridian arcs (m_y = 0) have dphi = 0 and give 0.
std::array<double, 3> arc_integral(const Columns& g, const Vertex& va, const Vertex& vb, std::vector<Breakpoint>& pts) {
  std::array<double, 3> out{0.0, 0.0, 0.0};
  const Vec3& a = va.p;
  const Vec3& b = vb.p;
  Vec3 m = cross(a, b);
  if (m.y == 0.0) return out;
  m = m / length(m);
  const double sgn = m.y > 0.0 ? 1.0 : -1.0;
  const double phi_a = va.phi;
  const double phi_b = phi_a + wrap_pi(vb.phi - phi_a);
  pts.clear();
  pts.push_back({1.0, a});
  pts.push_back({dot(a, b), b});
  // Column boundaries strictly inside: the point of the great circle at azimuth phi_k.
  const double lo = std::min(phi_a, phi_b), hi = std::max(phi_a, phi_b);
  for (long k = static_cast<long>(std::floor((lo + pi) / g.dphi)) + 1; -pi + static_cast<double>(k) * g.dphi < hi; ++k) {
    const auto idx = static_cast<std::size_t>(((k % g.w) + g.w) % g.w);
    const double c = g.cosb[idx], s = g.sinb[idx];
    const double cot = -(m.x * c + m.z * s) / m.y;
    const double inv = 1.0 / std::sqrt(1.0 + cot * cot);
    const Vec3 p{c * inv, cot * inv, s * inv};
    pts.push_back({dot(p, a), p});
  }
  // Row crossings: the points of the great circle with y = u_k, kept if strictly between a and b. The
  // range of u over the arc: its endpoints, or the circle's extreme +-sqrt(m_x^2 + m_z^2) where dy/dt,
  // (m x p)_y along the arc, changes sign.
  const double ta = m.z * a.x - m.x * a.z, tb = m.z * b.x - m.x * b.z;  // (m x p)_y at a and b
  const double rho2 = m.x * m.x + m.z * m.z;
  double u_max = std::max(a.y, b.y), u_min = std::min(a.y, b.y);
  if (ta > 0.0 && tb < 0.0) u_max = std::sqrt(rho2);
  if (ta < 0.0 && tb > 0.0) u_min = -std::sqrt(rho2);
  auto row_of = [&](double u) { return std::clamp(static_cast<int>(std::acos(std::clamp(u, -1.0, 1.0)) * g.h / pi), 0, g.h - 1); };
  const int k_first = row_of(u_max), k_last = row_of(u_min) + 1;
  if (k_last > k_first + 1 && rho2 > 0.0) {
    const double rho = std::sqrt(rho2);
    for (int k = k_first + 1; k < k_last; ++k) {
      const double uk = g.u[static_cast<std::size_t>(k)];
      if (!(uk > u_min && uk < u_max)) continue;
      // (x, z) on the line m_x x + m_z z = -m_y u_k at distance sqrt(1 - u_k^2) from the axis.
      const double along = -m.y * uk / rho;
      const double across2 = (1.0 - uk * uk) - along * along;
      if (across2 < 0.0) continue;
      const double across = std::sqrt(across2);
      for (const double sd : {across, -across}) {
        const Vec3 p{(along * m.x - sd * m.z) / rho, uk, (along * m.z + sd * m.x) / rho};
        if (dot(cross(a, p), m) > 0.0 && dot(cross(p, b), m) > 0.0) pts.push_back({dot(p, a), p});
      }
    }
  }
  std::sort(pts.begin() + 1, pts.end(), [](const Breakpoint& x, const Breakpoint& y) { return x.key > y.key; });
  // G at each breakpoint as (sin G, cos G): sin G = sgn (m_z cos phi - m_x sin phi), cos G =
  // sqrt(m_y^2 + (m_x cos phi + m_z sin phi)^2) (1 - sin^2 G written without cancellation).
  double phi = phi_a;
  double c0 = 0.0, s0 = 0.0, sg0 = 0.0, cg0 = 0.0;
  auto azimuth = [&](const Vec3& p, double& c, double& s, double& sg, double& cg) {
    const double inv_rho = 1.0 / std::sqrt(p.x * p.x + p.z * p.z);
    c = p.x * inv_rho;
    s = p.z * inv_rho;
    sg = sgn * (m.z * c - m.x * s);
    const double q = m.x * c + m.z * s;
    cg = std::sqrt(m.y * m.y + q * q);
  };
  azimuth(pts[0].p, c0, s0, sg0, cg0);
  int row = row_of(0.5 * (pts[0].p.y + pts[1].p.y));
  for (std::size_t n = 1; n < pts.size(); ++n) {
    double c1 = 0.0, s1 = 0.0, sg1 = 0.0, cg1 = 0.0;
    azimuth(pts[n].p, c1, s1, sg1, cg1);
    const double dphi = angle_between(c0, s0, c1, s1);
    if (dphi != 0.0) {
      const double dg = angle_between(cg0, sg0, cg1, sg1);  // G1 - G0 (angles in (-pi/2, pi/2))
      int col = static_cast<int>(std::floor((phi + 0.5 * dphi + pi) / g.dphi));
      col = col < 0 ? col + g.w : (col >= g.w ? col - g.w : col);
      // The piece lies in one row; the mean of its end heights is inside that row's closed range.
      const double u_mid = 0.5 * (pts[n].p.y + pts[n - 1].p.y);
      while (row + 1 < g.h && u_mid < g.u[static_cast<std::size_t>(row + 1)]) ++row;
      while (row > 0 && u_mid > g.u[static_cast<std::size_t>(row)]) --row;
      const std::size_t ci = (static_cast<std::size_t>(col) * static_cast<std::size_t>(g.h + 1) + static_cast<std::size_t>(row + 1)) * 3;
      const std::size_t li = (static_cast<std::size_t>(col) * static_cast<std::size_t>(g.h) + static_cast<std::size_t>(row)) * 3;
      const double u_below = g.u[static_cast<std::size_t>(row + 1)];
      for (std::size_t ch = 0; ch < 3; ++ch) out[ch] += (g.c[ci + ch] - g.l[li + ch] * u_below) * dphi + g.l[li + ch] * dg;
      phi += dphi;
    }
    c0 = c1;
    s0 = s1;
    sg0 = sg1;
    cg0 = cg1;
  }
  return out;
}

// The integral of the column totals F_j(1) over phi in [phi0, phi1]: the flux term of the north pole.
double pole_integral(const Columns& g, double phi0, double phi1, int ch) {
  double sum = 0.0;
  for (int j = 0; j < g.w; ++j) {
    const double a = std::max(phi0, -pi + j * g.dphi);
    const double b = std::min(phi1, -pi + (j + 1) * g.dphi);
    if (b > a) sum += g.col_total(j, ch) * (b - a);
  }
  return sum;
}

}  // namespace

// Exact area-weighted resampling: each cube texel is (1 / its solid angle) x the integral of the
// piecewise-constant lat-long map over the texel, so the flux of every lat-long texel lands exactly in
// the cube texels it overlaps, in proportion to the overlap. The integral over a texel R is, by Green's
// theorem in the equal-area plane (phi, u) where dOmega = dphi du,
//   flux(R) = integral over R of dF/du dphi du = (sign) sum over its four edges of integral F dphi,
// each edge an arc of a great circle (arc_integral), plus, for the texels touching the north pole
// (where the (phi, u) chart has the edge u = 1), the integral of the column totals over their azimuths.
CubeMap latlong_to_cube(const Image& latlong, int size, int supersample) {
  if (supersample > 0) return latlong_to_cube_bilinear(latlong, size, supersample);
  const Columns g = make_columns(latlong);
  const int n = size;
  const auto np1 = static_cast<std::size_t>(n + 1);
  const auto nn = static_cast<std::size_t>(n);
  // Edge integrals: horizontal edges (x, y) -> (x + 1, y) and vertical edges (x, y) -> (x, y + 1), where
  // vertex (x, y) is at face coordinates (x / N, y / N).
  std::vector<std::array<double, 3>> horizontal(6 * np1 * nn), vertical(6 * np1 * nn);
  std::vector<Vertex> vertices(6 * np1 * np1);
  tbb::parallel_for(0, 6 * (n + 1), [&](int row) {
    const int f = row / (n + 1);
    const int y = row % (n + 1);
    for (int x = 0; x <= n; ++x) {
      const Vec3 p = cube_direction(f, static_cast<double>(x) / n, static_cast<double>(y) / n);
      vertices[(static_cast<std::size_t>(f) * np1 + static_cast<std::size_t>(y)) * np1 + static_cast<std::size_t>(x)] = {p, std::atan2(p.z, p.x)};
    }
  });
  auto vertex = [&](int f, int x, int y) -> const Vertex& {
    return vertices[(static_cast<std::size_t>(f) * np1 + static_cast<std::size_t>(y)) * np1 + static_cast<std::size_t>(x)];
  };
  tbb::parallel_for(0, 6 * 2 * (n + 1), [&](int line) {
    const int f = line / (2 * (n + 1));
    const int r = line % (2 * (n + 1));
    std::vector<Breakpoint> pts;
    pts.reserve(16);
    if (r <= n) {  // the horizontal line y = r
      for (int x = 0; x < n; ++x)
        horizontal[(static_cast<std::size_t>(f) * np1 + static_cast<std::size_t>(r)) * nn + static_cast<std::size_t>(x)] =
            arc_integral(g, vertex(f, x, r), vertex(f, x + 1, r), pts);
    } else {  // the vertical line x = r - n - 1
      const int x = r - n - 1;
      for (int y = 0; y < n; ++y)
        vertical[(static_cast<std::size_t>(f) * np1 + static_cast<std::size_t>(x)) * nn + static_cast<std::size_t>(y)] =
            arc_integral(g, vertex(f, x, y), vertex(f, x, y + 1), pts);
    }
  });
  // Orientation of each face's (s, t) chart against the (phi, u) chart: the sign of the Jacobian of
  // (s, t) -> (phi, u) at an off-centre point (the same over the whole face).
  double orient[6];
  for (int f = 0; f < 6; ++f) {
    const double s = 0.7, t = 0.6, h = 1e-4;
    auto pu = [&](double ss, double tt) {
      const Vec3 d = cube_direction(f, ss, tt);
      return Vec2{std::atan2(d.z, d.x), d.y};
    };
    const Vec2 p0 = pu(s, t), ps = pu(s + h, t), pt = pu(s, t + h);
    const double det = (ps.x - p0.x) * (pt.y - p0.y) - (ps.y - p0.y) * (pt.x - p0.x);
    // A walk (s0,t0) -> (s1,t0) -> (s1,t1) -> (s0,t1) is counter-clockwise in (phi, u) when det > 0; the
    // flux is the clockwise sum of the edge integrals.
    orient[f] = det > 0.0 ? -1.0 : 1.0;
  }
  const std::vector<double>& solid_angle = cube_face_solid_angles(n);
  CubeMap cube(n);
  tbb::parallel_for(0, 6 * n, [&](int row) {
    const int f = row / n;
    const int y = row % n;
    for (int x = 0; x < n; ++x) {
      const auto& bottom = horizontal[(static_cast<std::size_t>(f) * np1 + static_cast<std::size_t>(y)) * nn + static_cast<std::size_t>(x)];
      const auto& top = horizontal[(static_cast<std::size_t>(f) * np1 + static_cast<std::size_t>(y + 1)) * nn + static_cast<std::size_t>(x)];
      const auto& left = vertical[(static_cast<std::size_t>(f) * np1 + static_cast<std::size_t>(x)) * nn + static_cast<std::size_t>(y)];
      const auto& right = vertical[(static_cast<std::size_t>(f) * np1 + static_cast<std::size_t>(x + 1)) * nn + static_cast<std::size_t>(y)];
      // The north pole (+Y face centre) on the texel's boundary or inside: its azimuth range there.
      double pole0 = 0.0, pole1 = 0.0;
      if (f == static_cast<int>(CubeFace::pos_y) && 2 * x <= n && 2 * (x + 1) >= n && 2 * y <= n && 2 * (y + 1) >= n) {
        if (n % 2 == 1) {
          pole0 = -pi;
          pole1 = pi;
        } else {
          // +Y: direction (sc, 1, tc), phi = atan2(tc, sc); the texel covers one quadrant around the pole.
          const bool pos_s = 2 * x == n, pos_t = 2 * y == n;
          if (pos_s && pos_t) { pole0 = 0.0; pole1 = pi / 2; }
          else if (!pos_s && pos_t) { pole0 = pi / 2; pole1 = pi; }
          else if (!pos_s && !pos_t) { pole0 = -pi; pole1 = -pi / 2; }
          else { pole0 = -pi / 2; pole1 = 0.0; }
        }
      }
      const double omega = solid_angle[static_cast<std::size_t>(y) * nn + static_cast<std::size_t>(x)];
      Rgb v;
      for (int ch = 0; ch < 3; ++ch) {
        const auto c = static_cast<std::size_t>(ch);
        double flux = orient[f] * (bottom[c] + right[c] - top[c] - left[c]);
        if (pole1 > pole0) flux += pole_integral(g, pole0, pole1, ch);
        v[ch] = flux / omega;
      }
      cube.set(f, x, y, v);
    }
  });
  return cube;
}

Image cube_to_latlong(const CubeMap& cube, int width, int ss) {
  const int height = std::max(1, width / 2);
  Image out(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      Rgb sum;
      for (int j = 0; j < ss; ++j) {
        for (int i = 0; i < ss; ++i) {
          const double u = (x + (i + 0.5) / ss) / width;
          const double v = (y + (j + 0.5) / ss) / height;
          sum += cube.sample(latlong_direction(u, v));
        }
      }
      out.set(x, y, sum / (ss * ss));
    }
  }
  return out;
}

namespace {
struct Slot {
  int face, col, row;
  bool rotate180;
};
constexpr Slot horizontal_slots[6] = {{2, 1, 0, false}, {1, 0, 1, false}, {4, 1, 1, false},
                                      {0, 2, 1, false}, {5, 3, 1, false}, {3, 1, 2, false}};
constexpr Slot vertical_slots[6] = {{2, 1, 0, false}, {1, 0, 1, false}, {4, 1, 1, false},
                                    {0, 2, 1, false}, {3, 1, 2, false}, {5, 1, 3, true}};
}  // namespace

Result<CubeMap> cube_from_cross(const Image& cross) {
  const Slot* slots = nullptr;
  int n = 0;
  if (cross.width * 3 == cross.height * 4 && cross.width % 4 == 0) {
    slots = horizontal_slots;
    n = cross.width / 4;
  } else if (cross.width * 4 == cross.height * 3 && cross.width % 3 == 0) {
    slots = vertical_slots;
    n = cross.width / 3;
  } else {
    return make_error("cube cross: a " + std::to_string(cross.width) + " x " + std::to_string(cross.height) +
                      " image is neither a horizontal (4:3) nor a vertical (3:4) cross of square faces");
  }
  if (n == 0) return make_error("cube cross: the image is empty");
  CubeMap cube(n);
  for (int k = 0; k < 6; ++k) {
    const Slot& s = slots[k];
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const int sx = s.rotate180 ? n - 1 - x : x;
        const int sy = s.rotate180 ? n - 1 - y : y;
        cube.set(s.face, x, y, cross.at(s.col * n + sx, s.row * n + sy));
      }
    }
  }
  return cube;
}

Image cube_to_cross(const CubeMap& cube, CrossLayout layout) {
  const int n = cube.size;
  const Slot* slots = layout == CrossLayout::horizontal ? horizontal_slots : vertical_slots;
  Image out = layout == CrossLayout::horizontal ? Image(4 * n, 3 * n) : Image(3 * n, 4 * n);
  for (int k = 0; k < 6; ++k) {
    const Slot& s = slots[k];
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const int sx = s.rotate180 ? n - 1 - x : x;
        const int sy = s.rotate180 ? n - 1 - y : y;
        out.set(s.col * n + sx, s.row * n + sy, cube.texel(s.face, x, y));
      }
    }
  }
  return out;
}

}  // namespace shadelab
