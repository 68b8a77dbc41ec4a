// MERL 100 files (brdf/merl.h): the binning against BRDFRead.cpp's formulas evaluated by hand, Rusinkiewicz's
// coordinates against their geometric meaning, the byte layout against bytes the test writes itself, refusals
// naming the file and what is wrong, and the virtual gonioreflectometer against the model evaluated at bin centres
// whose directions the test computes from its own closed form.
#include "shadelab/brdf/merl.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"
#include "shadelab/sampling/rng.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {
namespace {

constexpr std::size_t kCount = 90 * 90 * 180;

// wi and wo of a bin centre with phi_h = 0, written out from the rotation: h = (sin th, 0, cos th), the difference
// vector d = (sin td cos pd, sin td sin pd, cos td) turned by th about y; wo is wi's mirror about h.
std::pair<Vec3, Vec3> centre_directions(int i, int j, int k) {
  const double th = std::pow((i + 0.5) / 90.0, 2) * pi / 2, td = (j + 0.5) / 90.0 * pi / 2, pd = (k + 0.5) / 180.0 * pi;
  const Vec3 wi{std::cos(th) * std::sin(td) * std::cos(pd) + std::sin(th) * std::cos(td), std::sin(td) * std::sin(pd),
                -std::sin(th) * std::sin(td) * std::cos(pd) + std::cos(th) * std::cos(td)};
  const Vec3 h{std::sin(th), 0.0, std::cos(th)};
  const Vec3 wo = h * (2.0 * std::cos(td)) - wi;
  return {wi, wo};
}

std::vector<char> header(std::int32_t a, std::int32_t b, std::int32_t c) {
  std::vector<char> bytes(12);
  const std::int32_t dims[3] = {a, b, c};
  std::memcpy(bytes.data(), dims, 12);
  return bytes;
}

void append_doubles(std::vector<char>& bytes, const std::vector<double>& v) {
  const std::size_t at = bytes.size();
  bytes.resize(at + v.size() * 8);
  std::memcpy(bytes.data() + at, v.data(), v.size() * 8);
}

TEST(Merl, BinsAreTheDatabaseReadersFormulas) {
  HalfDiffAngles a;
  a.theta_h = pi / 4;  // floor(90 sqrt(1/2)) = 63
  a.theta_d = pi / 4;  // floor(45) = 45
  a.phi_d = -pi / 2;   // folded to pi/2: floor(90) = 90
  MerlBin b = merl_bin(a);
  EXPECT_EQ(b.theta_h, 63);
  EXPECT_EQ(b.theta_d, 45);
  EXPECT_EQ(b.phi_d, 90);
  a.theta_h = 0.0;
  a.theta_d = pi / 2;
  a.phi_d = pi - 1e-12;
  b = merl_bin(a);
  EXPECT_EQ(b.theta_h, 0);
  EXPECT_EQ(b.theta_d, 89);  // 90 clamped
  EXPECT_EQ(b.phi_d, 179);
  a.theta_h = 1.0 / 8100.0 * pi / 2 * 0.999;  // just below the first sqrt step: bin 0; just above: bin 1
  EXPECT_EQ(merl_bin(a).theta_h, 0);
  a.theta_h = 1.0 / 8100.0 * pi / 2 * 1.001;
  EXPECT_EQ(merl_bin(a).theta_h, 1);
  // Each bin's centre lies in that bin.
  for (int i : {0, 1, 44, 89}) {
    for (int j : {0, 30, 89}) {
      for (int k : {0, 77, 179}) {
        const MerlBin c = merl_bin(merl_bin_centre(i, j, k));
        EXPECT_EQ(c.theta_h, i);
        EXPECT_EQ(c.theta_d, j);
        EXPECT_EQ(c.phi_d, k);
      }
    }
  }
  EXPECT_EQ(MerlTable::index(2, 3, 4), 4u + 180u * (3u + 90u * 2u));
}

// theta_h is the half vector's elevation, theta_d the angle between wi and h; swapping wi and wo turns phi_d by pi;
// the inverse gives the pair back.
TEST(Merl, HalfDiffAnglesAreRusinkiewiczs) {
  Pcg32 rng(7);
  for (int n = 0; n < 2000; ++n) {
    const Vec3 wi = sample_uniform_hemisphere({rng.next_double(), rng.next_double()});
    const Vec3 wo = sample_uniform_hemisphere({rng.next_double(), rng.next_double()});
    const HalfDiffAngles a = half_diff_angles(wi, wo);
    const Vec3 h = normalize(wi + wo);
    EXPECT_NEAR(a.theta_h, std::acos(h.z), 1e-12);
    EXPECT_NEAR(a.theta_d, std::acos(std::min(1.0, dot(wi, h))), 1e-7);
    const HalfDiffAngles b = half_diff_angles(wo, wi);
    EXPECT_NEAR(b.theta_h, a.theta_h, 1e-12);
    EXPECT_NEAR(b.theta_d, a.theta_d, 1e-7);
    const double turn = std::remainder(b.phi_d - a.phi_d - pi, 2 * pi);
    EXPECT_NEAR(turn, 0.0, 1e-7) << a.phi_d << " " << b.phi_d;
    const auto [wi2, wo2] = half_diff_directions(a);
    EXPECT_NEAR(length(wi2 - wi), 0.0, 1e-12);
    EXPECT_NEAR(length(wo2 - wo), 0.0, 1e-12);
  }
  for (int i : {0, 20, 89}) {
    for (int j : {0, 45, 89}) {
      for (int k : {0, 100, 179}) {
        const auto [wi, wo] = half_diff_directions(merl_bin_centre(i, j, k));
        const auto [ti, to] = centre_directions(i, j, k);
        EXPECT_NEAR(length(wi - ti), 0.0, 1e-14);
        EXPECT_NEAR(length(wo - to), 0.0, 1e-14);
      }
    }
  }
}

// A file the test writes byte by byte: the header, then three planes; the values come back scaled by the published
// channel scales, negatives as missing, and encoding gives the same bytes back.
TEST(Merl, ReadsTheLayoutAndWritesItBackByteForByte) {
  std::vector<double> planes(3 * kCount);
  for (std::size_t i = 0; i < planes.size(); ++i) planes[i] = static_cast<double>((i * 2654435761u) % 100000) * 0.37;
  planes[5] = -1.0;
  planes[kCount + 6] = -2.5;
  std::vector<char> bytes = header(90, 90, 180);
  append_doubles(bytes, planes);
  ASSERT_EQ(bytes.size(), 34992012u);
  const auto t = parse_merl(bytes, "hand.binary");
  ASSERT_TRUE(t.has_value()) << t.error().message;
  const double scale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};
  for (std::size_t idx : {0u, 1u, 7u, 12345u, 1457999u}) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(t->value(c, idx), planes[static_cast<std::size_t>(c) * kCount + idx] * scale[c]) << idx << " " << c;
    }
  }
  EXPECT_EQ(t->value(0, 5), -1.0);
  EXPECT_EQ(t->value(1, 6), -1.0);
  EXPECT_EQ(encode_merl(*t), bytes);
}

TEST(Merl, MalformedFilesAreOneLineNamingTheFileAndTheField) {
  std::vector<char> good = header(90, 90, 180);
  append_doubles(good, std::vector<double>(3 * kCount, 0.5));
  const auto expect_error = [](const std::vector<char>& b, const std::string& needle) {
    const auto r = parse_merl(b, "m.binary");
    ASSERT_FALSE(r.has_value()) << needle;
    EXPECT_NE(r.error().message.find("m.binary"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find(needle), std::string::npos) << r.error().message;
    EXPECT_EQ(r.error().message.find('\n'), std::string::npos) << r.error().message;
  };
  expect_error(std::vector<char>(good.begin(), good.end() - 8), "truncated");
  expect_error(std::vector<char>(good.begin(), good.begin() + 5), "truncated");
  std::vector<char> longer = good;
  longer.push_back(0);
  expect_error(longer, "trailing bytes");
  std::vector<char> dims = good;
  const std::int32_t phi = 360;
  std::memcpy(dims.data() + 8, &phi, 4);
  expect_error(dims, "header dims 90 x 90 x 360");
  std::vector<char> nan = good;
  const double q = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(nan.data() + 12 + 8 * (kCount + MerlTable::index(3, 4, 5)), &q, 8);
  expect_error(nan, "channel G at bin (theta_h 3, theta_d 4, phi_d 5) is not finite");
  // The same through the file reader: a missing file and a truncated one name the path.
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "shadelab_merl_test";
  std::filesystem::create_directories(dir);
  const auto missing = read_merl(dir / "missing.binary");
  ASSERT_FALSE(missing.has_value());
  EXPECT_NE(missing.error().message.find("missing.binary"), std::string::npos);
  {
    std::ofstream f(dir / "cut.binary", std::ios::binary);
    f.write(good.data(), 1000);
  }
  const auto cut = read_merl(dir / "cut.binary");
  ASSERT_FALSE(cut.has_value());
  EXPECT_NE(cut.error().message.find("cut.binary"), std::string::npos);
  EXPECT_NE(cut.error().message.find("truncated"), std::string::npos) << cut.error().message;
}

// The gonioreflectometer: every bin whose centre is above the horizon holds the model's f at that centre (the
// directions from the test's own closed form), to 1e-12 relative after the scale round trip; the others hold -1,
// and they are exactly the centres where wi.z or wo.z is <= 0.
TEST(Merl, MeasureEvaluatesTheModelAtEachBinCentre) {
  const auto ggx = make_brdf("ggx", {{"roughness", "0.5"}, {"kd", "0.2,0.3,0.4"}, {"f0", "0.04"}});
  ASSERT_TRUE(ggx.has_value());
  const MerlTable t = measure_merl(**ggx);
  std::size_t missing = 0, expected_missing = 0;
  double worst = 0.0;
  for (int i = 0; i < 90; ++i) {
    for (int j = 0; j < 90; ++j) {
      for (int k = 0; k < 180; ++k) {
        const auto [wi, wo] = centre_directions(i, j, k);
        const std::size_t idx = MerlTable::index(i, j, k);
        const bool below = !(wi.z > 0.0 && wo.z > 0.0);
        expected_missing += below ? 1 : 0;
        missing += t.value(0, idx) < 0.0 ? 1 : 0;
        if (below || (i + j + k) % 7 != 0) continue;
        const Rgb f = (*ggx)->eval(normalize(wi), normalize(wo));
        const double v[3] = {f.r, f.g, f.b};
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(t.value(c, idx) - v[c]) / v[c]);
      }
    }
  }
  EXPECT_EQ(missing, expected_missing);
  EXPECT_GT(missing, 0u);
  EXPECT_LE(worst, 1e-12);
  std::printf("[ merl     ] measured ggx: %zu of %zu bins below the horizon, max relative difference %.3g\n", missing,
              kCount, worst);
}

}  // namespace
}  // namespace shadelab
