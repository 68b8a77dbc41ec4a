// shadelab kernels: every formula written once in the shading dialect (sl.h), compiled here as C++ in
// double precision inside namespace shadelab::kernel. The shader exporter reads the same files (in the
// order listed here, which is their dependency order) and writes them as GLSL, GLSL ES or HLSL.
#pragma once

#include <atomic>

#include "shadelab/kernels/sl.h"

namespace shadelab::kernel {

// Texel fetches of the precomputed tables (tables.h): the one language-specific piece of the kernels. In C++
// they read the tables computed at first use (tables.cpp; the pointer is cached here so that a fetch is an
// inlined load); a shader defines them over const arrays of the same numbers (ggx_energy_table() gives them
// to the exporter). The layout: texel (g, row, col) at [(g * ROWS + row) * COLS + col], averages at
// [g * ROWS + row].
const double* ggx_energy_texels();          // 2 * 32 * 32 values (tables.cpp)
const double* ggx_energy_average_texels();  // 2 * 32 values
inline const double* ggx_energy_cached(std::atomic<const double*>& cache, const double* (*compute)()) {
  const double* p = cache.load(std::memory_order_acquire);
  if (p == nullptr) {
    p = compute();  // thread-safe and computed once (function-local statics in tables.cpp)
    cache.store(p, std::memory_order_release);
  }
  return p;
}
inline real ggx_energy_texel(int g, int row, int col) {
  static std::atomic<const double*> cache{nullptr};
  return ggx_energy_cached(cache, ggx_energy_texels)[(g * 32 + row) * 32 + col];
}
inline real ggx_energy_average_texel(int g, int row) {
  static std::atomic<const double*> cache{nullptr};
  return ggx_energy_cached(cache, ggx_energy_average_texels)[g * 32 + row];
}

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
#include "shadelab/kernels/game_shading.sl"
#include "shadelab/kernels/sh9.sl"
#include "shadelab/kernels/game_ambient.sl"
#include "shadelab/kernels/display.sl"
// clang-format on
}  // namespace shadelab::kernel
