// Shared pieces of the Python module: errors as ValueError, NumPy array conversions that name the argument,
// images between shadelab::Image and float32 (H, W, 3) arrays. Only glue: every formula is the library's.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json_fwd.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "shadelab/brdf/brdf.h"
#include "shadelab/color/rgb.h"
#include "shadelab/core/error.h"
#include "shadelab/core/vec.h"
#include "shadelab/envmap/base/cubemap.h"
#include "shadelab/image/image.h"

namespace shadelab::python {

namespace py = pybind11;

// Bad input from Python: a ValueError with one line. Where the library makes the message it is the line
// the CLI prints after "shadelab: "; checks of the module's own arguments name the argument as the CLI
// names its option ("theta_deg: 95 is out of range [0, 90) degrees" for "--theta: ...").
[[noreturn]] void fail(const std::string& message);

template <typename T>
T unwrap(Result<T> r, const std::string& prefix = {}) {
  if (!r) fail(prefix + r.error().message);
  return std::move(r).value();
}

// A number as the CLI prints it (fmt's "{}": the shortest text that reads back to the same double).
std::string number_text(double v);
// "(4, 2)": the shape of an array as NumPy prints it.
std::string shape_text(const py::array& a);

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// obj as a NumPy array of an integer or float dtype (np.asarray: no copy when it is one), or a ValueError
// "NAME: EXPECTED, got ..." for None, a ragged list, a masked array, or an array (or what NumPy makes of the
// object) of dtype bool, complex, str, bytes, object or datetime, which a cast would misread as numbers.
py::object real_array(py::handle obj, const std::string& name, const std::string& expected);

// Any array-like of numbers as a C-contiguous float64 array (no copy when it already is one).
DoubleArray to_double_array(py::handle obj, const std::string& name);

// Directions or other 3-vectors: an (N, 3) array, or one (3,) vector (single = true).
struct Vectors {
  DoubleArray array;
  const double* data = nullptr;
  py::ssize_t count = 0;
  bool single = false;
  Vec3 at(py::ssize_t i) const { return {data[3 * i], data[3 * i + 1], data[3 * i + 2]}; }
};
Vectors to_vectors(py::handle obj, const std::string& name);

// Two sets of vectors paired row by row; a single vector (or one row) pairs with every row of the other.
struct Pairs {
  Vectors a;
  Vectors b;
  py::ssize_t count = 0;
  py::ssize_t step_a = 1;  // 0 when a is broadcast
  py::ssize_t step_b = 1;
  bool single = false;  // both given as (3,): the result drops the row axis
};
Pairs to_pairs(py::handle a, const std::string& name_a, py::handle b, const std::string& name_b);

// The CLI's direction rule (cli_common.cpp parse_direction): v / |v|; false for a zero or non-finite vector.
// A unit vector (is_unit_direction: squared length within 4 ulp of 1) is used as given: dividing it by its
// length would move each component by at most an ulp, and skipping the check's division lets eval read
// NumPy's arrays in place (bench/python_eval_overhead.py). Every other vector is divided exactly as the
// CLI divides it, so the CLI and Python give the same bits for it.
inline bool normalize_direction(Vec3& v) {
  if (is_unit_direction(v)) return true;
  const double len = std::sqrt(dot(v, v));
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  v = v / len;
  return true;
}

// Rows of a C-contiguous (N, 3) float64 array as Vec3 and a (N, 3) result as Rgb: both are three packed
// doubles, so the library's batch entries read and write NumPy's memory in place.
static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Rgb) == 3 * sizeof(double), "packed like (N, 3) rows");
inline const Vec3* vec3_rows(const Vectors& v) { return reinterpret_cast<const Vec3*>(v.data); }
inline Rgb* rgb_rows(double* o) { return reinterpret_cast<Rgb*>(o); }

// Whether each of these m vectors is a unit direction (normalize_direction leaves it as it is).
inline bool all_unit(const Vec3* v, py::ssize_t m) {
  bool unit = true;
  for (py::ssize_t j = 0; j < m; ++j) unit &= is_unit_direction(v[j]);
  return unit;
}

// The walk of eval, pdf and sample over the pairs. Where neither side is broadcast, in_place(a, b, start,
// rest) is first given the arrays' own rows from pair `start` on and returns how many pairs it handled
// (0 to rest). The walk then takes the next chunk of up to 256 pairs the slow way: copied into small
// buffers pair by pair and checked (check_a, check_b may change a row, e.g. normalize it, and return
// false to stop), then body(a, b, start, m) with a[j], b[j] the pairs start + j; and goes back to
// in_place. Copying a whole chunk ahead, rather than each pair just before its call, keeps the model's
// loads away from the stores that made them (a store-to-load forwarding stall when a model reads x and y
// with one 16-byte load). Returns -1, or the array row where a check failed, with *which = 0 for a, 1 for
// b (the first failing pair, a before b). Runs without the GIL: no Python calls inside.
template <typename CheckA, typename CheckB, typename InPlace, typename Body>
py::ssize_t for_each_chunk(const Pairs& p, CheckA check_a, CheckB check_b, InPlace in_place, Body body, int* which) {
  constexpr py::ssize_t chunk = 256;
  Vec3 buf_a[chunk];
  Vec3 buf_b[chunk];
  const Vec3* rows_a = vec3_rows(p.a);
  const Vec3* rows_b = vec3_rows(p.b);
  const bool contiguous = p.step_a == 1 && p.step_b == 1;
  py::ssize_t start = 0;
  while (start < p.count) {
    if (contiguous) {
      start += in_place(rows_a + start, rows_b + start, start, p.count - start);
      if (start >= p.count) break;
    }
    const py::ssize_t m = std::min(chunk, p.count - start);
    for (py::ssize_t j = 0; j < m; ++j) {
      const py::ssize_t ra = (start + j) * p.step_a;
      const py::ssize_t rb = (start + j) * p.step_b;
      buf_a[j] = rows_a[ra];
      buf_b[j] = rows_b[rb];
      if (!check_a(buf_a[j])) return *which = 0, ra;
      if (!check_b(buf_b[j])) return *which = 1, rb;
    }
    body(static_cast<const Vec3*>(buf_a), static_cast<const Vec3*>(buf_b), start, m);
    start += m;
  }
  return -1;
}

// Pairs of directions (pdf): a chunk of unit directions is used in place, any other is copied and normalized.
template <typename Body>
py::ssize_t for_each_direction_chunk(const Pairs& p, Body body, int* which) {
  const auto in_place = [&](const Vec3* a, const Vec3* b, py::ssize_t start, py::ssize_t rest) -> py::ssize_t {
    const py::ssize_t m = std::min<py::ssize_t>(256, rest);
    if (!all_unit(a, m) || !all_unit(b, m)) return 0;
    body(a, b, start, m);
    return m;
  };
  return for_each_chunk(p, normalize_direction, normalize_direction, in_place, body, which);
}

// When `out` shares memory with an input (out=wi, or an overlapping view), the input is copied first, so
// every row is read before any result is written over it, as NumPy's ufuncs do.
void detach_from_output(Pairs& p, const double* out, py::ssize_t out_doubles);

// "wi: row 3 (0, 0, 0) is not a direction (zero length or not finite)".
[[noreturn]] void fail_direction(const std::string& name, const Vectors& v, py::ssize_t row);

// An integer (int or a NumPy integer; not bool, not float) as long long, or a ValueError naming it.
long long to_integer(py::handle v, const std::string& name);

// A scalar or a 1-D sequence of numbers; *scalar tells which was given.
std::vector<double> to_numbers(py::handle obj, const std::string& name, bool* scalar = nullptr);

// One number (a float, an int or a 0-d array), or a ValueError "NAME: expected one number".
double to_number(py::handle obj, const std::string& name);

// Angles in degrees, each finite and in [0, 90) (or [0, 90] with up_to_90), as the CLI checks --theta:
// "theta_deg: 95 is out of range [0, 90) degrees". A scalar or a 1-D sequence; *scalar tells which.
std::vector<double> to_angles_deg(py::handle obj, const std::string& name, bool up_to_90, bool* scalar = nullptr);

// The caller's output array for `out=`: writable, C-contiguous float64 of exactly this shape.
double* output_buffer(py::handle out, const std::vector<py::ssize_t>& shape, const std::string& name);

py::tuple rgb_tuple(const Rgb& c);
py::array_t<double> rgb_array(const Rgb& c);

// A scene dict as the JSON document parse_scene reads (scene_dict.cpp, over scene/value_tree.h): bounded as a
// scene file is (64 levels, 64 MiB of JSON, each length checked before its items are read); a value that is
// not JSON is a ValueError naming its pointer, "scene: /shapes/0/radius: ...".
nlohmann::json scene_dict_json(py::handle scene);

// str or os.PathLike -> the path as text; is_path tells whether obj is one.
bool is_path(py::handle obj);
std::string path_text(py::handle obj);

// An image from (H, W, 3), (H, W, 1) or (H, W) numbers (grey is copied to R, G and B). With `finite`,
// a NaN or infinite value is an error naming the pixel.
Image to_image(py::handle obj, const std::string& name, bool finite);
// A float32 (H, W, 3) array that owns the image's pixels (no copy).
py::array_t<float> image_array(Image image);
// Six faces as one float32 (6, S, S, 3) array, in the OpenGL order +X, -X, +Y, -Y, +Z, -Z.
py::array_t<float> cube_array(const CubeMap& cube);

// A Python parameter value as the text the CLI's --param takes: numbers in their shortest exact form,
// sequences joined by ',' (a colour r,g,b), sequences of sequences by ';' (lobes); anything else as str()
// so that the library's parser names what is wrong. is_number: a Python or NumPy real scalar (not bool, not str).
bool is_number(py::handle v);
std::string param_text(py::handle v);

}  // namespace shadelab::python
