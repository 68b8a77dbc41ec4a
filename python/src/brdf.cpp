// shadelab.models() and shadelab.Brdf: the BRDF registry and vectorized eval / pdf / sample over NumPy
// arrays, directional albedo and the `brdf check` report. Every model comes from brdf_models(), so a model
// added to the registry appears here without an edit.
#include <fmt/core.h>

#include <cmath>
#include <memory>

#include "bindings.h"
#include "common.h"
#include "shadelab/analysis/albedo.h"
#include "shadelab/analysis/check.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/constants.h"

namespace shadelab::python {

namespace {

py::list number_list(const std::vector<double>& v) {
  py::list l;
  for (double x : v) l.append(x);
  return l;
}

// A parameter's value as Python sees it: float (scalar), (r, g, b) (color), str (choice), list of lists
// (lobes).
py::object param_value(const ParamSpec& spec, const ParamValues& values) {
  switch (spec.kind) {
    case ParamKind::scalar: return py::float_(values.scalar(spec.name));
    case ParamKind::color: return rgb_tuple(values.color(spec.name));
    case ParamKind::choice: return py::str(values.choice(spec.name));
    case ParamKind::file: {  // the path as given; None for a required one not set
      const std::string& path = values.file(spec.name);
      return path.empty() ? py::object(py::none()) : py::object(py::str(path));
    }
    case ParamKind::lobes: {
      py::list groups;
      for (const auto& g : values.lobes(spec.name)) groups.append(number_list(g));
      return groups;
    }
  }
  return py::none();
}

py::list models() {
  py::list out;
  for (const auto& m : brdf_models()) {
    const ParamValues defaults = unwrap(parse_params(m.name, m.params, {}));
    py::list params;
    for (const auto& p : m.params) {
      py::dict d;
      d["name"] = p.name;
      d["kind"] = param_kind_name(p.kind);
      d["default"] = param_value(p, defaults);
      d["default_text"] = p.default_value;
      d["description"] = p.description;
      if (p.kind == ParamKind::choice) {
        d["choices"] = p.choices;
      } else if (p.kind == ParamKind::file) {
        d["required"] = is_required(p);  // a path: no range
      } else {
        d["min"] = p.min;
        d["max"] = p.max;
      }
      if (p.kind == ParamKind::lobes) {
        d["group_size"] = p.group_size;
        py::list ranges;
        for (const auto& [lo, hi] : p.group_ranges) ranges.append(py::make_tuple(lo, hi));
        d["group_ranges"] = ranges;
      }
      params.append(d);
    }
    py::dict model;
    model["name"] = m.name;
    model["summary"] = m.summary;
    model["source"] = m.source;
    model["params"] = params;
    out.append(model);
  }
  return out;
}

struct PyBrdf {
  std::string name;
  ParamAssignments assignments;  // as given, in the CLI's text form
  std::shared_ptr<const Brdf> f;
  const ModelInfo* info = nullptr;
  ParamValues values;
};

PyBrdf make(const std::string& name, const py::kwargs& kwargs) {
  PyBrdf b;
  b.name = name;
  for (const auto& [key, value] : kwargs) b.assignments.emplace_back(key.cast<std::string>(), param_text(value));
  BrdfPtr f = unwrap(make_brdf(name, b.assignments));
  b.f = std::shared_ptr<const Brdf>(std::move(f));
  b.info = find_brdf_model(name);
  b.values = unwrap(parse_params(b.info->name, b.info->params, b.assignments));
  return b;
}

std::string repr(const PyBrdf& b) {
  std::string s = "shadelab.Brdf('" + b.name + "'";
  for (const auto& [key, text] : b.assignments) {
    const auto nums = parse_numbers(text);
    std::string value = "'" + text + "'";
    if (nums && nums->size() == 1) value = text;
    if (nums && nums->size() == 3) value = fmt::format("({}, {}, {})", (*nums)[0], (*nums)[1], (*nums)[2]);
    s += ", " + key + "=" + value;
  }
  return s + ")";
}

py::dict params_dict(const PyBrdf& b) {
  py::dict d;
  for (const auto& spec : b.info->params) d[py::str(spec.name)] = param_value(spec, b.values);
  return d;
}

py::object eval(const PyBrdf& b, py::handle wi, py::handle wo, py::handle out) {
  Pairs p = to_pairs(wi, "wi", wo, "wo");
  const std::vector<py::ssize_t> shape = p.single ? std::vector<py::ssize_t>{3} : std::vector<py::ssize_t>{p.count, 3};
  py::array_t<double> result;
  double* o = nullptr;
  if (out.is_none()) {
    result = py::array_t<double>(shape);
    o = result.mutable_data();
  } else {
    o = output_buffer(out, shape, "out");
    detach_from_output(p, o, 3 * p.count);
  }
  // The loop and the kernel are the library's (Brdf::eval_batch_checked, as bench/python_eval_baseline.cpp
  // calls it): unit directions are read from NumPy's arrays in place, checked in the library's own loop;
  // from the first pair that is not, a chunk is copied, normalized and given to eval_batch, and the walk
  // goes back to the arrays. Broadcast rows always take the copy.
  const Brdf& f = *b.f;
  Rgb* rows = rgb_rows(o);
  int which = 0;
  py::ssize_t bad = -1;
  {
    py::gil_scoped_release release;
    bad = for_each_chunk(
        p, normalize_direction, normalize_direction,
        [&](const Vec3* a, const Vec3* c, py::ssize_t start, py::ssize_t rest) {
          return static_cast<py::ssize_t>(f.eval_batch_checked(a, c, rows + start, static_cast<std::size_t>(rest)));
        },
        [&](const Vec3* a, const Vec3* c, py::ssize_t start, py::ssize_t m) {
          f.eval_batch(a, c, rows + start, static_cast<std::size_t>(m));
        }, &which);
  }
  if (bad >= 0) fail_direction(which == 0 ? "wi" : "wo", which == 0 ? p.a : p.b, bad);
  if (!out.is_none()) return py::reinterpret_borrow<py::object>(out);
  return result;
}

py::object pdf(const PyBrdf& b, py::handle wi, py::handle wo, py::handle out) {
  const Pairs p = to_pairs(wi, "wi", wo, "wo");
  py::array_t<double> result;
  double* o = nullptr;
  if (out.is_none() || p.single) {
    result = py::array_t<double>(p.count);
    o = result.mutable_data();
  } else {
    o = output_buffer(out, {p.count}, "out");
  }
  const Brdf& f = *b.f;
  int which = 0;
  py::ssize_t bad = -1;
  {
    py::gil_scoped_release release;
    bad = for_each_direction_chunk(
        p, [&](const Vec3* a, const Vec3* c, py::ssize_t start, py::ssize_t m) {
          for (py::ssize_t j = 0; j < m; ++j) o[start + j] = f.pdf(a[j], c[j]);
        }, &which);
  }
  if (bad >= 0) fail_direction(which == 0 ? "wi" : "wo", which == 0 ? p.a : p.b, bad);
  if (p.single) return py::float_(o[0]);
  if (!out.is_none()) return py::reinterpret_borrow<py::object>(out);
  return result;
}

py::tuple sample(const PyBrdf& b, py::handle wo, py::handle u) {
  const Pairs p = to_pairs(wo, "wo", u, "u");
  const py::ssize_t n = p.count;
  py::array_t<double> wi_out(p.single ? std::vector<py::ssize_t>{3} : std::vector<py::ssize_t>{n, 3});
  py::array_t<double> pdf_out(n);
  py::array_t<double> weight_out(p.single ? std::vector<py::ssize_t>{3} : std::vector<py::ssize_t>{n, 3});
  double* wi_d = wi_out.mutable_data();
  double* pdf_d = pdf_out.mutable_data();
  double* w_d = weight_out.mutable_data();
  const Brdf& f = *b.f;
  const auto in_unit_cube = [](Vec3& r) {
    const auto in_unit = [](double x) { return x >= 0.0 && x < 1.0; };  // false for NaN
    return in_unit(r.x) && in_unit(r.y) && in_unit(r.z);
  };
  int which = 0;
  py::ssize_t bad = -1;
  {
    py::gil_scoped_release release;
    bad = for_each_chunk(
        p, normalize_direction, in_unit_cube, [](const Vec3*, const Vec3*, py::ssize_t, py::ssize_t) { return py::ssize_t{0}; },
        [&](const Vec3* wo_rows, const Vec3* u_rows, py::ssize_t start, py::ssize_t m) {
          for (py::ssize_t j = 0; j < m; ++j) {
            const py::ssize_t i = start + j;
            const Vec3& r = u_rows[j];
            const BrdfSample s = f.sample(wo_rows[j], {r.x, r.y}, r.z);
            wi_d[3 * i] = s.wi.x;
            wi_d[3 * i + 1] = s.wi.y;
            wi_d[3 * i + 2] = s.wi.z;
            pdf_d[i] = s.pdf;
            w_d[3 * i] = s.weight.r;
            w_d[3 * i + 1] = s.weight.g;
            w_d[3 * i + 2] = s.weight.b;
          }
        }, &which);
  }
  if (bad >= 0 && which == 0) fail_direction("wo", p.a, bad);
  if (bad >= 0) {
    const Vec3 r = p.b.at(bad);
    fail(fmt::format("u: row {} ({}, {}, {}) has a value outside [0, 1)", bad, r.x, r.y, r.z));
  }
  if (p.single) return py::make_tuple(wi_out, py::float_(pdf_d[0]), weight_out);
  return py::make_tuple(wi_out, pdf_out, weight_out);
}

py::array_t<double> albedo(const PyBrdf& b, py::handle theta_deg) {
  bool scalar = false;
  const std::vector<double> thetas = to_angles_deg(theta_deg, "theta_deg", false, &scalar);  // brdf albedo --theta
  const py::ssize_t m = static_cast<py::ssize_t>(thetas.size());
  py::array_t<double> out(scalar ? std::vector<py::ssize_t>{3} : std::vector<py::ssize_t>{m, 3});
  Rgb* o = rgb_rows(out.mutable_data());
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < thetas.size(); ++i) o[i] = directional_albedo(*b.f, deg_to_rad(thetas[i])).albedo;
  }
  return out;
}

py::dict check(const PyBrdf& b, py::handle angles_deg, py::handle samples) {
  CheckOptions options;
  if (!angles_deg.is_none()) {
    options.angles_deg = to_angles_deg(angles_deg, "angles_deg", false);
    if (options.angles_deg.empty()) fail("angles_deg: give at least one angle");
  }
  if (!samples.is_none()) {
    const long long s = to_integer(samples, "samples");
    if (s < 1000 || s > 100'000'000) fail(fmt::format("samples: {} is out of range [1000, 1e8]", s));
    options.chi_square.samples = static_cast<std::uint64_t>(s);
  }
  Result<CheckReport> report = make_error("");
  {
    py::gil_scoped_release release;
    report = check_brdf(b.name, b.assignments, options);
  }
  const CheckReport r = unwrap(std::move(report));
  // The same shape as `shadelab brdf check --json`.
  py::list items;
  for (const auto& item : r.items) {
    py::dict d;
    d["name"] = item.name;
    d["passed"] = item.passed;
    d["figure"] = item.figure;
    d["threshold"] = std::isfinite(item.threshold) ? py::object(py::float_(item.threshold)) : py::object(py::none());
    d["detail"] = item.detail;
    items.append(d);
  }
  py::dict d;
  d["model"] = r.model;
  d["params"] = r.params;
  d["passed"] = r.passed();
  d["checks"] = items;
  return d;
}

}  // namespace

void bind_brdf(py::module_& m) {
  m.def("models", &models, R"(models() -> list[dict]

Every BRDF model of the registry, in its fixed order (the list `shadelab brdf list` prints).

Each dict has ``name`` (what Brdf() takes), ``summary`` (the formula, one line), ``source`` (where the
formula comes from) and ``params``: a list of dicts with ``name``, ``kind`` ('scalar', 'color', 'choice' or
'lobes'), ``default`` (float, (r, g, b), str, or a list of lobes), ``default_text`` (as typed on the command
line), ``description``, and ``min``/``max`` (numbers) or ``choices`` (words).)");

  py::class_<PyBrdf>(m, "Brdf", R"(A BRDF model of the registry with its parameters.

Brdf(name, **params): ``name`` as in models(); each parameter by its name, a number, an (r, g, b) sequence
for colours (or one number for grey), a word for choices, a list of lobes (or the CLI's text) for
'lobes'. Unknown models or parameters, out-of-range or non-finite values raise ValueError with the line the
CLI prints, e.g. "brdf phong: parameter 'n' = -1 is out of range [0, 1e+06]".

Frame and units (docs/conventions.md): the local shading frame has the normal on +Z; wi points toward the
light, wo toward the viewer. Directions are normalized as the CLI does (v / |v|); a zero or non-finite
direction raises ValueError. eval returns f_r in 1/sr WITHOUT the cosine. The loops run in C++ with the GIL
released, one thread per call (call from several Python threads to use several cores).)")
      .def(py::init(&make), py::arg("name"), "Brdf(name, **params)\n\nThe model `name` of models() with the given parameters.")
      .def_property_readonly("name", [](const PyBrdf& b) { return b.name; }, "The model's registry name.")
      .def_property_readonly("params", &params_dict,
                             "Every parameter's value (given or default), as a dict: float, (r, g, b), str or lobes.")
      .def_property_readonly("is_reciprocal", [](const PyBrdf& b) { return b.f->is_reciprocal(); },
                             "False for published forms that are not reciprocal by design (original Phong, ...).")
      .def_property_readonly("diffuse_albedo", [](const PyBrdf& b) { return rgb_tuple(b.f->diffuse_albedo()); },
                             "(r, g, b) albedo of the model's Lambertian part (what a game multiplies by E/pi).")
      .def("__repr__", &repr)
      .def("eval", &eval, py::arg("wi"), py::arg("wo"), py::kw_only(), py::arg("out") = py::none(),
           R"(eval(wi, wo, *, out=None) -> ndarray

f_r(wi, wo) in 1/sr, RGB, without the cosine factor: shape (N, 3) for (N, 3) inputs. wi and wo are (N, 3)
(or (3,)) arrays of directions; a single row pairs with every row of the other. 0 when either is on or
below the horizon. ``out``: a C-contiguous float64 (N, 3) array to write into (returned).)")
      .def("pdf", &pdf, py::arg("wi"), py::arg("wo"), py::kw_only(), py::arg("out") = py::none(),
           R"(pdf(wi, wo, *, out=None) -> ndarray

Density per unit solid angle of sample(wo) choosing wi: shape (N,) (a float for two (3,) vectors). It
integrates to 1 over the whole sphere of wi.)")
      .def("sample", &sample, py::arg("wo"), py::arg("u"),
           R"(sample(wo, u) -> (wi, pdf, weight)

Draws wi for each wo from the model's sampler. u has shape (N, 3) with values in [0, 1): u[:, 0:2] picks
the direction within a lobe, u[:, 2] picks the lobe. Returns wi (N, 3), pdf (N,) per unit solid angle and
weight (N, 3) = f_r(wi, wo) cos(theta_i) / pdf (0 where the sample is below the horizon or pdf is 0).)")
      .def("albedo", &albedo, py::arg("theta_deg") = std::vector<double>{0, 15, 30, 45, 60, 75, 85, 89},
           R"(albedo(theta_deg=[0, 15, 30, 45, 60, 75, 85, 89]) -> ndarray

Directional albedo: the integral over the hemisphere of f_r cos(theta_i), per channel, for a viewer at
theta_deg from the normal (each in [0, 90)), by deterministic adaptive quadrature (the numbers of
`shadelab brdf albedo`). Shape (M, 3) for M angles, (3,) for one number.)")
      .def("check", &check, py::arg("angles_deg") = py::none(), py::arg("samples") = py::none(),
           R"(check(angles_deg=None, samples=None) -> dict

The report of `shadelab brdf check`: normalization, energy, reciprocity, pdf integral, sample weights and a
chi-square test of the sampler per angle (default 0, 30, 60, 80 degrees; ``samples`` per chi-square test,
default 1e6). Returns {'model', 'params', 'passed', 'checks': [{'name', 'passed', 'figure', 'threshold',
'detail'}]}, the CLI's JSON. About one to a few seconds per model.)");
}

}  // namespace shadelab::python
