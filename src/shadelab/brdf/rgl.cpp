#include "shadelab/brdf/rgl.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <system_error>

#include "shadelab/core/constants.h"
#include "shadelab/core/text.h"
#include "shadelab/sampling/warp.h"

namespace shadelab {

static_assert(std::endian::native == std::endian::little, "tensor files are little-endian; this reader assumes the host is");

namespace {

constexpr char tensor_magic[12] = {'t', 'e', 'n', 's', 'o', 'r', '_', 'f', 'i', 'l', 'e', '\0'};
constexpr std::size_t tensor_header_bytes = 12 + 2 + 4;

template <class T>
T load(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}
template <class T>
void append(std::vector<char>& out, T v) {
  const auto at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &v, sizeof(T));
}

// The loader's theta2u and phi2u: u = sqrt(theta / (pi/2)), (phi + pi) / 2pi.
double theta_to_u(double theta) { return std::sqrt(std::max(theta, 0.0) * (2.0 / pi)); }
double phi_to_u(double phi) { return (phi + pi) / two_pi; }
// Their inverses (the loader's u2theta, u2phi).
double u_to_theta(double u) { return u * u * (0.5 * pi); }
double u_to_phi(double u) { return (2.0 * u - 1.0) * pi; }
// The loader's elevation: acos(z) written as 2 asin(|d - n| / 2), accurate near the pole.
double elevation(const Vec3& d) {
  return 2.0 * std::asin(std::min(1.0, 0.5 * std::sqrt(d.x * d.x + d.y * d.y + (d.z - 1.0) * (d.z - 1.0))));
}

// A shape for a message: at most 6 sizes, then how many there are (a file may claim 65535).
std::string shape_text(const std::vector<std::uint64_t>& s) {
  std::string t = "[";
  for (std::size_t i = 0; i < s.size() && i < 6; ++i) t += (i ? ", " : "") + std::to_string(s[i]);
  if (s.size() > 6) t += ", ... (" + std::to_string(s.size()) + " sizes)";
  return t + "]";
}

// Clamped to [0, 1], NaN to 0.
double unit(double x) { return x >= 0.0 ? std::min(x, 1.0) : 0.0; }

}  // namespace

std::size_t tensor_dtype_size(TensorDtype t) {
  switch (t) {
    case TensorDtype::u8: case TensorDtype::i8: return 1;
    case TensorDtype::u16: case TensorDtype::i16: case TensorDtype::f16: return 2;
    case TensorDtype::u32: case TensorDtype::i32: case TensorDtype::f32: return 4;
    case TensorDtype::u64: case TensorDtype::i64: case TensorDtype::f64: return 8;
    default: return 0;
  }
}

const char* tensor_dtype_name(TensorDtype t) {
  static const char* names[] = {"invalid", "uint8", "int8", "uint16", "int16", "uint32", "int32",
                                "uint64", "int64", "float16", "float32", "float64"};
  const auto i = static_cast<std::size_t>(t);
  return i < 12 ? names[i] : "unknown";
}

const TensorField* TensorFile::find(const std::string& name) const {
  for (const auto& f : fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

std::vector<double> TensorFile::floats(const TensorField& f) const {
  std::vector<double> v(f.count);
  const char* p = bytes.data() + f.offset;
  for (std::size_t i = 0; i < f.count; ++i) v[i] = static_cast<double>(load<float>(p + 4 * i));
  return v;
}

Result<TensorFile> parse_tensor_file(std::vector<char> bytes, const std::string& name) {
  const std::size_t size = bytes.size();
  if (size < tensor_header_bytes) {
    return make_error(name + ": truncated: " + std::to_string(size) + " bytes, a tensor file has an 18-byte header");
  }
  if (std::memcmp(bytes.data(), tensor_magic, 12) != 0) {
    return make_error(name + ": not a tensor file: the first 12 bytes are not \"tensor_file\\0\"");
  }
  const auto major = static_cast<unsigned char>(bytes[12]), minor = static_cast<unsigned char>(bytes[13]);
  if (major != 1 || minor != 0) {
    return make_error(name + ": tensor file version " + std::to_string(major) + "." + std::to_string(minor) + ", only 1.0 is read");
  }
  const auto n_fields = load<std::uint32_t>(bytes.data() + 14);
  // Each field header takes at least 13 bytes (name length, ndim, dtype, offset).
  if (n_fields > (size - tensor_header_bytes) / 13) {
    return make_error(name + ": " + std::to_string(n_fields) + " fields cannot fit in " + std::to_string(size) + " bytes: truncated");
  }
  TensorFile t;
  t.fields.reserve(n_fields);
  std::size_t p = tensor_header_bytes;
  for (std::uint32_t i = 0; i < n_fields; ++i) {
    const std::string which = "field " + std::to_string(i);
    if (size - p < 2) return make_error(name + ": " + which + ": truncated before its name length");
    const auto name_length = load<std::uint16_t>(bytes.data() + p);
    p += 2;
    if (size - p < name_length) return make_error(name + ": " + which + ": truncated in its name");
    TensorField f;
    f.name.assign(bytes.data() + p, name_length);
    p += name_length;
    const std::string fname = which + " (\"" + printable(f.name) + "\")";  // a name from the file: escaped, cut
    if (size - p < 11) return make_error(name + ": " + fname + ": truncated before its dtype and offset");
    const auto ndim = load<std::uint16_t>(bytes.data() + p);
    const auto dtype = static_cast<std::uint8_t>(bytes[p + 2]);
    f.offset = load<std::uint64_t>(bytes.data() + p + 3);
    p += 11;
    if (dtype == 0 || dtype > 11) return make_error(name + ": " + fname + ": unknown dtype " + std::to_string(dtype));
    f.dtype = static_cast<TensorDtype>(dtype);
    if ((size - p) / 8 < ndim) return make_error(name + ": " + fname + ": truncated in its shape of " + std::to_string(ndim) + " dimensions");
    f.shape.resize(ndim);
    for (std::size_t j = 0; j < ndim; ++j) f.shape[j] = load<std::uint64_t>(bytes.data() + p + 8 * j);
    p += 8 * static_cast<std::size_t>(ndim);
    if (f.offset > size) {
      return make_error(name + ": " + fname + ": data offset " + std::to_string(f.offset) + " is past the end of the file (" +
                        std::to_string(size) + " bytes)");
    }
    // The bytes from the offset bound the value count; the product is checked against that bound as it grows, so
    // it never overflows.
    const std::uint64_t limit = (size - f.offset) / tensor_dtype_size(f.dtype);
    const bool empty = std::find(f.shape.begin(), f.shape.end(), std::uint64_t{0}) != f.shape.end();
    std::uint64_t count = 1;
    for (std::size_t j = 0; j < ndim && !empty; ++j) {
      if (f.shape[j] > limit / count) {
        return make_error(name + ": " + fname + ": shape " + shape_text(f.shape) + " of " + tensor_dtype_name(f.dtype) +
                          " does not fit in the file after offset " + std::to_string(f.offset));
      }
      count *= f.shape[j];
    }
    if (!empty && count > limit) {  // a rank-0 field is one value
      return make_error(name + ": " + fname + ": one " + tensor_dtype_name(f.dtype) + " value (rank 0) does not fit in the file after offset " +
                        std::to_string(f.offset));
    }
    f.count = empty ? 0 : static_cast<std::size_t>(count);
    t.fields.push_back(std::move(f));
  }
  t.bytes = std::move(bytes);
  return t;
}

std::vector<char> encode_tensor_file(const std::vector<TensorFieldData>& fields) {
  std::vector<char> out(tensor_magic, tensor_magic + 12);
  out.push_back(1);
  out.push_back(0);
  append(out, static_cast<std::uint32_t>(fields.size()));
  std::size_t header = out.size();
  for (const auto& f : fields) header += 2 + f.name.size() + 2 + 1 + 8 + 8 * f.shape.size();
  std::uint64_t offset = header;
  for (const auto& f : fields) {
    append(out, static_cast<std::uint16_t>(f.name.size()));
    out.insert(out.end(), f.name.begin(), f.name.end());
    append(out, static_cast<std::uint16_t>(f.shape.size()));
    out.push_back(static_cast<char>(f.dtype));
    append(out, offset);
    for (auto s : f.shape) append(out, s);
    offset += f.data.size();
  }
  for (const auto& f : fields) out.insert(out.end(), f.data.begin(), f.data.end());
  return out;
}

TensorFieldData tensor_f32(const std::string& name, std::vector<std::uint64_t> shape, const std::vector<double>& values) {
  TensorFieldData f{name, TensorDtype::f32, std::move(shape), std::vector<char>(4 * values.size())};
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto v = static_cast<float>(values[i]);
    std::memcpy(f.data.data() + 4 * i, &v, 4);
  }
  return f;
}

TensorFieldData tensor_u8(const std::string& name, std::vector<std::uint64_t> shape, const std::vector<std::uint8_t>& values) {
  return TensorFieldData{name, TensorDtype::u8, std::move(shape), std::vector<char>(values.begin(), values.end())};
}

// ---------------------------------------------------------------------------------------------------------------
// The warp (powitacq's Marginal2D, in double).

double RglWarp::slice_integral(int w, int h, const double* v) {
  // The bilinear interpolant's integral over a cell is the mean of its four corners times the cell's area.
  double sum = 0.0;
  for (int y = 0; y + 1 < h; ++y) {
    for (int x = 0; x + 1 < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      sum += 0.25 * (v[i] + v[i + 1] + v[i + static_cast<std::size_t>(w)] + v[i + static_cast<std::size_t>(w) + 1]);
    }
  }
  return sum / (static_cast<double>(w - 1) * static_cast<double>(h - 1));
}

RglWarp::RglWarp(int w, int h, std::vector<std::vector<double>> param_values, const std::vector<double>& data, bool normalized)
    : m_w(w), m_h(h), m_params(std::move(param_values)), m_data(data) {
  if (!normalized) return;
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  const std::size_t slices = data.size() / n;
  m_cond.assign(data.size(), 0.0);
  m_marg.assign(slices * static_cast<std::size_t>(h), 0.0);
  for (std::size_t s = 0; s < slices; ++s) {
    double* d = m_data.data() + s * n;
    double* c = m_cond.data() + s * n;
    double* m = m_marg.data() + s * static_cast<std::size_t>(h);
    // Conditional CDF along each row by the trapezoid rule (exact for the linear interpolant), in cell units.
    for (int y = 0; y < h; ++y) {
      const std::size_t r = static_cast<std::size_t>(y) * static_cast<std::size_t>(w);
      c[r] = 0.0;
      for (int x = 0; x + 1 < w; ++x) c[r + static_cast<std::size_t>(x) + 1] = c[r + static_cast<std::size_t>(x)] + 0.5 * (d[r + static_cast<std::size_t>(x)] + d[r + static_cast<std::size_t>(x) + 1]);
    }
    // Marginal CDF over rows: the trapezoid rule on the row totals (the integral along x is linear in y).
    m[0] = 0.0;
    for (int y = 0; y + 1 < h; ++y) {
      const double r0 = c[static_cast<std::size_t>(y + 1) * static_cast<std::size_t>(w) - 1];
      const double r1 = c[static_cast<std::size_t>(y + 2) * static_cast<std::size_t>(w) - 1];
      m[y + 1] = m[y] + 0.5 * (r0 + r1);
    }
    // Normalize: the total in cell units is the marginal's last value (rgl_table refuses a zero one).
    const double k = 1.0 / m[h - 1];
    for (std::size_t i = 0; i < n; ++i) {
      d[i] *= k;
      c[i] *= k;
    }
    for (int y = 0; y < h; ++y) m[y] *= k;
  }
}

RglWarp::Weights RglWarp::weights(std::span<const double> params) const {
  Weights k;
  std::size_t stride = 1;
  for (std::size_t d = m_params.size(); d-- > 0;) {
    const auto& v = m_params[d];
    const std::size_t n = v.size();
    if (n == 1) {
      k.w[2 * d] = 1.0;
      k.w[2 * d + 1] = 0.0;
      k.stride[d] = 0;
      continue;
    }
    const double p = params[d];
    // The interval [v[i], v[i+1]] with v[i] <= p (the first one below v[0], the last one above the end).
    std::size_t i = static_cast<std::size_t>(std::upper_bound(v.begin(), v.end(), p) - v.begin());
    i = std::min(i == 0 ? 0 : i - 1, n - 2);
    const double t = unit((p - v[i]) / (v[i + 1] - v[i]));  // linear between the two values, clamped
    k.w[2 * d] = 1.0 - t;
    k.w[2 * d + 1] = t;
    k.stride[d] = stride;
    k.slice += i * stride;
    stride *= n;
  }
  return k;
}

double RglWarp::lookup(const std::vector<double>& v, std::size_t in_slice, std::size_t slice_size, const Weights& k) const {
  const std::size_t dims = m_params.size();
  double sum = 0.0;
  for (std::size_t corner = 0; corner < (std::size_t{1} << dims); ++corner) {
    double w = 1.0;
    std::size_t slice = k.slice;
    for (std::size_t d = 0; d < dims; ++d) {
      const std::size_t bit = (corner >> d) & 1;
      w *= k.w[2 * d + bit];
      slice += bit * k.stride[d];
    }
    if (w != 0.0) sum += w * v[slice * slice_size + in_slice];
  }
  return sum;
}

double RglWarp::eval(Vec2 pos, std::span<const double> params) const {
  const Weights k = weights(params);
  const double fx = unit(pos.x) * (m_w - 1), fy = unit(pos.y) * (m_h - 1);
  const int ix = std::min(static_cast<int>(fx), m_w - 2), iy = std::min(static_cast<int>(fy), m_h - 2);
  const double tx = fx - ix, ty = fy - iy;
  const std::size_t n = static_cast<std::size_t>(m_w) * static_cast<std::size_t>(m_h);
  const std::size_t i = static_cast<std::size_t>(iy) * static_cast<std::size_t>(m_w) + static_cast<std::size_t>(ix);
  const std::size_t w = static_cast<std::size_t>(m_w);
  const double v00 = lookup(m_data, i, n, k), v10 = lookup(m_data, i + 1, n, k);
  const double v01 = lookup(m_data, i + w, n, k), v11 = lookup(m_data, i + w + 1, n, k);
  // Bilinear interpolation; a normalized warp's values are in cell units, times the cell count per unit area.
  const double f = (1.0 - ty) * ((1.0 - tx) * v00 + tx * v10) + ty * ((1.0 - tx) * v01 + tx * v11);
  return m_cond.empty() ? f : f * (m_w - 1) * (m_h - 1);
}

std::pair<Vec2, double> RglWarp::invert(Vec2 pos, std::span<const double> params) const {
  const Weights k = weights(params);
  const double fx = unit(pos.x) * (m_w - 1), fy = unit(pos.y) * (m_h - 1);
  const int ix = std::min(static_cast<int>(fx), m_w - 2), iy = std::min(static_cast<int>(fy), m_h - 2);
  const double tx = fx - ix, ty = fy - iy;
  const std::size_t n = static_cast<std::size_t>(m_w) * static_cast<std::size_t>(m_h);
  const std::size_t w = static_cast<std::size_t>(m_w);
  const std::size_t row = static_cast<std::size_t>(iy) * w;
  const std::size_t i = row + static_cast<std::size_t>(ix);
  const double v00 = lookup(m_data, i, n, k), v10 = lookup(m_data, i + 1, n, k);
  const double v01 = lookup(m_data, i + w, n, k), v11 = lookup(m_data, i + w + 1, n, k);
  // The density along x at this y, linear in x within the cell: c0 at its left edge, c1 at its right.
  const double c0 = (1.0 - ty) * v00 + ty * v01, c1 = (1.0 - ty) * v10 + ty * v11;
  const double density = (1.0 - tx) * c0 + tx * c1;
  // x: the CDF to the cell's left edge (the rows' CDFs, linear in y) plus the integral of the linear density
  // over [0, tx] (tx c0 + tx^2 (c1 - c0) / 2), over the row's total.
  const double left = (1.0 - ty) * lookup(m_cond, i, n, k) + ty * lookup(m_cond, i + w, n, k);
  const double r0 = lookup(m_cond, row + w - 1, n, k), r1 = lookup(m_cond, row + 2 * w - 1, n, k);
  const double total = (1.0 - ty) * r0 + ty * r1;
  const double ux = total > 0.0 ? (left + tx * (c0 + 0.5 * tx * (c1 - c0))) / total : (ix + tx) / (m_w - 1);
  // y: the marginal CDF to the row plus the integral of the linear row total over [0, ty].
  const double uy = lookup(m_marg, static_cast<std::size_t>(iy), static_cast<std::size_t>(m_h), k) + ty * (r0 + 0.5 * ty * (r1 - r0));
  return {{unit(ux), unit(uy)}, density * (m_w - 1) * (m_h - 1)};
}

namespace {
// The root t in [0, 1] of a t + b t^2 / 2 = c (the integral of the linear density a + b t), written without
// cancellation: t = 2c / (a + sqrt(a^2 + 2 b c)).
double linear_cdf_root(double a, double b, double c) {
  const double den = a + std::sqrt(std::max(0.0, a * a + 2.0 * b * c));
  return den > 0.0 ? unit(2.0 * c / den) : 0.0;
}
}  // namespace

std::pair<Vec2, double> RglWarp::sample(Vec2 u, std::span<const double> params) const {
  const Weights k = weights(params);
  const std::size_t n = static_cast<std::size_t>(m_w) * static_cast<std::size_t>(m_h);
  const std::size_t w = static_cast<std::size_t>(m_w);
  const std::size_t hs = static_cast<std::size_t>(m_h);
  const double uy = unit(u.y), ux0 = unit(u.x);
  // The row: the last with marginal CDF <= uy (binary search over the monotone interpolated CDF).
  std::size_t lo = 0, hi = hs - 2;
  while (lo < hi) {
    const std::size_t mid = (lo + hi + 1) / 2;
    if (lookup(m_marg, mid, hs, k) <= uy) lo = mid; else hi = mid - 1;
  }
  const std::size_t iy = lo, row = iy * w;
  const double r0 = lookup(m_cond, row + w - 1, n, k), r1 = lookup(m_cond, row + 2 * w - 1, n, k);
  const double ty = linear_cdf_root(r0, r1 - r0, uy - lookup(m_marg, iy, hs, k));
  // The column: the last with conditional CDF (linear in y between the two rows) <= ux x the row's total.
  const double target = ux0 * ((1.0 - ty) * r0 + ty * r1);
  const auto cond = [&](std::size_t x) { return (1.0 - ty) * lookup(m_cond, row + x, n, k) + ty * lookup(m_cond, row + w + x, n, k); };
  lo = 0;
  hi = w - 2;
  while (lo < hi) {
    const std::size_t mid = (lo + hi + 1) / 2;
    if (cond(mid) <= target) lo = mid; else hi = mid - 1;
  }
  const std::size_t ix = lo, i = row + ix;
  const double v00 = lookup(m_data, i, n, k), v10 = lookup(m_data, i + 1, n, k);
  const double v01 = lookup(m_data, i + w, n, k), v11 = lookup(m_data, i + w + 1, n, k);
  const double c0 = (1.0 - ty) * v00 + ty * v01, c1 = (1.0 - ty) * v10 + ty * v11;
  const double tx = linear_cdf_root(c0, c1 - c0, target - cond(ix));
  const Vec2 p{(static_cast<double>(ix) + tx) / (m_w - 1), (static_cast<double>(iy) + ty) / (m_h - 1)};
  return {p, ((1.0 - tx) * c0 + tx * c1) * (m_w - 1) * (m_h - 1)};
}

// ---------------------------------------------------------------------------------------------------------------
// The BRDF's fields.

Result<RglTable> rgl_table(const TensorFile& file, const std::string& name) {
  if (!file.find("rgb") && file.find("spectra")) {
    return make_error(name + ": a spectral tensor file (field \"spectra\"); only the RGB files (\"_rgb.bsdf\", field \"rgb\") are read");
  }
  const auto field = [&](const char* key, TensorDtype dtype, std::size_t rank) -> Result<const TensorField*> {
    const TensorField* f = file.find(key);
    if (!f) return make_error(name + ": no field \"" + key + "\"");
    if (f->dtype != dtype) {
      return make_error(name + ": field \"" + key + "\" is " + tensor_dtype_name(f->dtype) + ", expected " + tensor_dtype_name(dtype));
    }
    if (f->shape.size() != rank) {
      return make_error(name + ": field \"" + key + "\" has shape " + shape_text(f->shape) + ", expected " + std::to_string(rank) + " dimensions");
    }
    return f;
  };
  const char* keys[] = {"theta_i", "phi_i", "ndf", "sigma", "vndf", "luminance", "rgb", "description", "jacobian"};
  const TensorDtype types[] = {TensorDtype::f32, TensorDtype::f32, TensorDtype::f32, TensorDtype::f32, TensorDtype::f32,
                               TensorDtype::f32, TensorDtype::f32, TensorDtype::u8, TensorDtype::u8};
  const std::size_t ranks[] = {1, 1, 2, 2, 4, 4, 5, 1, 1};
  const TensorField* f[9];
  for (int i = 0; i < 9; ++i) {
    auto r = field(keys[i], types[i], ranks[i]);
    if (!r) return r.error();
    f[i] = *r;
  }
  const auto& [theta_f, phi_f, ndf_f, sigma_f, vndf_f, lum_f, rgb_f, desc_f, jac_f] = f;
  const auto bad_shape = [&](const TensorField* x, const std::string& what) {
    return make_error(name + ": field \"" + x->name + "\" has shape " + shape_text(x->shape) + ", " + what);
  };
  const std::uint64_t nt = theta_f->shape[0], np = phi_f->shape[0];
  if (nt < 1) return bad_shape(theta_f, "expected at least one value");
  if (np < 1) return bad_shape(phi_f, "expected at least one value");
  for (const TensorField* x : {ndf_f, sigma_f}) {
    if (x->shape[0] < 2 || x->shape[1] < 2) return bad_shape(x, "expected at least 2 x 2");
  }
  for (const TensorField* x : {vndf_f, lum_f}) {
    if (x->shape[0] != np || x->shape[1] != nt) return bad_shape(x, "expected [phi_i, theta_i, h, w] = [" + std::to_string(np) + ", " + std::to_string(nt) + ", ...]");
    if (x->shape[2] < 2 || x->shape[3] < 2) return bad_shape(x, "expected h, w >= 2");
  }
  if (lum_f->shape[2] != lum_f->shape[3]) return bad_shape(lum_f, "expected a square table (h = w), as the loader does");
  if (rgb_f->shape[0] != np || rgb_f->shape[1] != nt || rgb_f->shape[2] != 3 || rgb_f->shape[3] != lum_f->shape[2] ||
      rgb_f->shape[4] != lum_f->shape[3]) {
    return bad_shape(rgb_f, "expected [phi_i, theta_i, 3, h, w] with luminance's h, w");
  }
  if (jac_f->shape[0] != 1) return bad_shape(jac_f, "expected [1]");
  // Values: finite everywhere; densities non-negative; sigma positive (it divides).
  std::vector<double> v[7];
  for (int i = 0; i < 7; ++i) {
    v[i] = file.floats(*f[i]);
    for (std::size_t j = 0; j < v[i].size(); ++j) {
      if (!std::isfinite(v[i][j])) {
        return make_error(name + ": field \"" + std::string(keys[i]) + "\" value " + std::to_string(j) + " is not finite");
      }
      if ((i >= 2 && i <= 5) && (v[i][j] < 0.0 || (i == 3 && v[i][j] == 0.0))) {
        return make_error(name + ": field \"" + std::string(keys[i]) + "\" value " + std::to_string(j) + " is " +
                          (i == 3 ? "not positive" : "negative") + " (" + std::to_string(v[i][j]) + ")");
      }
    }
  }
  for (int i = 0; i < 2; ++i) {
    for (std::size_t j = 0; j + 1 < v[i].size(); ++j) {
      if (!(v[i][j + 1] > v[i][j])) return make_error(name + ": field \"" + std::string(keys[i]) + "\" is not increasing at value " + std::to_string(j + 1));
    }
  }
  RglTable t;
  t.theta_i = v[0];
  t.phi_i = v[1];
  t.isotropic = np <= 2;  // the loader's test
  if (!t.isotropic) {
    // The loader's reduction: the phi_i values must span the whole circle.
    // The span is printed, not the reduction: a tiny span makes 2 pi / span overflow any integer type.
    const double span = t.phi_i.back() - t.phi_i.front();
    const double reduction = std::rint(two_pi / span);
    if (reduction != 1.0) {
      char text[32];
      std::snprintf(text, sizeof text, "%.6g", span);
      return make_error(name + ": field \"phi_i\" spans " + text +
                        " rad, not the whole circle; only files covering 2 pi (reduction 1) are read, as the loader does");
    }
  }
  t.jacobian = file.bytes[jac_f->offset] != 0;
  t.description.assign(file.bytes.data() + desc_f->offset, desc_f->count);
  const int vw = static_cast<int>(vndf_f->shape[3]), vh = static_cast<int>(vndf_f->shape[2]);
  const int lw = static_cast<int>(lum_f->shape[3]), lh = static_cast<int>(lum_f->shape[2]);
  // Every slice of a density must integrate to more than 0 (it is divided by its integral).
  for (int i : {4, 5}) {
    const int w = i == 4 ? vw : lw, h = i == 4 ? vh : lh;
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    for (std::size_t s = 0; s < v[i].size() / n; ++s) {
      if (!(RglWarp::slice_integral(w, h, v[i].data() + s * n) > 0.0)) {
        return make_error(name + ": field \"" + std::string(keys[i]) + "\" slice " + std::to_string(s) + " (phi_i " +
                          std::to_string(s / nt) + ", theta_i " + std::to_string(s % nt) + ") integrates to 0");
      }
    }
  }
  const std::vector<std::vector<double>> params = {t.phi_i, t.theta_i};
  t.ndf = RglWarp(static_cast<int>(ndf_f->shape[1]), static_cast<int>(ndf_f->shape[0]), {}, v[2], false);
  t.sigma = RglWarp(static_cast<int>(sigma_f->shape[1]), static_cast<int>(sigma_f->shape[0]), {}, v[3], false);
  t.vndf = RglWarp(vw, vh, params, v[4], true);
  t.luminance = RglWarp(lw, lh, params, v[5], true);
  t.rgb = RglWarp(lw, lh, {t.phi_i, t.theta_i, {0.0, 1.0, 2.0}}, v[6], false);
  return t;
}

Result<RglTable> parse_rgl(std::vector<char> bytes, const std::string& name) {
  auto file = parse_tensor_file(std::move(bytes), name);
  if (!file) return file.error();
  return rgl_table(*file, name);
}

Result<RglTable> read_rgl(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(path.string() + ": cannot read (" + ec.message() + ")");
  constexpr std::uintmax_t max_bytes = std::uintmax_t{1} << 30;  // the published files are 1-40 MB
  if (size > max_bytes) return make_error(path.string() + ": " + std::to_string(size) + " bytes, more than the 1 GiB a tensor file may have here");
  std::vector<char> bytes(static_cast<std::size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in.seekg(0) || !in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    return make_error(path.string() + ": cannot read " + std::to_string(size) + " bytes");
  }
  return parse_rgl(std::move(bytes), path.string());
}

// ---------------------------------------------------------------------------------------------------------------
// The BRDF.

RglBrdf::RglBrdf(std::shared_ptr<const RglTable> table) : m_table(std::move(table)) {}

Rgb RglBrdf::loader_eval(const Vec3& wi, const Vec3& wo) const {
  if (!(wi.z > 0.0 && wo.z > 0.0)) return {};
  const RglTable& t = *m_table;
  const Vec3 wm = normalize(wi + wo);
  const double theta_i = elevation(wi), phi_i = std::atan2(wi.y, wi.x);
  const double theta_m = elevation(wm), phi_m = std::atan2(wm.y, wm.x);
  const Vec2 u_wi{theta_to_u(theta_i), phi_to_u(phi_i)};
  Vec2 u_wm{theta_to_u(theta_m), phi_to_u(t.isotropic ? phi_m - phi_i : phi_m)};
  u_wm.y -= std::floor(u_wm.y);  // wrapped into [0, 1)
  const double params[2] = {phi_i, theta_i};
  const Vec2 s = t.vndf.invert(u_wm, params).first;
  double fr[3];
  for (int c = 0; c < 3; ++c) {
    const double pc[3] = {phi_i, theta_i, static_cast<double>(c)};
    fr[c] = std::max(0.0, t.rgb.eval(s, pc));  // out-of-gamut negatives clipped
  }
  // f = rgb(s) D(wm) / (4 sigma(wi)): powitacq_rgb BRDF::eval (Dupuy & Jakob 2018, the microfacet form with the
  // VNDF normalization sigma, the projected area).
  const double k = t.ndf.eval(u_wm, {}) / (4.0 * t.sigma.eval(u_wi, {}));
  return {fr[0] * k, fr[1] * k, fr[2] * k};
}

Rgb RglBrdf::eval(const Vec3& wi, const Vec3& wo) const { return loader_eval(wo, wi); }

double RglBrdf::warp_pdf(const Vec3& wi, const Vec3& wo) const {
  if (!(wi.z > 0.0)) return 0.0;
  const RglTable& t = *m_table;
  const Vec3 sum = wi + wo;
  if (!(sum.z != 0.0) || !(length(sum) > 0.0)) return 0.0;
  // The microfacet normal in the upper hemisphere that mirrors wi into wo.
  const Vec3 wm = normalize(sum) * (sum.z > 0.0 ? 1.0 : -1.0);
  const double theta_i = elevation(wi), phi_i = std::atan2(wi.y, wi.x);
  const double theta_m = elevation(wm), phi_m = std::atan2(wm.y, wm.x);
  Vec2 u_wm{theta_to_u(theta_m), phi_to_u(t.isotropic ? phi_m - phi_i : phi_m)};
  u_wm.y -= std::floor(u_wm.y);
  const double params[2] = {phi_i, theta_i};
  const auto [s, vndf_pdf] = t.vndf.invert(u_wm, params);
  const double lum_pdf = t.luminance.eval(s, params);
  // d(omega_m) = sin theta_m d theta d phi = 2 pi^2 u_x sin theta_m du (theta = u_x^2 pi/2, phi = (2 u_y - 1) pi);
  // d(omega_o) = 4 |wi . wm| d(omega_m) (the mirror's Jacobian, Walter et al. 2007, eq. 14).
  // The exact Jacobian, not the loader's floor of 1e-6 on its first factor: that floor, reached within about 1e-5
  // rad of the normal, took 0.5% of the density's mass away in rgl_test's table (u_m.x < 0.003 there holds that
  // much), more for a sharper lobe, so the loader's pdf does not integrate to 1. At wm = n exactly (measure zero)
  // the density is taken as 0, and so where the quotient overflows (wm within about 1e-200 rad of n).
  const double sin_m = std::sqrt(wm.x * wm.x + wm.y * wm.y);
  const double jac = 2.0 * pi * pi * u_wm.x * sin_m * 4.0 * std::abs(dot(wi, wm));
  const double p = jac > 0.0 ? vndf_pdf * lum_pdf / jac : 0.0;
  return std::isfinite(p) ? p : 0.0;
}

double RglBrdf::pdf(const Vec3& wi, const Vec3& wo) const {
  if (!(wo.z > 0.0)) return 0.0;
  return cosine_share * std::max(wi.z, 0.0) * inv_pi + (1.0 - cosine_share) * warp_pdf(wo, wi);
}

BrdfSample RglBrdf::sample(const Vec3& wo, Vec2 u, double u_lobe) const {
  BrdfSample s;
  if (!(wo.z > 0.0)) return s;
  if (u_lobe < cosine_share) {
    s.wi = sample_cosine_hemisphere(u);
  } else {
    const RglTable& t = *m_table;
    const double theta_o = elevation(wo), phi_o = std::atan2(wo.y, wo.x);
    const double params[2] = {phi_o, theta_o};
    // The loader's sampler: the luminance warp, then the vndf warp, then the mirror about the microfacet normal.
    const Vec2 lum = t.luminance.sample(u, params).first;
    const Vec2 u_wm = t.vndf.sample(lum, params).first;
    const double theta_m = u_to_theta(u_wm.x);
    const double phi_m = u_to_phi(u_wm.y) + (t.isotropic ? phi_o : 0.0);
    const Vec3 wm{std::sin(theta_m) * std::cos(phi_m), std::sin(theta_m) * std::sin(phi_m), std::cos(theta_m)};
    s.wi = normalize(wm * (2.0 * dot(wm, wo)) - wo);
  }
  s.pdf = pdf(s.wi, wo);
  if (s.pdf > 0.0 && s.wi.z > 0.0) s.weight = eval(s.wi, wo) * (s.wi.z / s.pdf);
  return s;
}

Result<BrdfPtr> read_rgl_brdf(const std::filesystem::path& path) {
  auto t = read_rgl(path);
  if (!t) return t.error();
  return BrdfPtr(std::make_unique<RglBrdf>(std::make_shared<const RglTable>(std::move(*t))));
}

}  // namespace shadelab
