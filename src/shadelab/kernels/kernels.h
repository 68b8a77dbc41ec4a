// shadelab kernels: every formula written once in the shading dialect (sl.h), compiled here as C++ in
// double precision inside namespace shadelab::kernel. The shader exporter reads the same files (in the
// order listed here, which is their dependency order) and writes them as GLSL, GLSL ES or HLSL.
#pragma once

#include "shadelab/kernels/sl.h"

namespace shadelab::kernel {

// Texel fetches of the precomputed tables (tables.h): the one language-specific piece of the kernels. The
// C++ definitions (tables.cpp) read the tables computed at first use; a shader defines them over const
// arrays of the same numbers (ggx_energy_table() gives them to the exporter).
real ggx_energy_texel(int g, int row, int col);
real ggx_energy_average_texel(int g, int row);

// clang-format off
#include "shadelab/kernels/common.sl"
#include "shadelab/kernels/fresnel.sl"
#include "shadelab/kernels/microfacet.sl"
#include "shadelab/kernels/ggx_energy.sl"
#include "shadelab/kernels/lambert.sl"
#include "shadelab/kernels/phong.sl"
#include "shadelab/kernels/blinn_phong.sl"
#include "shadelab/kernels/cook_torrance.sl"
#include "shadelab/kernels/minimalist_cook_torrance.sl"
#include "shadelab/kernels/ward.sl"
#include "shadelab/kernels/lafortune.sl"
#include "shadelab/kernels/wrapped_diffuse.sl"
#include "shadelab/kernels/ggx.sl"
#include "shadelab/kernels/burley.sl"
#include "shadelab/kernels/filament.sl"
// clang-format on
}  // namespace shadelab::kernel
