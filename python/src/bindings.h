// The parts of the Python module, one function per source file; module.cpp calls them in order.
#pragma once

#include <pybind11/pybind11.h>

namespace shadelab::python {

void bind_brdf(pybind11::module_& m);      // brdf.cpp: models(), Brdf
void bind_analysis(pybind11::module_& m);  // analysis.cpp: zoo()
void bind_light(pybind11::module_& m);     // light.cpp: fresnel(), convert_light(), their lists
void bind_images(pybind11::module_& m);    // images.cpp: read_image, write_image, compare, bake_sh, bake_irradiance
void bind_render(pybind11::module_& m);    // render.cpp: render()
void bind_fit(pybind11::module_& m);       // fit.cpp: fit_grid(), fit(), convert_shininess()

}  // namespace shadelab::python
