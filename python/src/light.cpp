// shadelab.fresnel(), fresnel_materials(), convert_light(), light_units(): the `fresnel` and `light`
// commands of the CLI, with the same rules and messages (the argument's name in place of the option's).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "bindings.h"
#include "common.h"
#include "shadelab/core/text.h"
#include "shadelab/brdf/fresnel.h"
#include "shadelab/brdf/fresnel_materials.h"
#include "shadelab/core/constants.h"
#include "shadelab/light/units.h"

namespace shadelab::python {

namespace {

py::object fresnel(py::handle ior, py::handle k, py::handle theta_deg, py::handle material) {
  bool scalar = false;
  const std::vector<double> thetas = to_angles_deg(theta_deg, "theta_deg", true, &scalar);
  const py::ssize_t count = static_cast<py::ssize_t>(thetas.size());
  if (!material.is_none()) {
    if (!ior.is_none() || !k.is_none()) fail("fresnel: give ior=N (and k=K) or material=NAME, not both");
    const std::string name = py::str(material).cast<std::string>();
    const FresnelMaterial* mat = find_fresnel_material(name);
    if (mat == nullptr) fail("material: unknown material '" + name + "' (see fresnel_materials())");
    py::array_t<double> out(scalar ? std::vector<py::ssize_t>{3} : std::vector<py::ssize_t>{count, 3});
    Rgb* o = rgb_rows(out.mutable_data());
    for (std::size_t i = 0; i < thetas.size(); ++i) o[i] = fresnel_reflectance(*mat, std::cos(deg_to_rad(thetas[i])));
    return out;
  }
  if (ior.is_none()) fail("fresnel: give ior=N (and k=K) or material=NAME");
  const double n = to_number(ior, "ior");
  if (!(n > 0.0) || !std::isfinite(n)) fail(fmt::format("ior: N = {} must be positive", n));
  double kk = 0.0;
  if (!k.is_none()) {
    kk = to_number(k, "k");
    if (!(kk >= 0.0) || !std::isfinite(kk)) fail(fmt::format("k: K = {} must not be negative", kk));
  }
  py::array_t<double> out(count);
  double* o = out.mutable_data();
  for (std::size_t i = 0; i < thetas.size(); ++i) {
    const double cos_i = std::cos(deg_to_rad(thetas[i]));
    o[i] = k.is_none() ? F_dielectric(cos_i, n) : F_conductor(cos_i, n, kk);
  }
  if (scalar) return py::float_(o[0]);
  return out;
}

py::list materials() {
  py::list out;
  for (const auto& m : fresnel_materials()) {
    py::dict d;
    d["name"] = std::string(m.name);
    d["conductor"] = m.conductor;
    d["n"] = rgb_tuple(m.n);
    d["k"] = rgb_tuple(m.k);
    d["F0"] = rgb_tuple(fresnel_f0(m));
    d["wavelengths"] = std::string(m.wavelengths);
    d["source"] = std::string(m.source);
    out.append(d);
  }
  return out;
}

py::list units() {
  py::list out;
  for (const auto& u : light_units()) {
    py::dict d;
    d["name"] = std::string(u.name);
    d["quantity"] = light_quantity_name(u.quantity);
    d["description"] = std::string(u.description);
    out.append(d);
  }
  return out;
}

py::object convert(py::handle value, const std::string& from, const std::string& to, double cone_deg) {
  bool scalar = false;
  const std::vector<double> v = to_numbers(value, "value", &scalar);
  if (v.size() != 1 && v.size() != 3) fail("value: expected a number or r,g,b, got " + std::to_string(v.size()) + " numbers");
  for (double x : v) {
    if (!std::isfinite(x)) fail(fmt::format("value: '{}' is not finite", x));
    if (x < 0.0) fail(fmt::format("value: {} is negative", x));
  }
  if (!std::isfinite(cone_deg) || cone_deg <= 0.0 || cone_deg > 180.0) {
    fail(fmt::format("cone_deg: {} is out of range (0, 180] degrees", cone_deg));
  }
  for (const auto& [name, unit] : {std::pair<const char*, const std::string*>{"from_unit", &from}, {"to_unit", &to}}) {
    if (find_light_unit(*unit) == nullptr) {
      fail(std::string(name) + ": unknown unit '" + printable(*unit) + "' (units: light_units())");
    }
  }
  const Rgb in = v.size() == 3 ? Rgb{v[0], v[1], v[2]} : Rgb::gray(v[0]);
  // cone_deg is the half-angle of a spot light's outer cone; 180 degrees is the whole sphere (as --cone).
  const Rgb out = unwrap(convert_light(in, from, to, std::max(-1.0, std::cos(deg_to_rad(cone_deg)))));
  // A finite value whose conversion overflows is bad input, as the CLI says (issue 40, finding 8), not inf.
  if (!std::isfinite(out.r) || !std::isfinite(out.g) || !std::isfinite(out.b)) {
    fail(fmt::format("value: {} {} overflows when converted to {} (the result exceeds the largest double, about "
                     "1.8e308)", v.size() == 1 ? number_text(v[0]) : fmt::format("{},{},{}", v[0], v[1], v[2]), from, to));
  }
  if (v.size() == 1) {
    if (scalar) return py::float_(out.r);
    py::array_t<double> a(1);
    a.mutable_data()[0] = out.r;
    return a;
  }
  return rgb_array(out);
}

}  // namespace

void bind_light(py::module_& m) {
  m.def("fresnel", &fresnel, py::kw_only(), py::arg("ior") = py::none(), py::arg("k") = py::none(),
        py::arg("theta_deg") = 0.0, py::arg("material") = py::none(),
        R"(fresnel(*, ior=None, k=None, theta_deg=0.0, material=None)

Exact unpolarized Fresnel reflectance of a smooth interface from air, at theta_deg from the normal (a number
or a sequence, each in [0, 90]). ior=N: a dielectric of relative index N (total internal reflection gives 1
for N < 1); with k=K a conductor of index N + iK. Returns a float (or (M,) array). material=NAME: a named
material of fresnel_materials() with RGB indices, returns (3,) (or (M, 3)).)");
  m.def("fresnel_materials", &materials,
        "fresnel_materials() -> list[dict]\n\nThe named materials: name, conductor, n, k and F0 as (r, g, b) at "
        "650, 550, 450 nm, wavelengths, source.");
  m.def("convert_light", &convert, py::arg("value"), py::arg("from_unit"), py::arg("to_unit"), py::kw_only(),
        py::arg("cone_deg") = 180.0,
        R"(convert_light(value, from_unit, to_unit, *, cone_deg=180.0)

Converts a light value (a number or r, g, b; finite, >= 0) between named units of the same quantity
(light_units()): game light units, radiometric (W/m2, W/sr, W/m2/sr, W), photometric (lux, cd, nit, lm) and
Blender's. A game colour of 1 is the radiance a white Lambert surface facing the light shows: its irradiance
is pi W/m2, so convert_light(1, 'game', 'W/m2') == pi. cone_deg: a spot light's outer half-angle for W and lm
(180: a point light). Returns a float for a number, a (3,) array for r, g, b.)");
  m.def("light_units", &units, "light_units() -> list[dict]\n\nThe named light units: name, quantity, description.");
}

}  // namespace shadelab::python
