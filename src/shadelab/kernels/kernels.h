// shadelab kernels: every formula written once in the shading dialect (sl.h), compiled here as C++ in
// double precision inside namespace shadelab::kernel. The shader exporter reads the same files (in the
// order listed here, which is their dependency order) and writes them as GLSL, GLSL ES or HLSL.
#pragma once

#include "shadelab/kernels/sl.h"

namespace shadelab::kernel {
// clang-format off
#include "shadelab/kernels/common.sl"
#include "shadelab/kernels/fresnel.sl"
#include "shadelab/kernels/microfacet.sl"
#include "shadelab/kernels/lambert.sl"
#include "shadelab/kernels/phong.sl"
#include "shadelab/kernels/blinn_phong.sl"
#include "shadelab/kernels/cook_torrance.sl"
#include "shadelab/kernels/minimalist_cook_torrance.sl"
#include "shadelab/kernels/ward.sl"
#include "shadelab/kernels/lafortune.sl"
#include "shadelab/kernels/wrapped_diffuse.sl"
#include "shadelab/kernels/game_shading.sl"
#include "shadelab/kernels/sh9.sl"
// clang-format on
}  // namespace shadelab::kernel
