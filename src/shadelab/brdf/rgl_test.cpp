// RGL/EPFL tensor files (brdf/rgl.h): the container written by the test's own writer and by hand, read back
// field by field; malformed containers and BRDF fields refused in one line naming the file and what; the warp
// against its definition (sample and invert are inverses, its density integrates to 1 and is the Jacobian of
// invert); the BRDF on tables whose evaluation has a closed form (a uniform VNDF makes the warp the identity, so
// f = rgb(u_m) ndf / (4 sigma)); at table nodes the stored values, between them between the neighbours; the
// sampler's density against its samples.
#include "shadelab/brdf/rgl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

// The fields of an RGB .bsdf file, filled by each test.
struct Spec {
  std::vector<double> theta_i{0.0, 0.5, 1.0};
  std::vector<double> phi_i{0.0};
  int nw = 5, nh = 5;  // vndf, luminance and rgb tables
  std::vector<double> ndf = std::vector<double>(9, 2.0);    // 3 x 3
  std::vector<double> sigma = std::vector<double>(9, 0.5);  // 3 x 3
  std::vector<double> vndf, luminance, rgb;
  std::size_t slices() const { return theta_i.size() * phi_i.size(); }
  std::size_t cells() const { return static_cast<std::size_t>(nw) * static_cast<std::size_t>(nh); }
  std::vector<TensorFieldData> fields() const {
    const std::uint64_t np = phi_i.size(), nt = theta_i.size(), h = static_cast<std::uint64_t>(nh), w = static_cast<std::uint64_t>(nw);
    return {tensor_f32("theta_i", {nt}, theta_i),
            tensor_f32("phi_i", {np}, phi_i),
            tensor_f32("ndf", {3, 3}, ndf),
            tensor_f32("sigma", {3, 3}, sigma),
            tensor_f32("vndf", {np, nt, h, w}, vndf),
            tensor_f32("luminance", {np, nt, h, w}, luminance),
            tensor_f32("rgb", {np, nt, 3, h, w}, rgb),
            tensor_u8("description", {4}, {'t', 'e', 's', 't'}),
            tensor_u8("jacobian", {1}, {1})};
  }
  std::vector<char> bytes() const { return encode_tensor_file(fields()); }
};

// Uniform VNDF and luminance; rgb(x, y) per channel from `g`, times (1 + slice) so that the slices differ.
template <class G>
Spec uniform_spec(G g, std::vector<double> phi_i = {0.0}) {
  Spec s;
  s.phi_i = std::move(phi_i);
  s.vndf.assign(s.slices() * s.cells(), 1.0);
  s.luminance.assign(s.slices() * s.cells(), 1.0);
  for (std::size_t sl = 0; sl < s.slices(); ++sl) {
    for (int c = 0; c < 3; ++c) {
      for (int y = 0; y < s.nh; ++y) {
        for (int x = 0; x < s.nw; ++x) s.rgb.push_back((1.0 + static_cast<double>(sl)) * g(c, x / (s.nw - 1.0), y / (s.nh - 1.0)));
      }
    }
  }
  return s;
}

RglBrdf brdf_of(const Spec& s) {
  auto t = parse_rgl(s.bytes(), "test.bsdf");
  EXPECT_TRUE(t.has_value()) << (t ? "" : t.error().message);
  return RglBrdf(std::make_shared<const RglTable>(std::move(*t)));
}

Vec3 spherical(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// The pair (wi, wo) whose half vector is at (theta_m, phi_m) for the view wo (the table's conditioning direction).
Vec3 mirrored(const Vec3& wo, double theta_m, double phi_m) {
  const Vec3 m = spherical(theta_m, phi_m);
  return normalize(m * (2.0 * dot(m, wo)) - wo);
}

std::string error_of(std::vector<char> bytes) {
  auto r = parse_rgl(std::move(bytes), "dir/x.bsdf");
  return r ? std::string("accepted") : r.error().message;
}

void expect_one_line(const std::string& m, const std::string& what) {
  EXPECT_NE(m.find("dir/x.bsdf"), std::string::npos) << m;
  EXPECT_NE(m.find(what), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(RglTensor, ReadsTheContainerFieldByField) {
  // A file written by hand: the magic, version 1.0, one uint16 field "ab" of shape [2] at offset 41.
  std::vector<char> hand = {'t', 'e', 'n', 's', 'o', 'r', '_', 'f', 'i', 'l', 'e', '\0', 1, 0, 1, 0, 0, 0,  // 18
                            2, 0, 'a', 'b', 1, 0, 3,                                                      // +7 = 25
                            41, 0, 0, 0, 0, 0, 0, 0,                                                      // offset 41
                            2, 0, 0, 0, 0, 0, 0, 0,                                                       // shape [2]
                            7, 0, static_cast<char>(0xff), 0x12};                                         // 41..44
  ASSERT_EQ(hand.size(), 45u);
  auto t = parse_tensor_file(hand, "hand.bsdf");
  ASSERT_TRUE(t.has_value()) << t.error().message;
  ASSERT_EQ(t->fields.size(), 1u);
  EXPECT_EQ(t->fields[0].name, "ab");
  EXPECT_EQ(t->fields[0].dtype, TensorDtype::u16);
  EXPECT_EQ(t->fields[0].offset, 41u);
  EXPECT_EQ(t->fields[0].count, 2u);
  std::uint16_t v[2];
  std::memcpy(v, t->bytes.data() + t->fields[0].offset, 4);
  EXPECT_EQ(v[0], 7u);
  EXPECT_EQ(v[1], 0x12ffu);
  // The writer's output read back: every dtype, names, shapes, data.
  std::vector<TensorFieldData> fields;
  for (int d = 1; d <= 11; ++d) {
    const auto dt = static_cast<TensorDtype>(d);
    std::vector<char> data(tensor_dtype_size(dt) * 6);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<char>(i * 7 + static_cast<std::size_t>(d));
    fields.push_back({std::string("f") + tensor_dtype_name(dt), dt, {2, 3}, data});
  }
  const auto bytes = encode_tensor_file(fields);
  auto r = parse_tensor_file(bytes, "w.bsdf");
  ASSERT_TRUE(r.has_value()) << r.error().message;
  ASSERT_EQ(r->fields.size(), fields.size());
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const TensorField& f = r->fields[i];
    EXPECT_EQ(f.name, fields[i].name);
    EXPECT_EQ(f.dtype, fields[i].dtype);
    EXPECT_EQ(f.shape, (std::vector<std::uint64_t>{2, 3}));
    ASSERT_EQ(f.count, 6u);
    EXPECT_EQ(0, std::memcmp(r->bytes.data() + f.offset, fields[i].data.data(), fields[i].data.size()));
  }
}

TEST(RglTensor, MalformedContainersAreOneLineNamingTheFileAndWhat) {
  const Spec s = uniform_spec([](int, double, double) { return 0.1; });
  const auto good = s.bytes();
  ASSERT_EQ(error_of(good), "accepted");
  expect_one_line(error_of(std::vector<char>(good.begin(), good.begin() + 10)), "truncated");
  auto magic = good;
  magic[0] = 'T';
  expect_one_line(error_of(magic), "not a tensor file");
  auto version = good;
  version[12] = 2;
  expect_one_line(error_of(version), "version 2.0");
  auto count = good;
  count[17] = 0x40;  // 2^30 fields
  expect_one_line(error_of(count), "fields cannot fit");
  // The first field ("theta_i"): its header is at 18: name length, 7 bytes of name, ndim, dtype at 18 + 11.
  auto dtype = good;
  dtype[29] = 12;
  expect_one_line(error_of(dtype), "field 0 (\"theta_i\"): unknown dtype 12");
  dtype[29] = 0;
  expect_one_line(error_of(dtype), "unknown dtype 0");
  auto offset = good;
  offset[37] = 0x7f;  // the offset's top byte
  expect_one_line(error_of(offset), "past the end of the file");
  auto shape = good;
  std::uint64_t huge = std::uint64_t{1} << 62;
  std::memcpy(shape.data() + 38, &huge, 8);  // theta_i's shape [2^62]: 2^64 bytes
  expect_one_line(error_of(shape), "does not fit in the file");
  expect_one_line(error_of(std::vector<char>(good.begin(), good.end() - 1)), "\"jacobian\"");  // the last field's data
  expect_one_line(error_of(std::vector<char>(good.begin(), good.begin() + 25)), "9 fields cannot fit in 25 bytes: truncated");
  // One field whose name claims 200 bytes in a 31-byte file.
  std::vector<char> name(good.begin(), good.begin() + 31);
  name[14] = 1;
  name[18] = static_cast<char>(200);
  expect_one_line(error_of(name), "field 0: truncated in its name");
  // Shapes that overflow 64 bits when multiplied: [2^32, 2^32, 16] of float32 in a tiny file.
  std::vector<TensorFieldData> over = {{"x", TensorDtype::f32, {std::uint64_t{1} << 32, std::uint64_t{1} << 32, 16}, {}}};
  expect_one_line(error_of(encode_tensor_file(over)), "does not fit in the file");
  // A rank-0 field is one value, which must fit too (libFuzzer's finding: one at the end of the file).
  auto scalar = encode_tensor_file({{"s", TensorDtype::f64, {}, {}}});
  expect_one_line(error_of(scalar), "one float64 value (rank 0) does not fit in the file after offset 32");
  scalar.resize(scalar.size() + 8);
  EXPECT_EQ(parse_tensor_file(scalar, "s.bsdf")->fields.at(0).count, 1u);
}

TEST(RglTensor, MalformedBrdfFieldsAreOneLineNamingTheField) {
  const auto base = [] { return uniform_spec([](int c, double x, double) { return 0.1 + 0.1 * c * x; }); };
  const auto without = [&](const std::string& name) {
    auto f = base().fields();
    f.erase(std::remove_if(f.begin(), f.end(), [&](const TensorFieldData& d) { return d.name == name; }), f.end());
    return encode_tensor_file(f);
  };
  expect_one_line(error_of(without("sigma")), "no field \"sigma\"");
  auto spectral = base().fields();
  spectral[6].name = "spectra";
  expect_one_line(error_of(encode_tensor_file(spectral)), "spectral");
  auto f64 = base().fields();
  f64[4].dtype = TensorDtype::f64;
  f64[4].shape[3] = 2;  // the same bytes as float64: 5 x 2 per slice... shape disagrees with luminance anyway
  expect_one_line(error_of(encode_tensor_file(f64)), "\"vndf\" is float64, expected float32");
  auto rank = base().fields();
  rank[2].shape = {9};
  expect_one_line(error_of(encode_tensor_file(rank)), "\"ndf\" has shape [9], expected 2 dimensions");
  auto channels = base().fields();
  channels[6].shape = {1, 3, 1, 5, 15};
  expect_one_line(error_of(encode_tensor_file(channels)), "\"rgb\" has shape [1, 3, 1, 5, 15]");
  Spec nan = base();
  nan.rgb[17] = std::numeric_limits<double>::quiet_NaN();
  expect_one_line(error_of(nan.bytes()), "\"rgb\" value 17 is not finite");
  Spec neg = base();
  neg.vndf[3] = -1.0;
  expect_one_line(error_of(neg.bytes()), "\"vndf\" value 3 is negative");
  Spec zero_sigma = base();
  zero_sigma.sigma[4] = 0.0;
  expect_one_line(error_of(zero_sigma.bytes()), "\"sigma\" value 4 is not positive");
  Spec flat = base();
  std::fill(flat.luminance.begin() + 25, flat.luminance.begin() + 50, 0.0);
  expect_one_line(error_of(flat.bytes()), "\"luminance\" slice 1 (phi_i 0, theta_i 1) integrates to 0");
  Spec order = base();
  order.theta_i = {0.0, 0.5, 0.5};
  expect_one_line(error_of(order.bytes()), "\"theta_i\" is not increasing at value 2");
  const Spec half = uniform_spec([](int, double, double) { return 0.1; }, {0.0, 1.0, 2.0, pi});
  expect_one_line(error_of(half.bytes()), "reduction 1");
}

// Uniform VNDF: the inverse warp is the identity, so f(wi, wo) = rgb(u_m; theta_o) ndf / (4 sigma) with
// u_m = (sqrt(theta_m / (pi/2)), (phi_m - phi_o + pi) / 2pi mod 1) (isotropic) and ndf / (4 sigma) = 1 here.
TEST(Rgl, AUniformVndfEvaluatesToTheClosedForm) {
  // Bilinear in (x, y), so the interpolation reproduces it exactly.
  const auto g = [](int c, double x, double y) { return c == 0 ? 0.2 + 0.3 * x + 0.1 * y : c == 1 ? 0.5 * x : 0.4 * y + 0.05; };
  const std::vector<double> aniso_phi = {-pi, -pi / 2, 0.0, pi / 2, pi};
  for (const bool iso : {true, false}) {
    const Spec s = uniform_spec(g, iso ? std::vector<double>{0.0} : aniso_phi);
    const RglBrdf f = brdf_of(s);
    EXPECT_EQ(f.table().isotropic, iso);
    EXPECT_EQ(f.table().description, "test");
    Pcg32 rng(5);
    double worst = 0.0;
    for (int k = 0; k < 2000; ++k) {
      const Vec3 wi = sample_uniform_hemisphere({rng.next_double(), rng.next_double()});
      const Vec3 wo = sample_uniform_hemisphere({rng.next_double(), rng.next_double()});
      const Vec3 m = normalize(wi + wo);
      const double theta_o = std::acos(wo.z), phi_o = std::atan2(wo.y, wo.x);
      double y = (std::atan2(m.y, m.x) - (iso ? phi_o : 0.0) + pi) / two_pi;
      y -= std::floor(y);
      const double x = std::sqrt(std::acos(m.z) / (0.5 * pi));
      // The slices' factor (1 + slice) interpolated linearly in theta_o (values 0, 0.5, 1) and phi_o.
      double slice_factor = 1.0 + std::min(theta_o, 1.0) / 0.5;
      if (!iso) {
        const double pp = std::clamp((phi_o + pi) / (pi / 2), 0.0, 4.0);
        slice_factor = 1.0 + pp * 3.0 + std::min(theta_o, 1.0) / 0.5;  // slice = phi_index * 3 + theta_index
      }
      const Rgb e = f.eval(wi, wo);
      const double want[3] = {slice_factor * g(0, x, y), slice_factor * g(1, x, y), slice_factor * g(2, x, y)};
      worst = std::max({worst, std::abs(e.r - want[0]), std::abs(e.g - want[1]), std::abs(e.b - want[2])});
    }
    EXPECT_LE(worst, 1e-6) << (iso ? "isotropic" : "anisotropic");
  }
  const RglBrdf f = brdf_of(uniform_spec(g));
  EXPECT_EQ(f.eval({0.0, 0.6, -0.8}, {0.0, 0.0, 1.0}).r, 0.0);
  EXPECT_EQ(f.eval({0.0, 0.0, 1.0}, {0.6, 0.0, -0.8}).r, 0.0);
}

// At the table's nodes the stored values (times ndf / (4 sigma)); in a cell between its corners' values.
TEST(Rgl, AtTableNodesItIsTheTableAndBetweenThemBetweenTheNeighbours) {
  Pcg32 rng(3);
  Spec s = uniform_spec([&](int, double, double) { return 0.05 + rng.next_double(); });
  std::fill(s.ndf.begin(), s.ndf.end(), 3.0);   // ndf / (4 sigma) = 3 / 2
  const RglBrdf f = brdf_of(s);
  const Vec3 wo = spherical(0.5, 0.3);  // at the theta_i value 0.5: slice 1 alone
  const auto stored = [&](int c, int x, int y) {
    return static_cast<double>(static_cast<float>(s.rgb[(static_cast<std::size_t>(3 + c) * 5 + static_cast<std::size_t>(y)) * 5 + static_cast<std::size_t>(x)]));
  };
  int nodes = 0, cells = 0;
  // From x = 1: at x = 0 (theta_m = 0) every y is the one direction wm = n.
  for (int x = 1; x < 5; ++x) {
    for (int y = 0; y < 5; ++y) {
      const double theta_m = (x / 4.0) * (x / 4.0) * 0.5 * pi, phi_m = 0.3 + (y / 4.0) * two_pi - pi;
      const Vec3 wi = mirrored(wo, theta_m, phi_m);
      if (!(wi.z > 1e-3) || y == 4) continue;  // y = 4 wraps to y = 0 (u_m.y in [0, 1))
      const Rgb e = f.eval(wi, wo);
      EXPECT_NEAR(e.r, 1.5 * stored(0, x, y), 1e-5) << x << " " << y;
      EXPECT_NEAR(e.b, 1.5 * stored(2, x, y), 1e-5) << x << " " << y;
      ++nodes;
      if (x == 4) continue;
      // The cell's centre: between its four corners.
      const double xc = (x + 0.5) / 4.0;
      const Vec3 wc = mirrored(wo, xc * xc * 0.5 * pi, 0.3 + ((y + 0.5) / 4.0) * two_pi - pi);
      if (!(wc.z > 1e-3)) continue;
      const double g = f.eval(wc, wo).g / 1.5;
      const double lo = std::min({stored(1, x, y), stored(1, x + 1, y), stored(1, x, y + 1), stored(1, x + 1, y + 1)});
      const double hi = std::max({stored(1, x, y), stored(1, x + 1, y), stored(1, x, y + 1), stored(1, x + 1, y + 1)});
      EXPECT_GE(g, lo - 1e-6);
      EXPECT_LE(g, hi + 1e-6);
      EXPECT_GT(hi - lo, 1e-3);  // a cell whose corners differ
      ++cells;
    }
  }
  EXPECT_GE(nodes, 8);
  EXPECT_GE(cells, 6);
}

// A normalized warp with two parameters: sample and invert are inverses, the density integrates to 1 (the
// midpoint rule on sub-cells, exact for a bilinear function) and is the Jacobian determinant of invert.
TEST(Rgl, TheWarpIsItsDefinition) {
  Pcg32 rng(9);
  const int w = 6, h = 5;
  std::vector<double> data(2 * 3 * static_cast<std::size_t>(w * h));
  for (auto& v : data) v = 0.1 + rng.next_double() * rng.next_double() * 4.0;
  const RglWarp warp(w, h, {{-1.0, 1.0}, {0.0, 0.3, 0.9}}, data, true);
  for (const auto& p : std::vector<std::array<double, 2>>{{-1.0, 0.0}, {0.2, 0.5}, {1.0, 0.9}, {0.7, 2.0}}) {
    double integral = 0.0;
    const int sub = 8;
    for (int i = 0; i < (w - 1) * sub; ++i) {
      for (int j = 0; j < (h - 1) * sub; ++j) {
        integral += warp.eval({(i + 0.5) / ((w - 1) * sub), (j + 0.5) / ((h - 1) * sub)}, p);
      }
    }
    integral /= static_cast<double>((w - 1) * sub * (h - 1) * sub);
    EXPECT_NEAR(integral, 1.0, 1e-12);
    double worst_round = 0.0, worst_density = 0.0, worst_jacobian = 0.0;
    for (int k = 0; k < 500; ++k) {
      const Vec2 u{rng.next_double(), rng.next_double()};
      const auto [x, density] = warp.sample(u, p);
      const auto [back, density2] = warp.invert(x, p);
      worst_round = std::max({worst_round, std::abs(back.x - u.x), std::abs(back.y - u.y)});
      worst_density = std::max({worst_density, std::abs(density - warp.eval(x, p)), std::abs(density2 - density)});
      // d(invert)/dx by central differences away from cell edges.
      const double e = 1e-6;
      if (x.x < 2 * e || x.x > 1 - 2 * e || x.y < 2 * e || x.y > 1 - 2 * e) continue;
      const Vec2 ax = warp.invert({x.x + e, x.y}, p).first, bx = warp.invert({x.x - e, x.y}, p).first;
      const Vec2 ay = warp.invert({x.x, x.y + e}, p).first, by = warp.invert({x.x, x.y - e}, p).first;
      const double det = ((ax.x - bx.x) * (ay.y - by.y) - (ay.x - by.x) * (ax.y - bx.y)) / (4 * e * e);
      worst_jacobian = std::max(worst_jacobian, std::abs(det - density) / density);
    }
    EXPECT_LE(worst_round, 1e-9);
    EXPECT_LE(worst_density, 1e-9);
    EXPECT_LE(worst_jacobian, 1e-4);
  }
  // At a parameter value the warp is that slice's; between two values, the slices' linear mix.
  const RglWarp a(w, h, {}, std::vector<double>(data.begin() + 4 * w * h, data.begin() + 5 * w * h), true);
  const RglWarp b(w, h, {}, std::vector<double>(data.begin() + 5 * w * h, data.begin() + 6 * w * h), true);
  const Vec2 x{0.37, 0.61};
  EXPECT_NEAR(warp.eval(x, std::vector<double>{1.0, 0.3}), a.eval(x, {}), 1e-12);
  EXPECT_NEAR(warp.eval(x, std::vector<double>{1.0, 0.6}), 0.5 * (a.eval(x, {}) + b.eval(x, {})), 1e-12);
}

// A VNDF and luminance that are not uniform (a peaked lobe in u_m): the sampler's own pdf is pdf(); the mean of
// q / pdf over its samples, q the cosine density (which the mixture covers), is 1.
TEST(Rgl, SampleAndPdfAgree) {
  Spec s = uniform_spec([](int c, double x, double y) { return 0.2 + 0.1 * c + 0.3 * x * (1.0 - y); });
  s.nw = s.nh = 9;
  s.vndf.clear();
  s.luminance.clear();
  s.rgb.clear();
  for (std::size_t sl = 0; sl < s.slices(); ++sl) {
    for (int y = 0; y < 9; ++y) {
      for (int x = 0; x < 9; ++x) {
        const double u = x / 8.0, v = y / 8.0;
        s.vndf.push_back(std::exp(-8.0 * u * u) * (1.2 + std::cos(two_pi * v)) + 0.01 * static_cast<double>(sl));
        s.luminance.push_back(0.3 + u * v + 0.2 * static_cast<double>(sl));
      }
    }
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 81; ++k) s.rgb.push_back(0.1 + 0.05 * c + 0.001 * k);
    }
  }
  const RglBrdf f = brdf_of(s);
  // Pairs whose half vector is the normal or all but: a finite density (0 exactly at the normal).
  for (const double t : {0.0, 1e-300, 1e-200, 1e-100, 1e-20, 1e-8}) {
    const Vec3 wo = spherical(0.5, 0.4), wi = mirrored(wo, t, 1.0);
    const double p = f.pdf(wi, wo);
    EXPECT_TRUE(std::isfinite(p) && p >= 0.0) << t << " " << p;
  }
  for (const double theta_o : {0.2, 0.7, 1.3}) {
    const Vec3 wo = spherical(theta_o, 0.4);
    // The warp part integrates to 1 over the sphere: in the warp's coordinates u of the half vector,
    // d(omega_i) = 4 |wo . wm| 2 pi^2 u_x sin theta_m du (the midpoint rule on 200 x 200; smooth there).
    double integral = 0.0;
    const int m = 200;
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < m; ++j) {
        const double ux = (i + 0.5) / m, uy = (j + 0.5) / m;
        const double theta_m = ux * ux * 0.5 * pi, phi_m = (2.0 * uy - 1.0) * pi + 0.4;
        const Vec3 wm = spherical(theta_m, phi_m);
        const Vec3 wi = mirrored(wo, theta_m, phi_m);
        integral += f.warp_pdf(wo, wi) * 4.0 * std::abs(dot(wo, wm)) * 2.0 * pi * pi * ux * std::sin(theta_m);
      }
    }
    integral /= static_cast<double>(m) * m;
    EXPECT_NEAR(integral, 1.0, 1e-4) << "theta_o " << theta_o;  // with the loader's floor on the Jacobian: 0.994-0.995
    Pcg32 rng(17);
    const int n = 200000;
    double sum = 0.0, sum2 = 0.0, worst = 0.0;
    int below = 0;
    for (int k = 0; k < n; ++k) {
      const BrdfSample b = f.sample(wo, {rng.next_double(), rng.next_double()}, rng.next_double());
      ASSERT_GT(b.pdf, 0.0);
      worst = std::max(worst, std::abs(b.pdf - f.pdf(b.wi, wo)) / b.pdf);
      if (!(b.wi.z > 0.0)) {
        ++below;
        continue;
      }
      const double r = (b.wi.z * inv_pi) / b.pdf;
      sum += r;
      sum2 += r * r;
    }
    const double mean = sum / n, sd = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_LE(worst, 1e-9);
    EXPECT_NEAR(mean, 1.0, 5.0 * sd + 1e-3) << "theta_o " << theta_o << " sd " << sd << " below " << below;
    std::printf("[ rgl ] theta_o %.1f: warp pdf integral %.6f; mean of q/pdf %.5f (sd %.5f), %d of %d samples below the horizon\n",
                theta_o, integral, mean, sd, below, n);
  }
}

TEST(Rgl, ReadsAFileAndRefusesATruncatedOne) {
  const auto dir = std::filesystem::temp_directory_path() / ("shadelab-rgl-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  const Spec s = uniform_spec([](int, double x, double) { return 0.25 + x; });
  const auto bytes = s.bytes();
  {
    std::ofstream out(dir / "a.bsdf", std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    std::ofstream cut(dir / "cut.bsdf", std::ios::binary);
    cut.write(bytes.data(), static_cast<std::streamsize>(bytes.size() - 100));
  }
  auto f = read_rgl_brdf(dir / "a.bsdf");
  ASSERT_TRUE(f.has_value()) << f.error().message;
  EXPECT_GT((*f)->eval(spherical(0.3, 0.0), spherical(0.3, pi)).r, 0.0);
  auto cut = read_rgl_brdf(dir / "cut.bsdf");
  ASSERT_FALSE(cut.has_value());
  EXPECT_NE(cut.error().message.find((dir / "cut.bsdf").string()), std::string::npos) << cut.error().message;
  EXPECT_NE(cut.error().message.find("does not fit in the file"), std::string::npos) << cut.error().message;
  auto missing = read_rgl_brdf(dir / "none.bsdf");
  ASSERT_FALSE(missing.has_value());
  EXPECT_NE(missing.error().message.find("none.bsdf: cannot read"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shadelab
