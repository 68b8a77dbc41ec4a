// shadelab shader exporter: the kernel text (src/shadelab/kernels/*.sl, embedded at build time in the order
// kernels.h includes them, which is their dependency order) read at the level the exporter needs: each file's
// top-level definitions (structs, constants, functions) and the identifiers it uses, so that an export
// carries only the kernel files a model needs, in dependency order; and the parameter structs' fields, so a
// model's KernelBinding can be checked against them and baked or packed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "shadelab/core/error.h"
#include "translate.h"

namespace shadelab::shaders {

struct KernelFile {
  std::string name;  // "phong.sl"
  std::string text;
};

// Generated at build time (kernel_text.cpp, from the .sl files): the library's kernels in kernels.h order,
// and the exporter's own shader-only support kernels (erf.sl: GLSL and HLSL have no erf).
std::span<const KernelFile> embedded_kernel_files();
std::span<const KernelFile> embedded_support_files();
// The GGX energy tables (kernels/tables.h) in a shader: a uniform block of vec4 (kGgxEnergyBlock, member
// kGgxEnergyMember) holding the E(mu, alpha) texels and then the E_avg(alpha) averages, in float. The kernel
// file holds the two texel fetches the C++ defines in kernels.h (ggx_energy_texel, ggx_energy_average_texel),
// reading that block; embedded() puts it after the support files. The exporter declares the block
// (ggx_energy_block_declaration) in any shader whose kernels use the file, and the application uploads
// ggx_energy_block_data().
inline constexpr const char* kGgxEnergyBlock = "ShadelabGgxEnergy";
inline constexpr const char* kGgxEnergyMember = "shadelab_ggx_energy";
inline constexpr int kGgxEnergyTexels = 2 * 32 * 32;
inline constexpr int kGgxEnergyAverages = 2 * 32;
inline constexpr int kGgxEnergyVec4s = (kGgxEnergyTexels + kGgxEnergyAverages + 3) / 4;
inline constexpr const char* kGgxEnergyTableFile = "ggx_energy_tables.sl";
KernelFile ggx_energy_table_file();
std::vector<std::uint8_t> ggx_energy_block_data();
std::string ggx_energy_block_declaration(Lang lang);
// The sheen lobe's albedo table (kernels/sheen.sl, tables.h SheenEnergyTable) the same way: a uniform block of vec4
// holding the 2 x 64 x 32 texels (charlie, then ashikhmin), four to a vec4 (16384 bytes: WebGL 2's and GLSL's
// smallest allowed MAX_UNIFORM_BLOCK_SIZE), fetched by sheen_energy_texel. A shader reads one tables block at most.
inline constexpr const char* kSheenEnergyBlock = "ShadelabSheenEnergy";
inline constexpr const char* kSheenEnergyMember = "shadelab_sheen_energy";
inline constexpr int kSheenEnergyTexels = 2 * 64 * 32;
inline constexpr int kSheenEnergyVec4s = kSheenEnergyTexels / 4;
inline constexpr const char* kSheenEnergyTableFile = "sheen_energy_tables.sl";
KernelFile sheen_energy_table_file();
std::vector<std::uint8_t> sheen_energy_block_data();
std::string sheen_energy_block_declaration(Lang lang);

enum class FieldType { real, integer, rgb, vec3, boolean };

struct StructField {
  FieldType type = FieldType::real;
  std::string type_name;  // as written: real, int, rgb, vec3, bool
  std::string name;
  int array_size = 0;  // 0: not an array
  // Number of scalars the field holds: 1 (real, int, bool), 3 (rgb, vec3), times array_size for an array.
  int scalar_count() const;
};

struct StructDecl {
  std::string name;
  std::vector<StructField> fields;
};

class KernelLibrary {
 public:
  // Reads the files (support files first, then kernels, each in the given order). Errors name the file and
  // line: a struct field of a type the exporter cannot bake, an array size that is not an int constant, a
  // name defined twice, or a file that uses a name defined in a later file (the order must be dependency order).
  static Result<KernelLibrary> parse(std::vector<KernelFile> files);
  // The embedded support files and kernels, parsed once (an error there is a build defect: throws).
  static const KernelLibrary& embedded();

  const std::vector<KernelFile>& files() const { return m_files; }
  // Index of the file that defines `name` at top level, if any.
  std::optional<std::size_t> defining_file(const std::string& name) const;
  // The files needed for the given top-level names: those defining them and, transitively, the files defining
  // the names those use; in library (dependency) order. Unknown names are ignored (built-ins).
  std::vector<std::size_t> closure(const std::vector<std::string>& names) const;
  const StructDecl* find_struct(const std::string& name) const;
  // The parameter type P of `S K_prepare(P p)` for kernel K, if the kernel exists.
  std::optional<std::string> prepare_parameter_type(const std::string& kernel) const;
  std::optional<long long> int_constant(const std::string& name) const;

 private:
  struct FileInfo {
    std::set<std::string> defines;
    std::set<std::string> uses;
  };
  std::vector<KernelFile> m_files;
  std::vector<FileInfo> m_info;
  std::map<std::string, std::size_t> m_defined_in;
  std::map<std::string, StructDecl> m_structs;
  std::map<std::string, long long> m_int_constants;
  std::map<std::string, std::string> m_prepare_parameter;  // kernel -> P
};

}  // namespace shadelab::shaders
