// A scene dict (Python) as the JSON document parse_scene reads: the library's converter
// (scene/value_tree.h, the one the fuzz harness fuzz_scene_dict drives) over Python objects.
//
// What is what (docs/python.md, "Scene dicts"): None; bool and numpy.bool_; int and NumPy integers; float and
// NumPy floats (a NumPy 0-d array of a bool, integer or float dtype is its scalar); str; dict (str keys);
// list, tuple, range and NumPy arrays of one or more dimensions (an array where a number belongs is then an
// array, and the scene parser says "expected a number"). Anything else (complex, bytes, Decimal, datetime64,
// a set, an object) is a ValueError naming its JSON pointer. Lengths are read before items (len() of a range
// is O(1)), so a huge sequence is refused before anything is converted.
#include <nlohmann/json.hpp>

#include <limits>

#include "common.h"
#include "shadelab/scene/value_tree.h"

namespace shadelab::python {

namespace {

struct PySource {
  py::object numpy_generic;
  py::object numpy_ndarray;

  PySource() {
    const py::module_ np = py::module_::import("numpy");
    numpy_generic = np.attr("generic");
    numpy_ndarray = np.attr("ndarray");
  }

  // A NumPy scalar or 0-d array as its Python scalar (bool, int, float, ...); anything else as it is.
  py::object scalar(py::handle v) const {
    if (py::isinstance(v, numpy_generic) ||
        (py::isinstance(v, numpy_ndarray) && ndim(v) == 0)) {
      return v.attr("item")();
    }
    return py::reinterpret_borrow<py::object>(v);
  }

  static int ndim(py::handle v) { return v.attr("ndim").cast<int>(); }

  static char dtype_kind(py::handle v) { return v.attr("dtype").attr("kind").cast<std::string>().at(0); }

  ValueKind kind(py::handle v) const {
    PyObject* p = v.ptr();
    if (v.is_none()) return ValueKind::null;
    if (PyBool_Check(p)) return ValueKind::boolean;
    if (PyLong_Check(p)) return ValueKind::integer;
    if (PyFloat_Check(p)) return ValueKind::real;  // numpy.float64 is a float
    if (PyUnicode_Check(p)) return ValueKind::string;  // numpy.str_ is a str
    if (PyDict_Check(p)) return ValueKind::mapping;
    if (PyList_Check(p) || PyTuple_Check(p) || PyRange_Check(p)) return ValueKind::sequence;
    const bool array = py::isinstance(v, numpy_ndarray);
    if (array && ndim(v) > 0) return ValueKind::sequence;
    if (array || py::isinstance(v, numpy_generic)) {
      switch (dtype_kind(v)) {
        case 'b': return ValueKind::boolean;
        case 'i':
        case 'u': return ValueKind::integer;
        case 'f': return ValueKind::real;
        default: return ValueKind::other;  // complex, datetime64, str / bytes arrays of 0-d, object, void
      }
    }
    return ValueKind::other;
  }

  std::string type_name(py::handle v) const {
    std::string name = py::str(py::type::of(v).attr("__name__")).cast<std::string>();
    if (py::isinstance(v, numpy_ndarray) || py::isinstance(v, numpy_generic)) {
      name += " (dtype " + py::str(v.attr("dtype")).cast<std::string>() + ")";
    }
    return name;
  }

  std::string repr(py::handle v) const { return py::repr(v).cast<std::string>(); }

  bool boolean(py::handle v) const { return PyObject_IsTrue(scalar(v).ptr()) == 1; }

  bool integer(py::handle v, IntegerValue& out) const {
    const py::object s = scalar(v);
    int overflow = 0;
    const long long x = PyLong_AsLongLongAndOverflow(s.ptr(), &overflow);
    if (x == -1 && PyErr_Occurred() != nullptr) throw py::error_already_set();
    if (overflow == 0) {
      out.i = x;
      return true;
    }
    if (overflow < 0) return false;
    const unsigned long long u = PyLong_AsUnsignedLongLong(s.ptr());
    if (PyErr_Occurred() != nullptr) {
      PyErr_Clear();
      return false;
    }
    out.is_unsigned = true;
    out.u = u;
    return true;
  }

  double real(py::handle v) const {
    const double d = PyFloat_AsDouble(scalar(v).ptr());
    if (d == -1.0 && PyErr_Occurred() != nullptr) throw py::error_already_set();
    return d;
  }

  std::size_t length(py::handle v) const {
    if (PyUnicode_Check(v.ptr())) return static_cast<std::size_t>(PyUnicode_GetLength(v.ptr()));  // code points
    // list, tuple, dict, an array's first axis; a range's len() may raise OverflowError.
    const Py_ssize_t n = PyObject_Length(v.ptr());
    if (n < 0 && PyErr_ExceptionMatches(PyExc_OverflowError)) {
      PyErr_Clear();  // range(10**30): more items than any bound
      return std::numeric_limits<std::size_t>::max();
    }
    if (n < 0) throw py::error_already_set();
    return static_cast<std::size_t>(n);
  }

  std::string string(py::handle v) const {
    Py_ssize_t size = 0;
    const char* utf8 = PyUnicode_AsUTF8AndSize(v.ptr(), &size);  // lone surrogates raise UnicodeEncodeError
    if (utf8 == nullptr) throw py::error_already_set();
    return std::string(utf8, static_cast<std::size_t>(size));
  }

  template <typename F>
  void items(py::handle v, F f) const {
    const std::size_t n = length(v);
    for (std::size_t i = 0; i < n; ++i) {
      const auto item = py::reinterpret_steal<py::object>(PySequence_GetItem(v.ptr(), static_cast<Py_ssize_t>(i)));
      if (!item) throw py::error_already_set();
      f(i, item);
    }
  }

  template <typename F>
  void members(py::handle v, F f) const {
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(v)) f(key, value);
  }
};

}  // namespace

nlohmann::json scene_dict_json(py::handle scene) {
  PySource source;
  ValueTreeToJson<PySource> convert(source);
  try {
    return convert.convert(scene);
  } catch (const ValueTreeError& e) {
    fail(e.line("scene"));
  }
}

}  // namespace shadelab::python
