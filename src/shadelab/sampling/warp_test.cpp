// Tests of sampling/warp.h. Every warp is checked the same way: samples are unit vectors inside the
// support; the pdf function equals the documented density and the numerical Jacobian of the sample map;
// invert undoes sample; the pdf integrates to one over the sphere (deterministic midpoint quadrature); and
// a histogram of samples drawn with a fixed seed passes a Pearson chi-square test against the pdf.
#include "shadelab/sampling/warp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "shadelab/core/constants.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

struct WarpCase {
  std::string name;
  std::function<Vec3(Vec2)> sample;
  std::function<double(const Vec3&)> pdf;
  std::function<Vec2(const Vec3&)> invert;
  double z_min = 0.0;                        // the support is cos(theta) in [z_min, 1]
  std::function<double(double)> density;     // the documented pdf as a function of cos(theta)
  std::function<double(double)> z_of_t;      // maps t in [0,1] to histogram bin edges in cos(theta)
};

std::vector<WarpCase> warp_cases() {
  std::vector<WarpCase> cases;
  const auto linear_bins = [](double z_min) {
    return [z_min](double t) { return z_min + t * (1.0 - z_min); };
  };
  cases.push_back({"uniform_hemisphere", sample_uniform_hemisphere, uniform_hemisphere_pdf,
                   invert_uniform_hemisphere, 0.0, [](double) { return inv_two_pi; }, linear_bins(0.0)});
  cases.push_back({"cosine_hemisphere", sample_cosine_hemisphere, cosine_hemisphere_pdf,
                   invert_cosine_hemisphere, 0.0, [](double z) { return z * inv_pi; },
                   [](double t) { return std::sqrt(t); }});
  for (double n : {0.0, 1.0, 5.0, 20.0, 100.0}) {
    cases.push_back({"power_cosine n=" + std::to_string(n), [n](Vec2 u) { return sample_power_cosine(u, n); },
                     [n](const Vec3& w) { return power_cosine_pdf(w, n); },
                     [n](const Vec3& w) { return invert_power_cosine(w, n); }, 0.0,
                     [n](double z) { return (n + 1.0) * inv_two_pi * std::pow(z, n); },
                     // bins of equal probability under the documented density: CDF(z) = z^(n+1)
                     [n](double t) { return std::pow(t, 1.0 / (n + 1.0)); }});
  }
  cases.push_back({"uniform_sphere", sample_uniform_sphere, uniform_sphere_pdf, invert_uniform_sphere, -1.0,
                   [](double) { return inv_four_pi; }, linear_bins(-1.0)});
  for (double c : {-0.5, 0.0, 0.5, 0.95}) {
    cases.push_back({"spherical_cap cos_max=" + std::to_string(c),
                     [c](Vec2 u) { return sample_spherical_cap(u, c); },
                     [c](const Vec3& w) { return spherical_cap_pdf(w, c); },
                     [c](const Vec3& w) { return invert_spherical_cap(w, c); }, c,
                     [c](double) { return 1.0 / (two_pi * (1.0 - c)); }, linear_bins(c)});
  }
  return cases;
}

// A direction from cos(theta) and phi.
Vec3 direction(double z, double phi) {
  return spherical_direction(std::sqrt(std::max(0.0, 1.0 - z * z)), z, phi);
}

// The chi-square 0.999 quantile for k degrees of freedom (Wilson & Hilferty 1931 cube-root approximation,
// within 0.5 % of the exact quantile for k >= 30).
double chi2_quantile_999(int k) {
  const double z = 3.0902;  // standard normal 0.999 quantile
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

TEST(Warp, SamplesAreUnitVectorsInTheSupport) {
  const double one_minus = std::nextafter(1.0, 0.0);
  for (const auto& c : warp_cases()) {
    std::vector<double> us{0.0, one_minus};
    for (int i = 0; i < 64; ++i) us.push_back((i + 0.5) / 64.0);
    for (double ux : us) {
      for (double uy : us) {
        const Vec3 w = c.sample({ux, uy});
        ASSERT_TRUE(is_finite(w)) << c.name << " u = " << ux << ", " << uy;
        EXPECT_NEAR(length(w), 1.0, 1e-12) << c.name << " u = " << ux << ", " << uy;
        EXPECT_GE(w.z, c.z_min - 1e-12) << c.name << " u = " << ux << ", " << uy;
      }
    }
  }
}

TEST(Warp, PdfIsTheDocumentedDensity) {
  for (const auto& c : warp_cases()) {
    // On samples.
    for (int i = 0; i < 32; ++i) {
      for (int j = 0; j < 8; ++j) {
        const Vec3 w = c.sample({(i + 0.5) / 32.0, (j + 0.5) / 8.0});
        const double expected = c.density(w.z);
        EXPECT_GT(c.pdf(w), 0.0) << c.name;
        EXPECT_NEAR(c.pdf(w), expected, 1e-12 * expected) << c.name << " z = " << w.z;
      }
    }
    // On directions anywhere: the documented density inside the support, zero outside.
    for (int i = 0; i <= 40; ++i) {
      const double z = -1.0 + 2.0 * i / 40.0;
      const Vec3 w = direction(z, 1.234);
      if (z < c.z_min) {
        EXPECT_EQ(c.pdf(w), 0.0) << c.name << " z = " << z;
      } else if (z > c.z_min) {
        EXPECT_NEAR(c.pdf(w), c.density(w.z), 1e-12 * c.density(w.z)) << c.name << " z = " << z;
      }
    }
  }
}

TEST(Warp, PdfEqualsInverseJacobianOfTheSampleMap) {
  // The solid angle swept by du_x du_y is |dw/du_x x dw/du_y| du_x du_y, so pdf(w) = 1 / that area factor.
  // Central differences with h = 1e-6 are accurate to ~1e-8 relative here (h^2 terms and rounding / h).
  const double h = 1e-6;
  for (const auto& c : warp_cases()) {
    for (int i = 0; i < 16; ++i) {
      for (int j = 0; j < 4; ++j) {
        const Vec2 u{0.03 + 0.94 * i / 15.0, (j + 0.5) / 4.0};
        const Vec3 dx = (c.sample({u.x + h, u.y}) - c.sample({u.x - h, u.y})) / (2.0 * h);
        const Vec3 dy = (c.sample({u.x, u.y + h}) - c.sample({u.x, u.y - h})) / (2.0 * h);
        const double area = length(cross(dx, dy));
        const double p = c.pdf(c.sample(u));
        EXPECT_NEAR(p * area, 1.0, 1e-6) << c.name << " u = " << u.x << ", " << u.y;
      }
    }
  }
}

TEST(Warp, InvertUndoesSample) {
  for (const auto& c : warp_cases()) {
    for (int i = 0; i < 50; ++i) {
      for (int j = 0; j < 50; ++j) {
        const Vec2 u{(i + 0.5) / 50.0, (j + 0.5) / 50.0};
        const Vec2 back = c.invert(c.sample(u));
        EXPECT_NEAR(back.x, u.x, 1e-9) << c.name << " u = " << u.x << ", " << u.y;
        EXPECT_NEAR(back.y, u.y, 1e-9) << c.name << " u = " << u.x << ", " << u.y;
      }
    }
    // And the other way round: directions inside the support, away from the pole (phi is undefined there).
    for (int i = 0; i < 20; ++i) {
      const double z = c.z_min + (1.0 - c.z_min) * (i + 0.5) / 20.0;
      for (double phi : {0.1, 1.7, 3.2, 4.9, 6.2}) {
        const Vec3 w = direction(z, phi);
        const Vec3 again = c.sample(c.invert(w));
        EXPECT_NEAR(again.x, w.x, 1e-9) << c.name;
        EXPECT_NEAR(again.y, w.y, 1e-9) << c.name;
        EXPECT_NEAR(again.z, w.z, 1e-9) << c.name;
      }
    }
  }
}

TEST(Warp, AzimuthIsInZeroToTwoPi) {
  EXPECT_EQ(azimuth({1.0, 0.0, 0.0}), 0.0);
  EXPECT_NEAR(azimuth({0.0, 1.0, 0.0}), 0.5 * pi, 1e-15);
  EXPECT_NEAR(azimuth({-1.0, 0.0, 0.0}), pi, 1e-15);
  EXPECT_NEAR(azimuth({0.0, -1.0, 0.0}), 1.5 * pi, 1e-15);
  // Just below the +X axis: phi is a hair under 2 pi and must not round up to 2 pi itself, or the inverse
  // warps would return u.y = 1, outside [0, 1).
  for (double y : {-1e-3, -1e-10, -1e-16, -1e-20, -1e-300}) {
    const Vec3 w = normalize(Vec3{1.0, y, 0.5});
    EXPECT_LT(azimuth(w), two_pi) << "y = " << y;
    EXPECT_GT(azimuth(w), pi) << "y = " << y;
    EXPECT_LT(invert_uniform_hemisphere(w).y, 1.0) << "y = " << y;
    EXPECT_LT(invert_cosine_hemisphere(w).y, 1.0) << "y = " << y;
  }
}

TEST(Warp, PdfIntegratesToOneOverTheSphere) {
  // Midpoint rule in (cos theta, phi), where d(omega) = d(cos theta) d(phi), with a cell edge on the support
  // boundary z_min so that the jump there is integrated exactly. The error for a smooth density f(z) is about
  // h^2 / 24 (f'(1) - f'(z_min)); the worst case, power cosine n = 100, gives 1.1e-6 with h = 5e-5.
  constexpr int nz = 20000;
  constexpr int nphi = 16;
  for (const auto& c : warp_cases()) {
    double total = 0.0;
    const double pieces[3] = {-1.0, c.z_min, 1.0};
    for (int piece = 0; piece < 2; ++piece) {
      const double z0 = pieces[piece];
      const double z1 = pieces[piece + 1];
      if (z1 <= z0) continue;
      const double dz = (z1 - z0) / nz;
      for (int i = 0; i < nz; ++i) {
        const double z = z0 + (i + 0.5) * dz;
        for (int j = 0; j < nphi; ++j) {
          const double phi = two_pi * (j + 0.5) / nphi;
          total += c.pdf(direction(z, phi)) * dz * (two_pi / nphi);
        }
      }
    }
    EXPECT_NEAR(total, 1.0, 1e-5) << c.name;
  }
}

TEST(Warp, HistogramMatchesPdfChiSquare) {
  // Bins: kz bands in cos(theta) (edges from the case's z_of_t, so that each band holds a fair share of the
  // samples) times kphi equal sectors in phi. Expected counts integrate the pdf function over each bin with
  // 256 x 2 midpoint sub-cells (the first band of the n = 100 lobe spans z in [0, 0.973], where z^100 needs
  // that many: relative error ~ h^2 f'' / (24 f) < 1e-2, a few counts at most); bins expecting fewer than 5
  // samples are pooled, as Pearson's test requires.
  constexpr int kz = 16;
  constexpr int kphi = 12;
  constexpr int samples = 100000;
  for (const auto& c : warp_cases()) {
    std::vector<double> edges(kz + 1);
    for (int i = 0; i <= kz; ++i) edges[i] = c.z_of_t(static_cast<double>(i) / kz);
    edges[0] = c.z_min;
    edges[kz] = 1.0;

    std::vector<double> expected(kz * kphi, 0.0);
    for (int i = 0; i < kz; ++i) {
      const double dz = (edges[i + 1] - edges[i]) / 256.0;
      for (int j = 0; j < kphi; ++j) {
        const double dphi = two_pi / kphi / 2.0;
        double mass = 0.0;
        for (int a = 0; a < 256; ++a) {
          for (int b = 0; b < 2; ++b) {
            const double z = edges[i] + (a + 0.5) * dz;
            const double phi = two_pi * j / kphi + (b + 0.5) * dphi;
            mass += c.pdf(direction(z, phi)) * dz * dphi;
          }
        }
        expected[i * kphi + j] = mass * samples;
      }
    }

    std::vector<double> observed(kz * kphi, 0.0);
    Pcg32 rng(0x5eed5eedu, 17u);
    for (int s = 0; s < samples; ++s) {
      const Vec2 u{rng.next_double(), rng.next_double()};
      const Vec3 w = c.sample(u);
      const auto it = std::upper_bound(edges.begin(), edges.end(), w.z);
      const int i = std::clamp(static_cast<int>(it - edges.begin()) - 1, 0, kz - 1);
      const int j = std::min(static_cast<int>(azimuth(w) / two_pi * kphi), kphi - 1);
      observed[i * kphi + j] += 1.0;
    }

    double chi2 = 0.0;
    int cells = 0;
    double pooled_expected = 0.0;
    double pooled_observed = 0.0;
    for (std::size_t b = 0; b < expected.size(); ++b) {
      if (expected[b] < 5.0) {
        pooled_expected += expected[b];
        pooled_observed += observed[b];
        continue;
      }
      chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
      ++cells;
    }
    if (pooled_expected >= 5.0) {
      chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
      ++cells;
    } else {
      EXPECT_LT(pooled_observed, 5.0 + 5.0 * std::sqrt(5.0)) << c.name << ": samples where the pdf is ~0";
    }
    ASSERT_GT(cells, 100) << c.name;
    EXPECT_LT(chi2, chi2_quantile_999(cells - 1)) << c.name << " with " << cells << " cells";
  }
}

TEST(Warp, SpecialCasesAgree) {
  // A power-cosine lobe of exponent 0 is the uniform hemisphere, of exponent 1 the cosine hemisphere; a cap
  // of cos_max = 0 is the hemisphere and of cos_max = -1 the sphere.
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 5; ++j) {
      const Vec2 u{(i + 0.5) / 20.0, (j + 0.5) / 5.0};
      const Vec3 a = sample_power_cosine(u, 0.0);
      const Vec3 b = sample_uniform_hemisphere(u);
      EXPECT_NEAR(length(a - b), 0.0, 1e-12);
      const Vec3 w = sample_cosine_hemisphere(u);
      EXPECT_NEAR(power_cosine_pdf(w, 1.0), cosine_hemisphere_pdf(w), 1e-15);
      EXPECT_NEAR(spherical_cap_pdf(b, 0.0), uniform_hemisphere_pdf(b), 1e-15);
      const Vec3 s = sample_uniform_sphere(u);
      EXPECT_NEAR(length(sample_spherical_cap(u, -1.0) - s), 0.0, 1e-12);
      EXPECT_NEAR(spherical_cap_pdf(s, -1.0), uniform_sphere_pdf(s), 1e-15);
    }
  }
  // Directions on or below the horizon have zero density for the cosine lobes.
  EXPECT_EQ(cosine_hemisphere_pdf({1.0, 0.0, 0.0}), 0.0);
  EXPECT_EQ(cosine_hemisphere_pdf({0.0, 0.6, -0.8}), 0.0);
  EXPECT_EQ(power_cosine_pdf({0.0, 0.6, -0.8}, 10.0), 0.0);
  EXPECT_EQ(uniform_hemisphere_pdf({0.0, 0.6, -0.8}), 0.0);
}

}  // namespace
}  // namespace shadelab
