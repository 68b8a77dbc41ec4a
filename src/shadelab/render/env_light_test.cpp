// The environment sampler against the radiance the renderer reads: around a one-texel sun the estimator's weight
// L / pdf stays within a small multiple of the environment's integral (issue 42: a table of the texels alone gave
// the bilinear lookup's rim around the sun only the floor's probability, weights 10^5 times the integral:
// fireflies), and the sampler's mean weight is that integral.
#include "shadelab/render/env_light.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "shadelab/core/constants.h"
#include "shadelab/envmap/base/latlong.h"
#include "shadelab/sampling/rng.h"

namespace shadelab {
namespace {

Scene sun_scene() {
  Scene s;
  s.environment.kind = Environment::Kind::image;
  s.environment.latlong = Image(64, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) s.environment.latlong.set(x, y, Rgb::gray(0.01));
  s.environment.latlong.set(20, 10, Rgb::gray(1e4));  // a one-texel sun
  return s;
}

TEST(EnvironmentLight, WeightAroundAOneTexelSunIsBounded) {
  const Scene scene = sun_scene();
  const EnvironmentLight env(scene);
  // The integral of what the lookup returns, by a fine midpoint rule in (u, v) (16 x 16 points per texel).
  const int nu = 64 * 16, nv = 32 * 16;
  double integral = 0.0;
  double max_ratio = 0.0;
  for (int j = 0; j < nv; ++j) {
    const double v = (j + 0.5) / nv;
    for (int i = 0; i < nu; ++i) {
      const Vec3 w = latlong_direction((i + 0.5) / nu, v);
      const double l = luminance(env.radiance(w));
      integral += l * 2.0 * pi * pi * std::sin(pi * v) / (static_cast<double>(nu) * nv);  // dw = 2 pi^2 sin(theta) du dv
      const double p = env.pdf(w);
      ASSERT_GT(p, 0.0);
      max_ratio = std::max(max_ratio, l / p);
    }
  }
  // The mean of L / pdf over the sampler is the integral; its largest value is what a firefly is. The exact cell
  // means bound it by 16 (a corner cell beside a point-like sun) times the sin(theta) spread of a row.
  EXPECT_LT(max_ratio / integral, 20.0) << max_ratio << " vs " << integral;

  Pcg32 rng(7);
  double sum = 0.0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const auto s = env.sample({rng.next_double(), rng.next_double()}, rng.next_double());
    ASSERT_GT(s.pdf, 0.0);
    EXPECT_NEAR(s.pdf, env.pdf(s.wi), 1e-9 * s.pdf);
    sum += luminance(s.radiance) / s.pdf;
  }
  EXPECT_NEAR(sum / n / integral, 1.0, 0.01);
}

}  // namespace
}  // namespace shadelab
