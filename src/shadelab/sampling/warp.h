// shadelab warps: maps from the unit square to directions, each in threes: sample_x(u) -> direction,
// x_pdf(direction) -> density per unit solid angle, invert_x(direction) -> u (so that
// invert_x(sample_x(u)) == u). All directions are in the local frame about +Z.
//
// Sources: Pharr, Jakob, Humphreys, "Physically Based Rendering", 4th ed., sections A.5 (hemisphere,
// cosine, sphere, cone) and the standard power-cosine lobe pdf (n+1)/(2 pi) cos^n (Lafortune & Willems 1994).
#pragma once

#include "shadelab/core/vec.h"

namespace shadelab {

// Uniform over the upper hemisphere (z >= 0): pdf = 1 / (2 pi).
Vec3 sample_uniform_hemisphere(Vec2 u);
double uniform_hemisphere_pdf(const Vec3& w);
Vec2 invert_uniform_hemisphere(const Vec3& w);

// Cosine-weighted upper hemisphere: pdf = cos(theta) / pi.
Vec3 sample_cosine_hemisphere(Vec2 u);
double cosine_hemisphere_pdf(const Vec3& w);
Vec2 invert_cosine_hemisphere(const Vec3& w);

// Power-cosine lobe about +Z, exponent n >= 0: pdf = (n + 1) / (2 pi) cos^n(theta) on the upper hemisphere.
Vec3 sample_power_cosine(Vec2 u, double n);
double power_cosine_pdf(const Vec3& w, double n);
Vec2 invert_power_cosine(const Vec3& w, double n);

// Uniform over the whole sphere: pdf = 1 / (4 pi).
Vec3 sample_uniform_sphere(Vec2 u);
double uniform_sphere_pdf(const Vec3& w);
Vec2 invert_uniform_sphere(const Vec3& w);

// Uniform over the spherical cap of directions within the half-angle whose cosine is cos_max (about +Z):
// pdf = 1 / (2 pi (1 - cos_max)). Used for sphere lights.
Vec3 sample_spherical_cap(Vec2 u, double cos_max);
double spherical_cap_pdf(const Vec3& w, double cos_max);
Vec2 invert_spherical_cap(const Vec3& w, double cos_max);

// phi in [0, 2 pi) of a direction about +Z.
double azimuth(const Vec3& w);

}  // namespace shadelab
