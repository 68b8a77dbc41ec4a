// shadelab.zoo(): the normalization zoo, closed forms against quadrature (the rows of `shadelab zoo --json`).
#include <fmt/core.h>

#include <cmath>

#include "bindings.h"
#include "common.h"
#include "shadelab/analysis/zoo.h"

namespace shadelab::python {

namespace {

py::object optional_number(const std::optional<double>& v) {
  return v ? py::object(py::float_(*v)) : py::object(py::none());
}

py::list zoo(py::handle n) {
  const std::vector<double> exponents = to_numbers(n, "n");
  for (double e : exponents) {
    if (!std::isfinite(e) || e < 0.0) fail(fmt::format("n: {} must be a finite number >= 0", e));  // as --n
  }
  std::vector<Result<std::vector<ZooRow>>> tables;
  {
    py::gil_scoped_release release;
    for (double e : exponents) tables.push_back(zoo_table(e));
  }
  py::list rows;
  for (auto& t : tables) {
    for (const ZooRow& r : unwrap(std::move(t))) {
      py::dict d;
      d["model"] = r.model;
      d["table"] = r.table;
      d["function"] = r.function_text;
      d["integrand"] = r.integrand_text;
      d["n"] = r.n;
      d["closed_form"] = r.closed_form_text;
      d["closed_form_value"] = r.closed_form;
      d["numeric"] = r.numeric;
      d["numeric_error"] = r.numeric_error;
      d["relative_error"] = r.relative_error;
      d["literature"] = r.literature;
      d["lower"] = optional_number(r.lower);
      d["upper"] = optional_number(r.upper);
      d["lower_text"] = r.lower_text;
      d["upper_text"] = r.upper_text;
      d["integral"] = r.integral;
      d["integral_error"] = r.integral_error;
      d["converged"] = r.converged;
      rows.append(d);
    }
  }
  return rows;
}

}  // namespace

void bind_analysis(py::module_& m) {
  m.def("zoo", &zoo, py::arg("n") = std::vector<double>{1, 10, 100, 1000},
        R"(zoo(n=[1, 10, 100, 1000]) -> list[dict]

The Blinn-Phong normalization zoo (Schueler 2011) recomputed for each exponent n (a number or a sequence,
each finite and >= 0): six rows per n, the RDF rows phong, phong-modified, blinn-phong, blinn-phong-modified
and the NDF rows blinn-phong-ndf, blinn-phong-heightfield. Each row: the closed form (text and value, from
the model code), the normalization 1 / (2 pi I(n)) by adaptive Gauss-Kronrod quadrature of the integrand
I(n) with its error estimate, their relative difference, bounds where the zoo gives them, and the
literature. The keys of `shadelab zoo --json`, plus integral, integral_error and converged.)");
}

}  // namespace shadelab::python
