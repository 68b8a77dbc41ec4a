// shadelab vectors: plain double-precision value types for directions and points.
//
// Conventions (docs/conventions.md): the local shading frame has the normal on +Z, the tangent on +X and
// the bitangent on +Y; cos_theta(w) is therefore w.z. Directions passed to BRDFs are unit length.
#pragma once

#include <cmath>

namespace shadelab {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

constexpr Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(const Vec3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator*(double s, const Vec3& a) { return a * s; }
constexpr Vec3 operator/(const Vec3& a, double s) { return {a.x / s, a.y / s, a.z / s}; }
constexpr Vec3& operator+=(Vec3& a, const Vec3& b) { a = a + b; return a; }

constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(const Vec3& a) { return a / length(a); }
inline bool is_finite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

// Mirror reflection of w about the unit axis n (both pointing away from the surface): 2 (w.n) n - w.
constexpr Vec3 reflect(const Vec3& w, const Vec3& n) { return 2.0 * dot(w, n) * n - w; }

// Local-frame trigonometry (normal = +Z).
constexpr double cos_theta(const Vec3& w) { return w.z; }
constexpr bool same_hemisphere(const Vec3& a, const Vec3& b) { return a.z * b.z > 0.0; }

// Unit vector from spherical coordinates about +Z.
inline Vec3 spherical_direction(double sin_theta, double cos_theta_, double phi) {
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta_};
}

}  // namespace shadelab
