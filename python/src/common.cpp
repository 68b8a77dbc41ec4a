#include "common.h"

#include <fmt/core.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <memory>

#include "shadelab/image/image_io.h"

namespace shadelab::python {

void fail(const std::string& message) { throw py::value_error(message); }

std::string number_text(double v) { return fmt::format("{}", v); }

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) {
    s += (i == 0 ? "" : ", ") + std::to_string(a.shape(i));
  }
  return s + (a.ndim() == 1 ? ",)" : ")");
}

py::object real_array(py::handle obj, const std::string& name, const std::string& expected) {
  const std::string type = py::str(py::type::of(obj).attr("__name__")).cast<std::string>();
  if (obj.is_none()) fail(name + ": " + expected + ", got None");
  const py::module_ np = py::module_::import("numpy");
  if (py::isinstance(obj, np.attr("ma").attr("MaskedArray"))) {
    fail(name + ": a masked array (its mask would be ignored; give .filled(value) or .compressed())");
  }
  py::object a;
  try {
    a = np.attr("asarray")(obj);  // a ragged list raises
  } catch (py::error_already_set&) {
    fail(name + ": " + expected + ", got " + type);
  }
  const std::string dtype = py::str(a.attr("dtype")).cast<std::string>();
  const char kind = a.attr("dtype").attr("kind").cast<std::string>().at(0);
  if (kind != 'i' && kind != 'u' && kind != 'f') {
    // bool, complex, str, bytes, object, datetime: NumPy would cast them (strings parsed, imaginary parts
    // dropped, True as 1), which reads a wrong input as numbers.
    if (py::isinstance<py::array>(obj)) fail(name + ": " + expected + ", got an array of dtype " + dtype);
    if (py::isinstance<py::str>(obj) || py::isinstance<py::bytes>(obj)) fail(name + ": " + expected + ", got " + type);
    fail(name + ": " + expected + ", got " + type + " (NumPy reads it as dtype " + dtype + ")");
  }
  return a;
}

DoubleArray to_double_array(py::handle obj, const std::string& name) {
  // Any layout (strided, negative strides, Fortran order) and any integer or float dtype: copied into a
  // C-contiguous float64 array when it is not one already.
  auto arr = DoubleArray::ensure(real_array(obj, name, "expected an array of numbers"));
  if (!arr) throw py::error_already_set();
  return arr;
}

Vectors to_vectors(py::handle obj, const std::string& name) {
  Vectors v;
  v.array = to_double_array(obj, name);
  const bool one = v.array.ndim() == 1 && v.array.shape(0) == 3;
  const bool rows = v.array.ndim() == 2 && v.array.shape(1) == 3;
  if (!one && !rows) fail(name + ": expected shape (N, 3) or (3,), got " + shape_text(v.array));
  v.single = one;
  v.count = one ? 1 : v.array.shape(0);
  v.data = v.array.data();
  return v;
}

Pairs to_pairs(py::handle a, const std::string& name_a, py::handle b, const std::string& name_b) {
  Pairs p;
  p.a = to_vectors(a, name_a);
  p.b = to_vectors(b, name_b);
  if (p.a.count == p.b.count) {
    p.count = p.a.count;
  } else if (p.a.count == 1) {
    p.count = p.b.count;
    p.step_a = 0;
  } else if (p.b.count == 1) {
    p.count = p.a.count;
    p.step_b = 0;
  } else {
    fail(name_a + " and " + name_b + ": " + std::to_string(p.a.count) + " and " + std::to_string(p.b.count) +
         " rows do not pair (give the same number of rows, or one row)");
  }
  p.single = p.a.single && p.b.single;
  return p;
}

void detach_from_output(Pairs& p, const double* out, py::ssize_t out_doubles) {
  const auto overlaps = [&](const Vectors& v) {
    const auto* lo = reinterpret_cast<const char*>(v.data);
    const auto* hi = lo + 3 * v.count * static_cast<py::ssize_t>(sizeof(double));
    const auto* o_lo = reinterpret_cast<const char*>(out);
    const auto* o_hi = o_lo + out_doubles * static_cast<py::ssize_t>(sizeof(double));
    return std::less<>()(lo, o_hi) && std::less<>()(o_lo, hi);
  };
  for (Vectors* v : {&p.a, &p.b}) {
    if (v->count == 0 || !overlaps(*v)) continue;
    v->array = DoubleArray::ensure(v->array.attr("copy")());
    v->data = v->array.data();
  }
}

void fail_direction(const std::string& name, const Vectors& v, py::ssize_t row) {
  const Vec3 d = v.at(row);
  fail(fmt::format("{}: row {} ({}, {}, {}) is not a direction (zero length or not finite)", name, row, d.x, d.y,
                   d.z));
}

long long to_integer(py::handle v, const std::string& name) {
  if (py::isinstance<py::bool_>(v) || !PyIndex_Check(v.ptr())) fail(name + ": expected an integer");
  const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(v.ptr()));
  int overflow = 0;
  const long long x = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
  if (overflow != 0) fail(name + ": " + py::str(py::handle(i)).cast<std::string>() + " is too large");
  return x;
}

std::vector<double> to_numbers(py::handle obj, const std::string& name, bool* scalar) {
  const DoubleArray arr = to_double_array(obj, name);
  if (arr.ndim() > 1) fail(name + ": expected a number or a 1-D sequence of numbers, got shape " + shape_text(arr));
  if (scalar != nullptr) *scalar = arr.ndim() == 0;
  return std::vector<double>(arr.data(), arr.data() + arr.size());
}

double to_number(py::handle obj, const std::string& name) {
  bool scalar = false;
  const std::vector<double> v = to_numbers(obj, name, &scalar);
  if (!scalar) fail(name + ": expected one number");
  return v[0];
}

std::vector<double> to_angles_deg(py::handle obj, const std::string& name, bool up_to_90, bool* scalar) {
  std::vector<double> angles = to_numbers(obj, name, scalar);
  for (double t : angles) {
    if (!std::isfinite(t) || t < 0.0 || (up_to_90 ? t > 90.0 : t >= 90.0)) {
      fail(fmt::format("{}: {} is out of range [0, 90{} degrees", name, t, up_to_90 ? "]" : ")"));
    }
  }
  return angles;
}

double* output_buffer(py::handle out, const std::vector<py::ssize_t>& shape, const std::string& name) {
  std::string want = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) want += (i == 0 ? "" : ", ") + std::to_string(shape[i]);
  want += shape.size() == 1 ? ",)" : ")";
  const std::string expected = name + ": expected a writable C-contiguous float64 array of shape " + want;
  if (!py::isinstance<py::array_t<double>>(out)) fail(expected);
  auto arr = py::reinterpret_borrow<py::array_t<double>>(out);
  if (!arr.writeable() || !(arr.flags() & py::array::c_style)) fail(expected);
  if (arr.ndim() != static_cast<py::ssize_t>(shape.size())) fail(expected + ", got " + shape_text(arr));
  for (std::size_t i = 0; i < shape.size(); ++i) {
    if (arr.shape(static_cast<py::ssize_t>(i)) != shape[i]) fail(expected + ", got " + shape_text(arr));
  }
  return arr.mutable_data();
}

py::tuple rgb_tuple(const Rgb& c) { return py::make_tuple(c.r, c.g, c.b); }

py::array_t<double> rgb_array(const Rgb& c) {
  py::array_t<double> a(3);
  double* d = a.mutable_data();
  d[0] = c.r;
  d[1] = c.g;
  d[2] = c.b;
  return a;
}

bool is_path(py::handle obj) {
  return py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__");
}

std::string path_text(py::handle obj) {
  const py::object p = py::module_::import("os").attr("fspath")(obj);
  if (!py::isinstance<py::str>(p)) fail("path: expected a str or os.PathLike of str");
  return p.cast<std::string>();
}

Image to_image(py::handle obj, const std::string& name, bool finite) {
  const FloatArray arr = [&] {
    auto a = FloatArray::ensure(real_array(obj, name, "expected an image array of shape (H, W, 3)"));
    if (!a) throw py::error_already_set();
    return a;
  }();
  const bool rgb = arr.ndim() == 3 && arr.shape(2) == 3;
  const bool grey = arr.ndim() == 2 || (arr.ndim() == 3 && arr.shape(2) == 1);
  if (!rgb && !grey) fail(name + ": expected shape (H, W, 3), (H, W, 1) or (H, W), got " + shape_text(arr));
  const py::ssize_t h = arr.shape(0);
  const py::ssize_t w = arr.shape(1);
  if (h < 1 || w < 1) fail(name + ": the image is empty, shape " + shape_text(arr));
  if (static_cast<long long>(h) * static_cast<long long>(w) > max_image_pixels) {
    fail(name + ": " + std::to_string(w) + " x " + std::to_string(h) + " pixels is more than the largest image, " +
         std::to_string(max_image_pixels));
  }
  Image img(static_cast<int>(w), static_cast<int>(h));
  const float* src = arr.data();
  const std::size_t pixels = img.pixel_count();
  if (rgb) {
    std::memcpy(img.data.data(), src, pixels * 3 * sizeof(float));
  } else {
    for (std::size_t i = 0; i < pixels; ++i) img.data[3 * i] = img.data[3 * i + 1] = img.data[3 * i + 2] = src[i];
  }
  if (finite) {
    for (std::size_t i = 0; i < img.data.size(); ++i) {
      if (!std::isfinite(img.data[i])) {
        const std::size_t p = i / 3;
        fail(fmt::format("{}: pixel (x {}, y {}) channel {} is {}, not a finite number", name, p % static_cast<std::size_t>(img.width),
                         p / static_cast<std::size_t>(img.width), "RGB"[i % 3], static_cast<double>(img.data[i])));
      }
    }
  }
  return img;
}

py::array_t<float> image_array(Image image) {
  auto* owned = new Image(std::move(image));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<Image*>(p); });
  const py::ssize_t h = owned->height;
  const py::ssize_t w = owned->width;
  return py::array_t<float>({h, w, py::ssize_t{3}},
                            {static_cast<py::ssize_t>(w * 3 * sizeof(float)), static_cast<py::ssize_t>(3 * sizeof(float)),
                             static_cast<py::ssize_t>(sizeof(float))},
                            owned->data.data(), free_when_done);
}

py::array_t<float> cube_array(const CubeMap& cube) {
  const py::ssize_t s = cube.size;
  py::array_t<float> a({py::ssize_t{6}, s, s, py::ssize_t{3}});
  float* d = a.mutable_data();
  const std::size_t face_floats = static_cast<std::size_t>(s) * static_cast<std::size_t>(s) * 3;
  for (std::size_t f = 0; f < 6; ++f) std::memcpy(d + f * face_floats, cube.faces[f].data.data(), face_floats * sizeof(float));
  return a;
}

// (moved from brdf.cpp: fit.cpp takes parameter values the same way)
bool is_number(py::handle v) {
  if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v)) return false;
  if (PyFloat_Check(v.ptr()) || PyLong_Check(v.ptr())) return true;
  // NumPy scalars and 0-d arrays: anything that converts to float and is not a sequence.
  if (py::isinstance<py::array>(v)) return py::reinterpret_borrow<py::array>(v).ndim() == 0;
  return py::hasattr(v, "__float__") && !PySequence_Check(v.ptr());
}

// A Python parameter value as the text the CLI's --param takes: numbers in their shortest exact form,
// sequences joined by ',' (a colour r,g,b), sequences of sequences by ';' (lobes); anything else as str()
// so that the library's parser names what is wrong.
std::string param_text(py::handle v) {
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (is_number(v)) return number_text(py::float_(py::reinterpret_borrow<py::object>(v)).cast<double>());
  if (PySequence_Check(v.ptr()) && !PyBytes_Check(v.ptr()) && !PyByteArray_Check(v.ptr())) {
    const py::sequence seq = py::reinterpret_borrow<py::sequence>(v);
    std::string text;
    bool groups = seq.size() > 0;
    for (const auto item : seq) groups = groups && !py::isinstance<py::str>(item) && PySequence_Check(item.ptr());
    const char* sep = groups ? ";" : ",";
    bool first = true;
    for (const auto item : seq) {
      text += (first ? "" : sep) + param_text(item);
      first = false;
    }
    return text;
  }
  return py::str(v).cast<std::string>();
}

}  // namespace shadelab::python
