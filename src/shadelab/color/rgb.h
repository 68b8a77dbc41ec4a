// shadelab linear RGB (Rec.709 primaries). Colours are linear inside shadelab; sRGB only at PNG I/O.
#pragma once

#include <algorithm>
#include <cmath>

namespace shadelab {

struct Rgb {
  double r = 0.0;
  double g = 0.0;
  double b = 0.0;

  static constexpr Rgb gray(double v) { return {v, v, v}; }
  constexpr double operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr double& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr double max_component() const { return std::max(r, std::max(g, b)); }
  constexpr double min_component() const { return std::min(r, std::min(g, b)); }
  constexpr double average() const { return (r + g + b) / 3.0; }
  constexpr bool is_black() const { return r == 0.0 && g == 0.0 && b == 0.0; }
};

constexpr Rgb operator+(const Rgb& a, const Rgb& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
constexpr Rgb operator-(const Rgb& a, const Rgb& b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
constexpr Rgb operator*(const Rgb& a, const Rgb& b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
constexpr Rgb operator*(const Rgb& a, double s) { return {a.r * s, a.g * s, a.b * s}; }
constexpr Rgb operator*(double s, const Rgb& a) { return a * s; }
constexpr Rgb operator/(const Rgb& a, double s) { return {a.r / s, a.g / s, a.b / s}; }
constexpr Rgb& operator+=(Rgb& a, const Rgb& b) { a = a + b; return a; }
constexpr Rgb& operator*=(Rgb& a, double s) { a = a * s; return a; }

inline bool is_finite(const Rgb& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

// Relative luminance of linear Rec.709 RGB (ITU-R BT.709-6, item 3.2).
constexpr double luminance(const Rgb& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

}  // namespace shadelab
