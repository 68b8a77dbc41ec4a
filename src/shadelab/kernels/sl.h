// shadelab kernels, C++ side: the types and functions of the shading dialect in which every formula that a
// shader also needs (BRDF eval, Fresnel, microfacet terms, game-shading pieces) is written ONCE, in the
// `*.sl` files of this folder. The same text compiles as C++ (here, in double precision, inside namespace
// shadelab::kernel; kernels.h includes it) and, through the shader exporter's token map, as GLSL 4.50,
// GLSL ES 3.00 and HLSL (in single precision). docs/design.md ("One source for C++ and shaders") gives the
// reasons; docs/shaders.md the dialect's rules, in short:
//
// - types: real (double here, float in shaders), int, bool, vec3 (directions), rgb (colours; vec3/float3 in
//   shaders), and structs of those. Colours and directions are different types in C++, so mixing them is a
//   compile error here even though the shading languages would allow it.
// - constructors: vec3(x, y, z), vec3(s) (all three = s), rgb(r, g, b), rgb(s); no other initialisers;
//   conversions int(x) (truncation) and real(i).
// - operators: + - * / on vec3 and rgb component-wise and with real scalars, unary minus; [] component
//   access; .x .y .z on vec3 and .r .g .b on rgb; no swizzles.
// - functions: sqrt exp exp2 log log2 pow abs floor sin cos acos min max clamp mix atan2 erf, dot length normalize
//   cross on vec3; user functions are marked `inline` (removed in shaders), take parameters by value, have no
//   out-parameters, defaults, overloads, recursion or pointers.
// - literals: always with a decimal point for reals (GLSL ES has no implicit int -> float conversion);
//   no `const` on locals (GLSL ES requires constant initialisers there); constants at file scope are
//   `const real NAME = value;` or `const int NAME = value;`, and tables `const real NAME[N] = {a, b, ...};`
//   (one-dimensional: GLSL ES 3.00 has no arrays of arrays; the exporter writes GLSL's float[N](...)).
// - pow(x, y) only where x > 0 (GLSL leaves other cases undefined); every division is guarded where the
//   divisor can vanish, with the reason at the guard.
// Compiling every kernel as C++ (here) and in every shading language (the shader tests) enforces the
// subset from both sides.
#pragma once

#include <algorithm>
#include <cmath>

#include "shadelab/color/rgb.h"
#include "shadelab/core/vec.h"

namespace shadelab::kernel {

using real = double;

struct vec3 {
  real x = 0.0;
  real y = 0.0;
  real z = 0.0;
  constexpr vec3() = default;
  constexpr explicit vec3(real s) : x(s), y(s), z(s) {}
  constexpr vec3(real x_, real y_, real z_) : x(x_), y(y_), z(z_) {}
  constexpr vec3(const Vec3& v) : x(v.x), y(v.y), z(v.z) {}  // NOLINT: the C++ boundary converts freely
  constexpr operator Vec3() const { return {x, y, z}; }       // NOLINT
  constexpr real operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

struct rgb {
  real r = 0.0;
  real g = 0.0;
  real b = 0.0;
  constexpr rgb() = default;
  constexpr explicit rgb(real s) : r(s), g(s), b(s) {}
  constexpr rgb(real r_, real g_, real b_) : r(r_), g(g_), b(b_) {}
  constexpr rgb(const Rgb& c) : r(c.r), g(c.g), b(c.b) {}  // NOLINT
  constexpr operator Rgb() const { return {r, g, b}; }     // NOLINT
  constexpr real operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
};

// Component-wise arithmetic, as in GLSL.
#define SHADELAB_SL_OPERATORS(T, A, B, C)                                                                 \
  constexpr T operator+(const T& u, const T& v) { return {u.A + v.A, u.B + v.B, u.C + v.C}; }            \
  constexpr T operator-(const T& u, const T& v) { return {u.A - v.A, u.B - v.B, u.C - v.C}; }            \
  constexpr T operator*(const T& u, const T& v) { return {u.A * v.A, u.B * v.B, u.C * v.C}; }            \
  constexpr T operator/(const T& u, const T& v) { return {u.A / v.A, u.B / v.B, u.C / v.C}; }            \
  constexpr T operator-(const T& u) { return {-u.A, -u.B, -u.C}; }                                      \
  constexpr T operator*(const T& u, real s) { return {u.A * s, u.B * s, u.C * s}; }                      \
  constexpr T operator*(real s, const T& u) { return {s * u.A, s * u.B, s * u.C}; }                      \
  constexpr T operator/(const T& u, real s) { return {u.A / s, u.B / s, u.C / s}; }                      \
  constexpr T operator+(const T& u, real s) { return {u.A + s, u.B + s, u.C + s}; }                      \
  constexpr T operator-(const T& u, real s) { return {u.A - s, u.B - s, u.C - s}; }                      \
  constexpr T operator+(real s, const T& u) { return {s + u.A, s + u.B, s + u.C}; }                      \
  constexpr T operator-(real s, const T& u) { return {s - u.A, s - u.B, s - u.C}; }                      \
  constexpr T& operator+=(T& u, const T& v) { return u = u + v; }                                       \
  constexpr T& operator-=(T& u, const T& v) { return u = u - v; }                                       \
  constexpr T& operator*=(T& u, const T& v) { return u = u * v; }                                       \
  constexpr T& operator*=(T& u, real s) { return u = u * s; }                                           \
  constexpr T& operator/=(T& u, real s) { return u = u / s; }
SHADELAB_SL_OPERATORS(vec3, x, y, z)
SHADELAB_SL_OPERATORS(rgb, r, g, b)
#undef SHADELAB_SL_OPERATORS

// Scalar functions with the shading languages' names (GLSL 4.50 section 8; HLSL intrinsics).
using std::abs;
using std::acos;
using std::cos;
using std::erf;  // GLSL/HLSL have none: the exporter supplies one with its stated error (docs/shaders.md)
using std::exp;
using std::exp2;
using std::floor;
using std::log;
using std::log2;
using std::pow;
using std::sin;
using std::sqrt;
// GLSL max/min/clamp/mix (section 8.3): min(max(x, lo), hi) and x (1 - a) + y a.
constexpr real max(real a, real b) { return a < b ? b : a; }
constexpr real min(real a, real b) { return b < a ? b : a; }
constexpr real clamp(real x, real lo, real hi) { return min(max(x, lo), hi); }
// The integer forms (GLSL's genIType; HLSL's int overloads): a call that mixes int and real does not compile,
// as GLSL ES requires.
constexpr int max(int a, int b) { return a < b ? b : a; }
constexpr int min(int a, int b) { return b < a ? b : a; }
constexpr int clamp(int x, int lo, int hi) { return min(max(x, lo), hi); }
constexpr real mix(real x, real y, real a) { return x * (1.0 - a) + y * a; }
constexpr rgb mix(const rgb& x, const rgb& y, real a) { return x * (1.0 - a) + y * a; }
inline real atan2(real y, real x) { return std::atan2(y, x); }  // GLSL atan(y, x)

// Geometry (GLSL section 8.5).
constexpr real dot(const vec3& u, const vec3& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }
constexpr vec3 cross(const vec3& u, const vec3& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}
inline real length(const vec3& u) { return std::sqrt(dot(u, u)); }
inline vec3 normalize(const vec3& u) { return u / length(u); }

}  // namespace shadelab::kernel
