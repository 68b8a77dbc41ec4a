// The Python module `shadelab`: the library's BRDFs, analysis, light units, images, environment baking and
// renderers over NumPy arrays. docs/python.md documents the API; help(shadelab) shows the same.
#include "bindings.h"
#include "common.h"

PYBIND11_MODULE(shadelab, m) {
  m.doc() = R"(shadelab: physically based shading, correct and checkable.

BRDF models with exact normalizations (models(), Brdf: vectorized eval / pdf / sample on (N, 3) arrays,
directional albedo, the check report), the normalization zoo (zoo), Fresnel (fresnel), light units
(convert_light), images as float32 (H, W, 3) arrays (read_image, write_image, compare), environment baking
(bake_sh, bake_irradiance) and the path tracer (render).

Conventions (docs/conventions.md): local shading frame with the normal on +Z; wi toward the light, wo toward
the viewer; f_r in 1/sr without the cosine; linear Rec.709 RGB. Bad input raises ValueError with the one line
the command-line tool prints. Loops run in C++ with the GIL released.)";
  m.attr("__version__") = SHADELAB_VERSION;
  // Each docstring starts with its Python signature; pybind11's own would name C++ types (handle).
  pybind11::options options;
  options.disable_function_signatures();
  shadelab::python::bind_brdf(m);
  shadelab::python::bind_analysis(m);
  shadelab::python::bind_light(m);
  shadelab::python::bind_images(m);
  shadelab::python::bind_render(m);
  shadelab::python::bind_fit(m);
}
