// UTIA .bin files (brdf/utia.h): a file written by the test's virtual gonioreflectometer from a known function,
// its bytes checked at the layout's offsets (the index written again here from the format's description), read
// back; at the measured directions the stored values, between them between the 16 neighbours, and a function
// linear in the angles reproduced exactly; theta beyond 75 degrees held, phi periodic; malformed files refused in
// one line; the sampler's density integrates to 1 and is the density of its samples.
#include "shadelab/brdf/utia.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "shadelab/core/constants.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {
namespace {

constexpr double deg = pi / 180.0;

void angles(const Vec3& w, double& theta, double& phi) {
  theta = std::acos(std::clamp(w.z, -1.0, 1.0));
  phi = std::atan2(w.y, w.x);
  if (phi < 0.0) phi += two_pi;
}

// A test function of the four angles (degrees), anisotropic and not reciprocal: linear in each theta, and in each
// phi a function whose samples are distinct.
class Known final : public Brdf {
 public:
  explicit Known(bool linear) : m_linear(linear) {}
  Rgb eval(const Vec3& wi, const Vec3& wo) const override {
    if (!(wi.z > 0.0 && wo.z > 0.0)) return {};
    double ti = 0, pi_ = 0, tv = 0, pv = 0;
    angles(wi, ti, pi_);
    angles(wo, tv, pv);
    ti /= deg, pi_ /= deg, tv /= deg, pv /= deg;
    if (m_linear) return {0.1 + 0.002 * ti + 0.001 * tv, 0.2 + 0.003 * tv, 0.05 + 0.001 * ti};
    return {0.1 + 0.002 * ti + 0.001 * tv + 0.05 * std::sin(pi_ * deg) * std::cos(2 * pv * deg) + 0.05,
            0.2 + 0.03 * std::cos(pv * deg - pi_ * deg), 0.05 + 0.001 * ti * (1 + std::cos(pi_ * deg))};
  }
  double pdf(const Vec3&, const Vec3&) const override { return 0.0; }
  BrdfSample sample(const Vec3&, Vec2, double) const override { return {}; }

 private:
  bool m_linear;
};

Vec3 at(double theta_deg, double phi_deg) {
  return {std::sin(theta_deg * deg) * std::cos(phi_deg * deg), std::sin(theta_deg * deg) * std::sin(phi_deg * deg), std::cos(theta_deg * deg)};
}

TEST(Utia, WritesAndReadsTheLayoutByteForByte) {
  const Known g(false);
  const UtiaTable t = measure_utia(g);
  const auto bytes = encode_utia(t);
  ASSERT_EQ(bytes.size(), 1990656u);
  // The format's index, written again: plane, then theta_i (15 deg), phi_i (7.5 deg), theta_v, phi_v (fastest).
  for (int c = 0; c < 3; ++c) {
    for (int ti : {0, 2, 5}) {
      for (int pi_ : {0, 7, 47}) {
        for (int tv : {0, 3, 5}) {
          for (int pv : {0, 11, 47}) {
            const std::size_t idx = static_cast<std::size_t>((((c * 6 + ti) * 48 + pi_) * 6 + tv) * 48 + pv);
            double v = 0.0;
            std::memcpy(&v, bytes.data() + 8 * idx, 8);
            const Rgb want = g.eval(at(15.0 * ti, 7.5 * pi_), at(15.0 * tv, 7.5 * pv));
            EXPECT_DOUBLE_EQ(v, c == 0 ? want.r : c == 1 ? want.g : want.b);
          }
        }
      }
    }
  }
  auto back = parse_utia(bytes, "m.bin");
  ASSERT_TRUE(back.has_value()) << back.error().message;
  EXPECT_EQ(back->values, t.values);
}

TEST(Utia, AtMeasuredDirectionsItIsTheTableAndBetweenThemBetweenTheNeighbours) {
  const Known g(false);
  const auto table = std::make_shared<const UtiaTable>(measure_utia(g));
  const UtiaBrdf f(table);
  double worst = 0.0;
  // From theta 15 up: at theta 0 the 48 phi samples are one direction, whose phi eval reads as atan2(0, 0) = 0.
  for (int ti = 1; ti < 6; ++ti) {
    for (int pi_ = 0; pi_ < 48; pi_ += 5) {
      for (int tv = 1; tv < 6; ++tv) {
        for (int pv = 0; pv < 48; pv += 3) {
          const Rgb e = f.eval(utia_direction(ti, pi_), utia_direction(tv, pv));
          const std::size_t idx = UtiaTable::index(ti, pi_, tv, pv);
          worst = std::max({worst, std::abs(e.r - table->value(0, idx)), std::abs(e.g - table->value(1, idx)), std::abs(e.b - table->value(2, idx))});
        }
      }
    }
  }
  EXPECT_LE(worst, 1e-12);
  // Between: inside the range of the 16 neighbours' values.
  Pcg32 rng(2);
  for (int k = 0; k < 2000; ++k) {
    const double a[4] = {rng.next_double() * 75.0, rng.next_double() * 360.0, rng.next_double() * 75.0, rng.next_double() * 360.0};
    const Rgb e = f.eval(at(a[0], a[1]), at(a[2], a[3]));
    const int k0[4] = {std::min(static_cast<int>(a[0] / 15), 4), static_cast<int>(a[1] / 7.5) % 48, std::min(static_cast<int>(a[2] / 15), 4),
                       static_cast<int>(a[3] / 7.5) % 48};
    double lo = 1e300, hi = -1e300;
    for (int corner = 0; corner < 16; ++corner) {
      const int ti = k0[0] + (corner & 1), pi_ = (k0[1] + ((corner >> 1) & 1)) % 48, tv = k0[2] + ((corner >> 2) & 1),
                pv = (k0[3] + ((corner >> 3) & 1)) % 48;
      const double v = table->value(1, UtiaTable::index(ti, pi_, tv, pv));
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    ASSERT_GE(e.g, lo - 1e-12) << k;
    ASSERT_LE(e.g, hi + 1e-12) << k;
  }
}

TEST(Utia, LinearDataIsReproducedExactlyThetaIsHeldBeyondTheLastAndPhiWraps) {
  const Known g(true);
  const UtiaBrdf f(std::make_shared<const UtiaTable>(measure_utia(g)));
  Pcg32 rng(4);
  double worst = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 wi = at(rng.next_double() * 75.0, rng.next_double() * 360.0), wo = at(rng.next_double() * 75.0, rng.next_double() * 360.0);
    const Rgb e = f.eval(wi, wo), w = g.eval(wi, wo);
    worst = std::max({worst, std::abs(e.r - w.r), std::abs(e.g - w.g), std::abs(e.b - w.b)});
  }
  EXPECT_LE(worst, 1e-9);
  // Beyond 75 degrees: the value at 75.
  EXPECT_NEAR(f.eval(at(85.0, 10.0), at(30.0, 0.0)).r, g.eval(at(75.0, 10.0), at(30.0, 0.0)).r, 1e-12);
  EXPECT_NEAR(f.eval(at(30.0, 10.0), at(89.9, 0.0)).g, g.eval(at(30.0, 10.0), at(75.0, 0.0)).g, 1e-12);
  EXPECT_EQ(f.eval(at(30.0, 0.0), {0.0, 1.0, -0.1}).r, 0.0);
  // phi between 352.5 and 360: between the samples at 352.5 and 0.
  UtiaTable t;
  t.values[UtiaTable::index(2, 47, 2, 0)] = 1.0;
  t.values[UtiaTable::index(2, 0, 2, 0)] = 3.0;
  const UtiaBrdf p(std::make_shared<const UtiaTable>(t));
  EXPECT_NEAR(p.eval(at(30.0, 356.25), at(30.0, 0.0)).r, 2.0, 1e-12);
  EXPECT_NEAR(p.eval(at(30.0, -1.875), at(30.0, 0.0)).r, 2.5, 1e-12);
  // Negative stored values are clamped at 0.
  t.values[UtiaTable::index(2, 0, 2, 0)] = -3.0;
  EXPECT_EQ(UtiaBrdf(std::make_shared<const UtiaTable>(t)).eval(at(30.0, 0.0), at(30.0, 0.0)).r, 0.0);
}

TEST(Utia, MalformedFilesAreOneLineNamingTheFileAndWhat) {
  const auto bytes = encode_utia(measure_utia(Known(true)));
  const auto check = [](const Result<UtiaTable>& r, const std::string& what) {
    ASSERT_FALSE(r.has_value());
    EXPECT_NE(r.error().message.find("dir/u.bin"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find(what), std::string::npos) << r.error().message;
    EXPECT_EQ(r.error().message.find('\n'), std::string::npos);
  };
  check(parse_utia(std::span<const char>(bytes.data(), bytes.size() - 8), "dir/u.bin"), "1990648 bytes, expected 1990656");
  check(parse_utia(std::span<const char>(bytes.data(), bytes.size() - 8), "dir/u.bin"), "truncated");
  std::vector<char> longer = bytes;
  longer.push_back(0);
  check(parse_utia(longer, "dir/u.bin"), "trailing bytes");
  check(parse_utia({}, "dir/u.bin"), "0 bytes");
  std::vector<char> nan = bytes;
  const double q = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(nan.data() + 8 * (UtiaTable::plane + UtiaTable::index(3, 2, 1, 47)), &q, 8);
  check(parse_utia(nan, "dir/u.bin"), "channel G at theta_i 45, phi_i 15, theta_v 15, phi_v 352.5 degrees is not finite");
  const auto dir = std::filesystem::temp_directory_path() / "shadelab-utia-test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream out(dir / "cut.bin", std::ios::binary);
    out.write(bytes.data(), 1000);
  }
  const auto r = read_utia_brdf(dir / "cut.bin");
  ASSERT_FALSE(r.has_value());
  EXPECT_NE(r.error().message.find((dir / "cut.bin").string() + ": 1000 bytes"), std::string::npos) << r.error().message;
  {
    std::ofstream out(dir / "ok.bin", std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  const auto ok = read_utia_brdf(dir / "ok.bin");
  ASSERT_TRUE(ok.has_value()) << ok.error().message;
  EXPECT_NEAR((*ok)->eval(at(30.0, 0.0), at(45.0, 90.0)).g, 0.2 + 0.003 * 45.0, 1e-12);
  std::filesystem::remove_all(dir);
}

// The mixture's density integrates to 1 over the hemisphere (the midpoint rule on sub-cells of its (phi, cos theta)
// cells: the table part is constant on each, the cosine part linear in cos theta, so it is exact), sample returns
// pdf(), and the mean of q / pdf over samples is 1 for the cosine density q.
TEST(Utia, PdfIntegratesToOneAndIsTheDensityOfTheSamples) {
  const UtiaBrdf f(std::make_shared<const UtiaTable>(measure_utia(Known(false))));
  for (const Vec3& wo : {at(0.0, 0.0), at(40.0, 100.0), at(80.0, 300.0)}) {
    double integral = 0.0;
    const int nx = UtiaBrdf::phi_cells * 2, ny = UtiaBrdf::z_cells * 2;
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < ny; ++j) {
        const double phi = (i + 0.5) / nx * two_pi, z = (j + 0.5) / ny;
        const double s = std::sqrt(1.0 - z * z);
        integral += f.pdf({s * std::cos(phi), s * std::sin(phi), z}, wo);
      }
    }
    integral *= two_pi / (static_cast<double>(nx) * ny);  // d(omega) = d(phi) d(cos theta)
    EXPECT_NEAR(integral, 1.0, 1e-9);
    Pcg32 rng(8);
    const int n = 100000;
    double sum = 0.0, sum2 = 0.0, worst = 0.0;
    for (int k = 0; k < n; ++k) {
      const BrdfSample b = f.sample(wo, {rng.next_double(), rng.next_double()}, rng.next_double());
      ASSERT_GT(b.pdf, 0.0);
      worst = std::max(worst, std::abs(b.pdf - f.pdf(b.wi, wo)) / b.pdf);
      const double r = b.wi.z * inv_pi / b.pdf;
      sum += r;
      sum2 += r * r;
    }
    const double mean = sum / n, sd = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_LE(worst, 1e-12);
    EXPECT_NEAR(mean, 1.0, 5.0 * sd);
    std::printf("[ utia ] view z %.3f: pdf integral %.12f, mean of q/pdf %.5f (sd %.5f)\n", wo.z, integral, mean, sd);
  }
}

}  // namespace
}  // namespace shadelab
