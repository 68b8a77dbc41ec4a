#include "shadelab/brdf/microfacet.h"

#include <algorithm>
#include <cmath>

namespace shadelab {

namespace {

// |(ax wo.x, ay wo.y, wo.z)|: the length of wo in the stretched configuration (Heitz 2018 section 3.2).
double stretched_length(const Vec3& wo, double ax, double ay) {
  return std::sqrt(ax * ax * wo.x * wo.x + ay * ay * wo.y * wo.y + wo.z * wo.z);
}

// The unit half vector of a pair, unflipped: the visible-normal samplers only produce h with wo.h > 0 and
// h.z > 0, so a pair whose sum points below the horizon has density 0 (unlike NDF sampling, see there).
bool visible_half_vector(const Vec3& wi, const Vec3& wo, Vec3& h) {
  const Vec3 s = wi + wo;
  const double len = length(s);
  if (!(len > 0.0)) return false;
  h = s / len;
  return h.z > 0.0 && dot(wo, h) > 0.0;
}

// Unstretch a stretched-configuration normal (Heitz 2018 section 3.4): normalize(ax x, ay y, max(0, z)).
Vec3 unstretch(const Vec3& n, double ax, double ay) {
  const Vec3 h{ax * n.x, ay * n.y, std::max(0.0, n.z)};
  const double len = length(h);
  return len > 0.0 ? h / len : Vec3{0.0, 0.0, 1.0};
}

// A point of the unit sphere with z uniform in [z_min, 1] and azimuth 2 pi u.y, plus the stretched wo:
// the (unnormalized) stretched half vector of the spherical-cap construction (Dupuy & Benyoub 2023 sec. 3).
Vec3 cap_point_plus(const Vec3& wo_s, Vec2 u, double z_min) {
  const double phi = two_pi * u.y;
  const double z = (1.0 - u.x) * (1.0 - z_min) + z_min;
  const double sin_theta = std::sqrt(std::clamp(1.0 - z * z, 0.0, 1.0));
  return Vec3{sin_theta * std::cos(phi), sin_theta * std::sin(phi), z} + wo_s;
}

Vec3 stretched_view(const Vec3& wo, double ax, double ay) { return normalize(Vec3{ax * wo.x, ay * wo.y, wo.z}); }

}  // namespace

Vec3 sample_ggx_ndf(Vec2 u, double ax, double ay) {
  const double r = std::sqrt(u.x / (1.0 - u.x));  // u.x < 1: finite
  const double phi = two_pi * u.y;
  return normalize(Vec3{ax * r * std::cos(phi), ay * r * std::sin(phi), 1.0});
}

double ggx_ndf_pdf(const Vec3& wi, const Vec3& wo, double ax, double ay) {
  // Reflection about h and about -h is the same map, so the flipped half vector (common.sl) is right here.
  const Vec3 h = half_vector(wi, wo);
  return reflect_jacobian_pdf(D_ggx_aniso(h, ax, ay) * h.z, wo, h);
}

Vec3 sample_ggx_vndf_heitz(const Vec3& wo, Vec2 u, double ax, double ay) {
  const Vec3 v = stretched_view(wo, ax, ay);
  // An orthonormal basis about v (T1 horizontal), with the special case of v = +Z.
  const double lensq = v.x * v.x + v.y * v.y;
  const Vec3 t1 = lensq > 0.0 ? Vec3{-v.y, v.x, 0.0} / std::sqrt(lensq) : Vec3{1.0, 0.0, 0.0};
  const Vec3 t2 = cross(v, t1);
  // A uniform point of the unit disk, its second coordinate warped so that the disk is the projection of the
  // visible hemisphere: the half disk behind v is squashed by (1 + v.z)/2.
  const double r = std::sqrt(u.x);
  const double phi = two_pi * u.y;
  const double p1 = r * std::cos(phi);
  double p2 = r * std::sin(phi);
  const double s = 0.5 * (1.0 + v.z);
  p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
  // Reproject onto the hemisphere about v and unstretch.
  const Vec3 n = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * v;
  return unstretch(n, ax, ay);
}

Vec3 sample_ggx_vndf_caps(const Vec3& wo, Vec2 u, double ax, double ay) {
  const Vec3 v = stretched_view(wo, ax, ay);
  return unstretch(cap_point_plus(v, u, -v.z), ax, ay);
}

double ggx_vndf_pdf(const Vec3& wi, const Vec3& wo, double ax, double ay) {
  Vec3 h;
  if (wo.z <= 0.0 || !visible_half_vector(wi, wo, h)) return 0.0;
  return D_ggx_aniso(h, ax, ay) / (2.0 * (wo.z + stretched_length(wo, ax, ay)));
}

double ggx_vndf_bounded_k(const Vec3& wo, double ax, double ay) {
  const double a = std::clamp(std::min(ax, ay), 0.0, 1.0);
  const double s = 1.0 + std::sqrt(wo.x * wo.x + wo.y * wo.y);
  const double a2 = a * a;
  const double s2 = s * s;
  return (1.0 - a2) * s2 / (s2 + a2 * wo.z * wo.z);
}

Vec3 sample_ggx_vndf_bounded(const Vec3& wo, Vec2 u, double ax, double ay) {
  const Vec3 v = stretched_view(wo, ax, ay);
  const double b = ggx_vndf_bounded_k(wo, ax, ay) * v.z;
  return unstretch(cap_point_plus(v, u, -b), ax, ay);
}

double ggx_vndf_bounded_pdf(const Vec3& wi, const Vec3& wo, double ax, double ay) {
  Vec3 h;
  if (wo.z <= 0.0 || !visible_half_vector(wi, wo, h)) return 0.0;
  const double k = ggx_vndf_bounded_k(wo, ax, ay);
  // The cap point c of h: the stretched half direction d meets the unit sphere about v at t = 2 d.v, and
  // c = t d - v; it was sampled only if c.z >= -b.
  const Vec3 v = stretched_view(wo, ax, ay);
  const Vec3 d = normalize(Vec3{h.x / ax, h.y / ay, h.z});
  const double c_z = 2.0 * dot(d, v) * d.z - v.z;
  if (c_z < -k * v.z) return 0.0;
  return D_ggx_aniso(h, ax, ay) / (2.0 * (k * wo.z + stretched_length(wo, ax, ay)));
}

}  // namespace shadelab
