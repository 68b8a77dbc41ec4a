// shadelab kernels: every formula written once in the shading dialect (sl.h), compiled here as C++ in
// double precision inside namespace shadelab::kernel. The shader exporter reads the same files (in the
// order listed here, which is their dependency order) and writes them as GLSL, GLSL ES or HLSL.
#pragma once

#include <atomic>
#include <cstddef>

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
// The sheen lobe's albedo table (sheen.sl): texel (v, row, col) at [(v * 64 + row) * 32 + col].
const double* sheen_energy_texels();  // 2 * 64 * 32 values (tables.cpp)
inline real sheen_energy_texel(int v, int row, int col) {
  static std::atomic<const double*> cache{nullptr};
  return ggx_energy_cached(cache, sheen_energy_texels)[(v * 64 + row) * 32 + col];
}

// Texel fetches of the baked environment the split sum reads (cube.sl, game_ibl.sl): cube maps addressed by an
// index (a GGX chain's level i is cube i) and the DFG table. In C++ they read the IblTexels bound to the calling
// thread by an IblBinding (envmap/ binds its cubes and tables around each call into those kernels, the game
// renderer once per pixel); a shader defines them over its textures (tools/shaders/: texelFetch on a 2D array
// texture, one layer a face, one mip level a cube, and on the DFG texture).
struct CubeTexels {
  const float* faces[6] = {};  // RGB floats per texel, row-major, row 0 at t = 0 (envmap/cubemap.h's images)
  int size = 0;
};
struct IblTexels {
  const CubeTexels* cubes = nullptr;  // cube i of cube_texel(i, ...)
  int cube_count = 0;
  const double* dfg = nullptr;  // dfg_size^2 texels of 3 channels (A, B, A + B), row-major, row = roughness
  int dfg_size = 0;
  // The lobe table's texel (i, j), channel c (angle_a, roughness_a, angle_b, roughness_b): a call, so that the
  // C++ table can compute a row at its first read (envmap/split_sum_lobes.h).
  double (*lobe_texel)(const void* table, int i, int j, int channel) = nullptr;
  const void* lobe_table = nullptr;
  int lobe_size = 0;
};
inline constinit thread_local const IblTexels* ibl_bound_texels = nullptr;
// Binds `texels` to the calling thread for the binding's lifetime, restoring the previous binding after.
class IblBinding {
 public:
  explicit IblBinding(const IblTexels& texels) : m_previous(ibl_bound_texels) { ibl_bound_texels = &texels; }
  ~IblBinding() { ibl_bound_texels = m_previous; }
  IblBinding(const IblBinding&) = delete;
  IblBinding& operator=(const IblBinding&) = delete;

 private:
  const IblTexels* m_previous;
};
inline int cube_size(int cube) { return ibl_bound_texels->cubes[cube].size; }
inline rgb cube_texel(int cube, int face, int x, int y) {
  const CubeTexels& c = ibl_bound_texels->cubes[cube];
  const float* p = c.faces[face] + 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(c.size) + static_cast<std::size_t>(x));
  return {static_cast<real>(p[0]), static_cast<real>(p[1]), static_cast<real>(p[2])};
}
inline real split_sum_lobe_texel(int x, int y, int channel) {
  const IblTexels& t = *ibl_bound_texels;
  return t.lobe_texel(t.lobe_table, x, y, channel);
}
inline real dfg_texel(int x, int y, int channel) {
  const IblTexels& t = *ibl_bound_texels;
  return t.dfg[(static_cast<std::size_t>(y) * static_cast<std::size_t>(t.dfg_size) + static_cast<std::size_t>(x)) * 3 +
               static_cast<std::size_t>(channel)];
}

// clang-format off
#include "shadelab/kernels/common.sl"
#include "shadelab/kernels/fresnel.sl"
#include "shadelab/kernels/microfacet.sl"
#include "shadelab/kernels/ggx_energy.sl"
#include "shadelab/kernels/sheen.sl"
#include "shadelab/kernels/split_sum.sl"
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
#include "shadelab/kernels/gltf.sl"
#include "shadelab/kernels/principled_v1.sl"
#include "shadelab/kernels/game_shading.sl"
#include "shadelab/kernels/sh9.sl"
#include "shadelab/kernels/game_ambient.sl"
#include "shadelab/kernels/cube.sl"
#include "shadelab/kernels/game_ibl.sl"
#include "shadelab/kernels/display.sl"
// clang-format on
}  // namespace shadelab::kernel
