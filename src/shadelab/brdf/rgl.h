// shadelab RGL/EPFL tensor `.bsdf` files (Dupuy & Jakob 2018, "An Adaptive Parameterization for Efficient Material
// Acquisition and Rendering", ACM TOG 37(6); the data at rgl.epfl.ch/materials; the layout and the evaluation
// that the authors' loader, powitacq_rgb, uses).
//
// The tensor container, little-endian:
//   char magic[12] = "tensor_file\0";  uint8 version[2] = {1, 0};  uint32 field_count
//   per field: uint16 name_length, char name[name_length], uint16 ndim, uint8 dtype, uint64 offset,
//              uint64 shape[ndim]
//   each field's data: prod(shape) values of its dtype at byte `offset` of the file, C order (last index fastest).
//   dtype: 1 uint8, 2 int8, 3 uint16, 4 int16, 5 uint32, 6 int32, 7 uint64, 8 int64, 9 float16, 10 float32,
//          11 float64 (0 and anything above 11 refused).
// The RGB BRDF (the `_rgb.bsdf` files): float32 theta_i[nt], phi_i[np] (radians, increasing); float32 ndf[a][b],
// sigma[c][d]; float32 vndf[np][nt][h][w], luminance[np][nt][h][w], rgb[np][nt][3][h][w]; uint8 description[n],
// jacobian[1]. A file is isotropic when np <= 2; an anisotropic one must cover 2 pi in phi_i (the loader's
// "reduction" of 1). The spectral files (`spectra`, `wavelengths` instead of `rgb`) are refused: RGB only.
//
// Evaluation (powitacq_rgb's BRDF::eval, in double): for the pair the loader calls (wi, wo), with its wi the
// direction the table is conditioned on, f = rgb(s; phi_i, theta_i, c) ndf(u_m) / (4 sigma(u_i)), where
//   u(theta, phi) = (sqrt(theta / (pi/2)), (phi + pi) / 2pi)   (the loader's theta2u, phi2u),
//   u_m = u(wm) with wm = normalize(wi + wo), its phi taken relative to phi_i for an isotropic file, wrapped to [0, 1),
//   s = the vndf warp's inverse at u_m (the point of the unit square that its sampler maps to u_m).
// Each 2D table is a bilinear interpolant on the unit square (nodes at i/(n-1)), linear in its parameters between
// the two neighbouring parameter values (clamped at the ends). vndf and luminance are densities: each slice is
// normalized to integrate to 1. shadelab's eval(wi, wo) is the loader's eval(wo, wi): the table is conditioned on the
// viewer, as Mitsuba's `measured` plugin does, so that sampling from the viewer uses the file's warps.
// The RGB values are clamped at 0 (the loader's POWITACQ_CLIP_RGB; the data has small negatives out of gamut).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "shadelab/brdf/brdf.h"
#include "shadelab/core/error.h"
#include "shadelab/core/vec.h"

namespace shadelab {

enum class TensorDtype : std::uint8_t {
  invalid = 0, u8, i8, u16, i16, u32, i32, u64, i64, f16, f32, f64
};
std::size_t tensor_dtype_size(TensorDtype t);  // 0 for invalid
const char* tensor_dtype_name(TensorDtype t);

struct TensorField {
  std::string name;
  TensorDtype dtype = TensorDtype::invalid;
  std::uint64_t offset = 0;              // byte offset of the data in the file
  std::vector<std::uint64_t> shape;
  std::size_t count = 0;                 // product of shape
};

// A parsed container: the fields and the file's bytes (each field's data is inside them: offset + count x size <=
// the file's size, checked).
struct TensorFile {
  std::vector<char> bytes;
  std::vector<TensorField> fields;
  const TensorField* find(const std::string& name) const;
  // The values of a float32 field, widened.
  std::vector<double> floats(const TensorField& f) const;
};

// Parses a container; `name` names the file in errors. Refused, each in one line naming the file and the field:
// a file shorter than the 18-byte header, a wrong magic, a version other than 1.0, a field header past the end,
// a dtype 0 or above 11, a shape whose product overflows, data past the end of the file (a rank-0 field is one value).
Result<TensorFile> parse_tensor_file(std::vector<char> bytes, const std::string& name);

// One field to write (the test's and the fuzz seeds' writer).
struct TensorFieldData {
  std::string name;
  TensorDtype dtype = TensorDtype::f32;
  std::vector<std::uint64_t> shape;
  std::vector<char> data;  // prod(shape) x dtype size bytes
};
std::vector<char> encode_tensor_file(const std::vector<TensorFieldData>& fields);
TensorFieldData tensor_f32(const std::string& name, std::vector<std::uint64_t> shape, const std::vector<double>& values);
TensorFieldData tensor_u8(const std::string& name, std::vector<std::uint64_t> shape, const std::vector<std::uint8_t>& values);

// The loader's marginal-conditional warp (Marginal2D): a w x h table (x fastest) per slice, slices over up to
// three parameters (outermost first), bilinear in (x, y) on the unit square and linear between parameter values.
class RglWarp {
 public:
  RglWarp() = default;
  // data: slices x h x w values; param_values[d] the increasing values of parameter d. normalized: each slice
  // divided by its integral (its bilinear interpolant's), and the CDFs built for invert / sample.
  RglWarp(int w, int h, std::vector<std::vector<double>> param_values, const std::vector<double>& data, bool normalized);

  double eval(Vec2 pos, std::span<const double> params) const;
  // The inverse of sample: the point of the unit square that sample maps to `pos`, and the density at pos.
  std::pair<Vec2, double> invert(Vec2 pos, std::span<const double> params) const;
  // Marginal in y, then conditional in x (normalized warps only): the point and its density.
  std::pair<Vec2, double> sample(Vec2 u, std::span<const double> params) const;
  // The integral of a slice's bilinear interpolant over the unit square (before normalization).
  static double slice_integral(int w, int h, const double* v);

 private:
  struct Weights {
    std::size_t slice = 0;                 // the first corner's slice
    std::array<std::size_t, 3> stride{};   // slice stride per parameter (0 where it has one value)
    std::array<double, 6> w{};             // (1 - t, t) per parameter
  };
  Weights weights(std::span<const double> params) const;
  double lookup(const std::vector<double>& v, std::size_t in_slice, std::size_t slice_size, const Weights& k) const;

  int m_w = 0, m_h = 0;
  std::vector<std::vector<double>> m_params;
  std::vector<double> m_data, m_cond, m_marg;
};

struct RglTable {
  std::vector<double> theta_i, phi_i;
  bool isotropic = true;
  bool jacobian = false;
  std::string description;
  RglWarp ndf, sigma, vndf, luminance, rgb;
};

// Builds the BRDF's tables from a parsed container; errors name the file and the field (missing field, wrong
// dtype, wrong rank, shapes that disagree, a NaN or infinite value, a negative or zero-integral density slice,
// a sigma value <= 0, parameter values not increasing, an anisotropic file not covering 2 pi, a spectral file).
Result<RglTable> rgl_table(const TensorFile& file, const std::string& name);
Result<RglTable> parse_rgl(std::vector<char> bytes, const std::string& name);
Result<RglTable> read_rgl(const std::filesystem::path& path);

// eval: the loader's (above). sample / pdf: a one-sample mixture with an exact pdf: with probability 0.1 the cosine
// lobe, else the file's own warps as the loader samples (luminance, then the vndf warp, then the mirror of wo about
// the sampled microfacet normal), whose density per solid angle is
//   p = luminance(s) vndf(u_m) / (2 pi^2 u_m.x sin theta_m) / (4 |wo . wm|)
// with the exact Jacobian (the loader floors its first factor at 1e-6, which loses mass near the normal: rgl.cpp).
class RglBrdf final : public Brdf {
 public:
  static constexpr double cosine_share = 0.1;
  explicit RglBrdf(std::shared_ptr<const RglTable> table);
  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  double pdf(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, Vec2 u, double u_lobe) const override;
  bool is_reciprocal() const override { return false; }
  bool is_tabulated() const override { return true; }  // interpolated between measured directions (brdf.h)
  const RglTable& table() const { return *m_table; }
  // The loader's eval(wi, wo) in its own naming (wi: the direction the table is conditioned on).
  Rgb loader_eval(const Vec3& wi, const Vec3& wo) const;
  // The warp part's density of wo given the conditioning direction wi (the loader's pdf without its clamps).
  double warp_pdf(const Vec3& wi, const Vec3& wo) const;

 private:
  std::shared_ptr<const RglTable> m_table;
};

Result<BrdfPtr> read_rgl_brdf(const std::filesystem::path& path);

}  // namespace shadelab
