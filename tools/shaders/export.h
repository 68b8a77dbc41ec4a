// shadelab shader exporter: a model of the registry as a self-contained GLSL 4.50, GLSL ES 3.00 or HLSL
// function file (docs/shaders.md). The file holds the kernels the model needs (src/shadelab/kernels/*.sl,
// translated token by token, in dependency order), the model's parameters (baked in as constants, or with
// `uniforms` a parameter struct in a uniform block) and the entry points:
//   vec3 ENTRY(vec3 wi, vec3 wo)                                 f_r in 1/sr, local frame (normal = +Z)
//   vec3 ENTRY_punctual_game(vec3 wi, vec3 wo, vec3 colour)      pi f c N.L  (game light units)
//   vec3 ENTRY_punctual_radiometric(vec3 wi, vec3 wo, vec3 e)    f E N.L     (E in W/m^2)
//   sh9_irradiance(sh, n), sh9_irradiance_game(sh, n), sh9_irradiance_game_wrapped(sh, n, w)
// (float3 for HLSL).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "kernel_library.h"
#include "shadelab/brdf/brdf.h"
#include "shadelab/brdf/registry.h"
#include "shadelab/core/error.h"
#include "translate.h"

namespace shadelab::shaders {

struct ExportOptions {
  Lang lang = Lang::glsl;
  std::string entry;      // empty: default_entry(model)
  bool uniforms = false;  // parameters in a uniform block instead of baked constants
  std::string command;    // the command line that made the file, for its header (may be empty)
  // Also export the environment lighting of the files `shadelab bake ibl` writes: SH9 diffuse plus the split
  // sum (the GGX chain read seamlessly, the DFG table, the lobe-matched lookup), the entry ENTRY_ambient_game
  // (kernels/game_ibl.sl game_ibl_ambient). Only for the models whose kernel writes a split-sum description
  // (KERNEL_split_sum: ggx, filament).
  bool ibl = false;
};

// Where a field of the parameter struct lies in the uniform block (std140; docs/shaders.md).
struct UniformField {
  std::string name;
  std::size_t offset = 0;        // bytes from the start of the block
  std::size_t array_stride = 0;  // arrays only
};

struct ShaderExport {
  std::string text;         // the function file
  std::string entry;        // the f_r entry's name
  std::string params_type;  // the kernel's parameter struct (PhongParams, ...)
  std::string block_name;   // uniforms: the uniform block (cbuffer) name; its member is ENTRY_params
  // The parameter values as the uniform block holds them (std140), with the fields' offsets; filled in both
  // modes, so a caller can run the uniform export with exactly the values the baked one has.
  std::vector<std::uint8_t> uniform_data;
  std::vector<UniformField> uniform_layout;
  // Models with Kulla-Conty or Filament energy compensation: the uniform block of the GGX energy tables
  // (kernel_library.h, kGgxEnergyBlock) and its bytes (std140, little-endian float); both empty otherwise.
  std::string tables_block;
  std::vector<std::uint8_t> tables_data;
  std::string ibl_entry;  // ibl: ENTRY_ambient_game; empty otherwise
};

// The texture names the exported IBL fetches read (docs/shaders.md): the GGX chain as a 2D array texture (layer
// = face +X, -X, +Y, -Y, +Z, -Z; mip level i = chain level i), the DFG table (R = A, G = B) and the lobe table
// (RGBA = angle_a, roughness_a, angle_b, roughness_b).
inline constexpr const char* kIblChainTexture = "shadelab_ggx_chain";
inline constexpr const char* kIblDfgTexture = "shadelab_dfg";
inline constexpr const char* kIblLobesTexture = "shadelab_split_sum_lobes";

// The language's definitions of the IBL fetches the kernels call (kernels.h: cube_texel, cube_size, dfg_texel,
// split_sum_lobe_texel) and of shadelab_dfg_size() and shadelab_split_sum_lobe_size(), over the three textures
// with texelFetch (HLSL: Load), inside #ifndef SHADELAB_IBL_FETCHES so that an application (or the verifier)
// can define them over its own storage first.
std::string ibl_fetch_declarations(Lang lang);

// brdf_<model> with '-' -> '_': brdf_cook_torrance.
std::string default_entry(std::string_view model);
// True for a name a shader may use as a function: [A-Za-z_][A-Za-z0-9_]*, not starting with gl_ or "__".
bool valid_entry_name(std::string_view name);

// Builds the model from the registry (errors name the model and parameter) and exports it.
Result<ShaderExport> export_model(std::string_view model, const ParamAssignments& params, const ExportOptions& options);

// The translated kernel files that define `names` and what they use, in dependency order, each in an include
// guard (SHADELAB_KERNEL_<FILE>_SL) so two exported files can share one shader.
Result<std::string> kernel_section(const std::vector<std::string>& names, Lang lang);

// A float literal every target language reads as the nearest float to v: "0.5", "50.0", "1.0e-05".
std::string float_literal(double v);

// The std140 bytes of a binding's values for the struct, and the fields' offsets. Errors (a binding that does
// not match the struct's fields by name and size) are defects of a model's kernel_binding().
Result<std::vector<std::uint8_t>> pack_std140(const StructDecl& decl, const KernelBinding& binding,
                                              std::vector<UniformField>* layout = nullptr);

}  // namespace shadelab::shaders
