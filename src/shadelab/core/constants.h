// shadelab core constants. pi and its relatives, spelled once.
#pragma once

#include <numbers>

namespace shadelab {

inline constexpr double pi = std::numbers::pi;        // 3.14159...
inline constexpr double two_pi = 2.0 * std::numbers::pi;
inline constexpr double four_pi = 4.0 * std::numbers::pi;
inline constexpr double inv_pi = std::numbers::inv_pi;  // 1/pi: the Lambertian BRDF of albedo 1
inline constexpr double inv_two_pi = 0.5 * std::numbers::inv_pi;
inline constexpr double inv_four_pi = 0.25 * std::numbers::inv_pi;

inline constexpr double deg_to_rad(double deg) { return deg * (pi / 180.0); }
inline constexpr double rad_to_deg(double rad) { return rad * (180.0 / pi); }

}  // namespace shadelab
