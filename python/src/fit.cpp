// shadelab.fit_grid(), shadelab.fit(), shadelab.convert_shininess(): the fitter and the shininess conversion
// (src/shadelab/fit) on NumPy arrays. Glue only: the grid, the metrics and the optimizer are the library's.
#include <fmt/core.h>

#include <cmath>

#include "bindings.h"
#include "common.h"
#include "shadelab/brdf/merl.h"
#include "shadelab/fit/fit.h"
#include "shadelab/fit/gltf_convert.h"
#include "shadelab/fit/shininess.h"

namespace shadelab::python {

namespace {

void check_grid_args(int theta_d_stride, int phi_d_stride, double max_theta_deg) {
  if (theta_d_stride < 1 || theta_d_stride > 90) fail(fmt::format("theta_d_stride: {} is out of range [1, 90]", theta_d_stride));
  if (phi_d_stride < 1 || phi_d_stride > 90) fail(fmt::format("phi_d_stride: {} is out of range [1, 90]", phi_d_stride));
  if (!(max_theta_deg > 0.0 && max_theta_deg <= 90.0)) fail(fmt::format("max_theta_deg: {} is out of range (0, 90]", max_theta_deg));
}

// FitData as arrays: wi, wo (N, 3), weight (N,), and values (N, 3) when it has them.
py::dict data_dict(const FitData& g) {
  const auto n = static_cast<py::ssize_t>(g.wi.size());
  DoubleArray wi({n, py::ssize_t{3}}), wo({n, py::ssize_t{3}}), w(n), values({n, py::ssize_t{3}});
  double* pi = wi.mutable_data();
  double* po = wo.mutable_data();
  double* pw = w.mutable_data();
  double* pv = values.mutable_data();
  for (py::ssize_t k = 0; k < n; ++k) {
    const auto u = static_cast<std::size_t>(k);
    for (int c = 0; c < 3; ++c) {
      pi[3 * k + c] = c == 0 ? g.wi[u].x : (c == 1 ? g.wi[u].y : g.wi[u].z);
      po[3 * k + c] = c == 0 ? g.wo[u].x : (c == 1 ? g.wo[u].y : g.wo[u].z);
      if (!g.value.empty()) pv[3 * k + c] = g.value[u][c];
    }
    pw[k] = g.weight[u];
  }
  py::dict d;
  d["wi"] = wi;
  d["wo"] = wo;
  d["weight"] = w;
  if (!g.value.empty()) d["values"] = values;
  return d;
}

py::dict merl_data_py(const std::string& path, int theta_d_stride, int phi_d_stride, double max_theta_deg) {
  check_grid_args(theta_d_stride, phi_d_stride, max_theta_deg);
  Result<MerlTable> t = Error{""};
  FitData g;
  {
    py::gil_scoped_release release;
    t = read_merl(path);
    if (t) g = fit_data_from_merl(*t, FitGridOptions{theta_d_stride, phi_d_stride, 1, max_theta_deg});
  }
  if (!t) fail(t.error().message);
  return data_dict(g);
}

py::dict fit_grid_py(int theta_d_stride, int phi_d_stride, int n_phi_h, double max_theta_deg) {
  check_grid_args(theta_d_stride, phi_d_stride, max_theta_deg);
  if (n_phi_h < 1 || n_phi_h > 64) fail(fmt::format("n_phi_h: {} is out of range [1, 64]", n_phi_h));
  FitGridOptions o{theta_d_stride, phi_d_stride, n_phi_h, max_theta_deg};
  FitData g;
  {
    py::gil_scoped_release release;
    g = fit_grid(o);
  }
  return data_dict(g);
}

py::dict fit_py(const std::string& model, py::handle wi_obj, py::handle wo_obj, py::handle values_obj, py::handle weights_obj,
                const std::string& metric_name, py::handle fix, py::handle free, int starts) {
  const FitMetric metric = unwrap(parse_fit_metric(metric_name), "");
  if (find_brdf_model(model) == nullptr) fail("fit: unknown model '" + model + "'");
  if (starts < 1 || starts > 64) fail(fmt::format("starts: {} is out of range [1, 64]", starts));
  const Vectors wi = to_vectors(wi_obj, "wi");
  const Vectors wo = to_vectors(wo_obj, "wo");
  if (wi.count != wo.count) fail(fmt::format("wo: {} rows, but wi has {}", wo.count, wi.count));
  const DoubleArray values = to_double_array(values_obj, "values");
  const bool grey = values.ndim() == 1;
  if (!((grey && values.shape(0) == wi.count) || (values.ndim() == 2 && values.shape(0) == wi.count && values.shape(1) == 3))) {
    fail(fmt::format("values: expected ({},) or ({}, 3), got {}", wi.count, wi.count, shape_text(values)));
  }
  FitData data;
  const auto n = static_cast<std::size_t>(wi.count);
  data.wi.resize(n);
  data.wo.resize(n);
  data.value.resize(n);
  data.weight.assign(n, 1.0);
  const double* v = values.data();
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<py::ssize_t>(k);
    const Vec3 a = wi.at(i), b = wo.at(i);
    const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b));
    if (!(la > 0.0 && std::isfinite(la) && lb > 0.0 && std::isfinite(lb))) fail(fmt::format("wi, wo: row {} is not a direction", k));
    data.wi[k] = a / la;
    data.wo[k] = b / lb;
    data.value[k] = grey ? Rgb::gray(v[k]) : Rgb{v[3 * k], v[3 * k + 1], v[3 * k + 2]};
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(data.value[k][c])) fail(fmt::format("values: row {} is not finite", k));
    }
  }
  if (!weights_obj.is_none()) {
    const DoubleArray w = to_double_array(weights_obj, "weights");
    if (w.ndim() != 1 || w.shape(0) != wi.count) fail(fmt::format("weights: expected ({},), got {}", wi.count, shape_text(w)));
    for (std::size_t k = 0; k < n; ++k) {
      data.weight[k] = w.data()[k];
      if (!(std::isfinite(data.weight[k]) && data.weight[k] >= 0.0)) fail(fmt::format("weights: row {} is not a finite number >= 0", k));
    }
  }
  FitOptions o;
  o.metric = metric;
  o.starts = starts;
  if (!fix.is_none()) {
    for (const auto& [k, val] : py::reinterpret_borrow<py::dict>(fix)) o.fixed.emplace_back(k.cast<std::string>(), param_text(val));
  }
  if (!free.is_none()) {
    for (const auto item : py::reinterpret_borrow<py::iterable>(free)) o.free.push_back(item.cast<std::string>());
  }
  Result<FitResult> r = Error{""};
  {
    py::gil_scoped_release release;
    r = fit_model(model, data, o);
  }
  const FitResult f = unwrap(std::move(r));
  py::dict params;
  for (const auto& p : f.params) {
    if (p.group_size > 0) {
      py::list groups;
      for (std::size_t g = 0; g < p.numbers.size(); g += static_cast<std::size_t>(p.group_size)) {
        py::list one;
        for (int j = 0; j < p.group_size; ++j) one.append(p.numbers[g + static_cast<std::size_t>(j)]);
        groups.append(one);
      }
      params[p.name.c_str()] = groups;
    } else if (p.numbers.size() == 3) {
      params[p.name.c_str()] = py::make_tuple(p.numbers[0], p.numbers[1], p.numbers[2]);
    } else {
      params[p.name.c_str()] = p.numbers[0];
    }
  }
  py::dict d;
  d["model"] = f.model;
  d["params"] = params;
  d["fitted"] = f.fitted;
  d["assignments"] = f.assignments;
  d["metric"] = fit_metric_name(f.metric);
  d["residual"] = f.residual;
  d["start_residuals"] = f.start_residuals;
  d["evaluations"] = f.evaluations;
  d["configurations"] = f.configurations;
  return d;
}

py::list convert_shininess_py(const std::string& source, const std::string& target, py::handle n_obj, const std::string& metric_name) {
  const FitMetric metric = unwrap(parse_fit_metric(metric_name), "");
  const DoubleArray ns = to_double_array(n_obj, "n");
  std::vector<Result<ShininessConversion>> out;
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < ns.size(); ++i) out.push_back(convert_shininess(source, target, ns.data()[i], metric));
  }
  py::list rows;
  for (auto& r : out) {
    const ShininessConversion c = unwrap(std::move(r));
    py::dict d;
    d["from"] = c.from;
    d["to"] = c.to;
    d["n"] = c.n;
    d["metric"] = fit_metric_name(c.metric);
    d["alpha"] = c.alpha;
    d["roughness"] = std::sqrt(c.alpha);
    d["residual"] = c.residual;
    d["relative_residual"] = c.relative_residual;
    d["at_bound"] = c.at_bound;
    py::list maps;
    for (const auto& m : c.mappings) {
      py::dict j;
      j["name"] = m.name;
      j["source"] = m.source;
      j["alpha"] = m.alpha ? py::object(py::float_(*m.alpha)) : py::object(py::none());
      j["residual"] = m.alpha ? py::object(py::float_(m.residual)) : py::object(py::none());
      j["relative_residual"] = m.alpha ? py::object(py::float_(m.relative_residual)) : py::object(py::none());
      j["excess"] = m.alpha ? py::object(py::float_(m.excess)) : py::object(py::none());
      maps.append(j);
    }
    d["mappings"] = maps;
    rows.append(d);
  }
  return rows;
}

// Rows of an (N, 3) colour array (or one (3,) colour, or one grey number broadcast to every row).
std::vector<Rgb> colour_rows(py::handle obj, const std::string& name, py::ssize_t& n) {
  const DoubleArray a = to_double_array(obj, name);
  std::vector<Rgb> rows;
  if (a.ndim() == 0) {
    rows.assign(1, Rgb::gray(a.data()[0]));
  } else if (a.ndim() == 1 && a.shape(0) == 3) {
    rows.assign(1, Rgb{a.data()[0], a.data()[1], a.data()[2]});
  } else if (a.ndim() == 2 && a.shape(1) == 3) {
    for (py::ssize_t i = 0; i < a.shape(0); ++i) rows.push_back({a.data()[3 * i], a.data()[3 * i + 1], a.data()[3 * i + 2]});
  } else {
    throw py::value_error(name + ": expected an (N, 3) array, a colour (3,) or a number, got shape " + shape_text(a));
  }
  if (rows.size() != 1) {
    if (n > 1 && static_cast<py::ssize_t>(rows.size()) != n) {
      throw py::value_error(fmt::format("{}: {} rows where the other arguments have {}", name, rows.size(), n));
    }
    n = static_cast<py::ssize_t>(rows.size());
  }
  for (const Rgb& c : rows) {
    for (double v : {c.r, c.g, c.b}) {
      if (!(v >= 0.0 && v <= 1.0)) throw py::value_error(name + ": values must lie in [0, 1], got " + number_text(v));
    }
  }
  return rows;
}

py::dict convert_spec_gloss_py(py::handle diffuse_obj, py::handle specular_obj, py::handle glossiness_obj,
                               const std::string& method) {
  if (method != "fast" && method != "fit") throw py::value_error("method: expected 'fast' or 'fit', got '" + method + "'");
  py::ssize_t n = 1;
  const std::vector<Rgb> diffuse = colour_rows(diffuse_obj, "diffuse", n);
  const std::vector<Rgb> specular = colour_rows(specular_obj, "specular", n);
  const DoubleArray g = to_double_array(glossiness_obj, "glossiness");
  if (g.ndim() > 1) throw py::value_error("glossiness: expected an (N,) array or a number, got shape " + shape_text(g));
  if (g.ndim() == 1 && g.shape(0) != 1) {
    if (n > 1 && g.shape(0) != n) throw py::value_error(fmt::format("glossiness: {} values where the colours have {} rows", g.shape(0), n));
    n = g.shape(0);
  }
  for (py::ssize_t i = 0; i < g.size(); ++i) {
    const double v = g.data()[i];
    if (!(v >= 0.0 && v <= 1.0)) throw py::value_error("glossiness: values must lie in [0, 1], got " + number_text(v));
  }
  const auto pick = [](const auto& v, py::ssize_t i) { return v.size() == 1 ? v[0] : v[static_cast<std::size_t>(i)]; };
  std::vector<MetalRoughFactors> out(static_cast<std::size_t>(n));
  std::vector<AlbedoDifference> start(out.size()), result(out.size());
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) {
      SpecGloss::Params sg;
      sg.diffuse = pick(diffuse, i);
      sg.specular = pick(specular, i);
      sg.glossiness = g.size() == 1 ? g.data()[0] : g.data()[i];
      const auto k = static_cast<std::size_t>(i);
      if (method == "fast") {
        out[k] = convert_spec_gloss_fast(sg).result;
        start[k] = table_albedo_difference(sg, pr1719_conversion(sg));
        result[k] = table_albedo_difference(sg, out[k]);
      } else {
        const GltfMaterialConversion c = convert_spec_gloss(sg);
        out[k] = c.result;
        start[k] = c.start_difference;
        result[k] = c.difference;
      }
    }
  }
  py::array_t<double> base({n, py::ssize_t{3}}), spec_colour({n, py::ssize_t{3}});
  py::array_t<double> metallic(n), roughness(n), spec(n), ior(n), diff(n), start_diff(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const MetalRoughFactors& m = out[static_cast<std::size_t>(i)];
    for (int c = 0; c < 3; ++c) {
      base.mutable_at(i, c) = m.base_color[c];
      spec_colour.mutable_at(i, c) = m.specular_color[c];
    }
    metallic.mutable_at(i) = m.metallic;
    roughness.mutable_at(i) = m.roughness;
    spec.mutable_at(i) = m.specular;
    ior.mutable_at(i) = m.ior;
    diff.mutable_at(i) = result[static_cast<std::size_t>(i)].max;
    start_diff.mutable_at(i) = start[static_cast<std::size_t>(i)].max;
  }
  py::dict d;
  d["base_color"] = base;
  d["metallic"] = metallic;
  d["roughness"] = roughness;
  d["specular"] = spec;
  d["specular_color"] = spec_colour;
  d["ior"] = ior;
  d["albedo_difference"] = diff;
  d["start_albedo_difference"] = start_diff;
  return d;
}

}  // namespace

void bind_fit(py::module_& m) {
  m.def("fit_grid", &fit_grid_py, py::arg("theta_d_stride") = 3, py::arg("phi_d_stride") = 6, py::arg("n_phi_h") = 1,
        py::arg("max_theta_deg") = 80.0,
        R"(fit_grid(theta_d_stride=3, phi_d_stride=6, n_phi_h=1, max_theta_deg=80.0) -> dict

The configurations `shadelab fit` compares at (docs/fitting.md): MERL 100 bin centres, every theta_h bin and every
stride-th theta_d and phi_d bin, at n_phi_h half-vector azimuths, both directions within max_theta_deg of the
normal. Returns {'wi': (N, 3), 'wo': (N, 3), 'weight': (N,)}, the weight each pair's measure dw_i dw_o.)");
  m.def("merl_data", &merl_data_py, py::arg("path"), py::arg("theta_d_stride") = 3, py::arg("phi_d_stride") = 6,
        py::arg("max_theta_deg") = 80.0,
        R"(merl_data(path, theta_d_stride=3, phi_d_stride=6, max_theta_deg=80.0) -> dict

A MERL 100 .binary file's values at fit_grid's configurations (its own bin values, no interpolation; bins with a
missing channel left out): {'wi', 'wo': (N, 3), 'values': (N, 3) f_r in 1/sr, 'weight': (N,)}, what fit() takes.
A missing or malformed file raises ValueError naming it.)");
  m.def("fit", &fit_py, py::arg("model"), py::arg("wi"), py::arg("wo"), py::arg("values"), py::arg("weights") = py::none(),
        py::arg("metric") = "cosine-l2", py::arg("fix") = py::none(), py::arg("free") = py::none(), py::arg("starts") = 4,
        R"(fit(model, wi, wo, values, weights=None, metric='cosine-l2', fix=None, free=None, starts=4) -> dict

Fits a registry model's free parameters to data: f_r values (N,) or (N, 3) at the pairs wi, wo ((N, 3) each),
weighted by weights (N,) (default 1; fit_grid's weights make the metric an integral over pairs). metric:
'cosine-l2', 'cube-root' or 'log'; fix: {name: value} held fixed; free: the names to fit (default: the model's
free set); starts: deterministic starts. The same fitter as `shadelab fit` (docs/fitting.md). Returns model,
params (every numeric parameter), fitted, assignments (what Brdf(model, ...) takes to rebuild it, as text), metric,
residual, start_residuals, evaluations, configurations.)");
  m.def("convert_shininess", &convert_shininess_py, py::arg("source"), py::arg("target") = "ggx", py::arg("n"),
        py::arg("metric") = "cosine-l2",
        R"(convert_shininess(source, target='ggx', n, metric='cosine-l2') -> list[dict]

For each exponent in n (a number or an array), the best-fit roughness of target ('ggx' or 'beckmann') for the
source lobe ('phong', 'blinn-phong', 'blinn-phong-modified' or 'blinn-phong-microfacet') beside the published
mappings, the keys of `shadelab convert shininess --json` (docs/conversions.md).)");
  m.def("convert_spec_gloss", &convert_spec_gloss_py, py::arg("diffuse"), py::arg("specular"), py::arg("glossiness"),
        py::arg("method") = "fast",
        R"(convert_spec_gloss(diffuse, specular, glossiness, method='fast') -> dict

KHR_materials_pbrSpecularGlossiness factors (linear diffuse and specular colours (N, 3), a (3,) colour or a number;
glossiness (N,) or a number; all in [0, 1]) as glTF metallic-roughness with KHR_materials_specular and
KHR_materials_ior, per row, as `shadelab convert gltf` converts them (docs/conversions.md): method 'fast' is the
per-texel rule (tables and Levenberg-Marquardt, about 15,000 rows/s), 'fit' the per-material BOBYQA fit (about
a second a row). Returns arrays: base_color, specular_color (N, 3); metallic, roughness, specular, ior (N,);
albedo_difference and start_albedo_difference (N,), the max directional-albedo difference of the result and of
Khronos PR #1719's conversion (the tables' for 'fast', the quadrature's for 'fit').)");
}

}  // namespace shadelab::python
