// shadelab sphere lights: a sphere of radius r0 and uniform radiance L seen from distance d > r0 subtends a
// cap of half-angle beta, sin(beta) = r0 / d (zoo article, comments: "sin beta = r0/r is always true").
//
//   fully above the horizon (theta <= pi/2 - beta):  E = pi L sin^2(beta) cos(theta)   (zoo article)
//   fully below (theta >= pi/2 + beta):              E = 0
//   straddling the horizon: the exact clipped-cap integral (Snyder, "Area Light Sources for Real-Time
//   Graphics", MSR-TR-96-11, 1996; as written in Lagarde & de Rousiers, "Moving Frostbite to PBR", 2014):
//     x = cot(beta), y = -x cot(theta), s = sin(theta) sqrt(1 - y^2)
//     E / L = (cos(theta) acos(y) - x s) sin^2(beta) + atan(s / x)
// theta is the angle between the surface normal and the direction to the sphere's centre. The formula is
// tested against numeric integration over the cap, including the straddling case.
// Point-light limit (r0 -> 0 at fixed I): I = pi L r0^2 (zoo article, comment of 2015-01-15).
#pragma once

#include "shadelab/color/rgb.h"
#include "shadelab/core/constants.h"
#include "shadelab/core/vec.h"

namespace shadelab {

// E / L for a cap of half-angle beta (given by sin_beta in (0, 1]) at angle theta (given by cos_theta).
double sphere_irradiance_factor(double cos_theta, double sin_beta);

struct SphereLight {
  Vec3 center;
  double radius = 1.0;
  Rgb radiance;  // W m^-2 sr^-1
};

// Irradiance at point p with unit normal n (0 inside the sphere, where no cap is defined).
Rgb sphere_light_irradiance(const SphereLight& light, const Vec3& p, const Vec3& n);

// The intensity of the equivalent point light: I = pi L r0^2.
constexpr Rgb sphere_light_intensity(const Rgb& radiance, double radius) {
  return radiance * (pi * radius * radius);
}

}  // namespace shadelab
