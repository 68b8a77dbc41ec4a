// shadelab shader verify: a shader (the exported one, or a user's file) compiled by glslang and run on real
// drivers (Mesa's lavapipe through Vulkan; GLSL ES also in headless Chromium's WebGL 2), its output compared
// number by number with the C++ reference eval on the same direction pairs (docs/shaders.md).
//
// Error measure, per case: e = max over R, G, B of |shader - reference| / max(|reference|, floor), with the
// absolute floor kRelativeErrorFloor (1/sr): values below it are compared absolutely. The reference is the C++
// eval (double precision) at exactly the float directions the shader received. A shader passes when the
// maximum e is at most the tolerance (1e-4 by default: float32 arithmetic and the drivers' transcendentals
// stay well inside it for the models' default parameters) and no output is NaN or infinite.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "shadelab/brdf/registry.h"
#include "shadelab/color/rgb.h"
#include "shadelab/core/error.h"
#include "shadelab/core/vec.h"
#include "translate.h"

namespace shadelab::shaders {

inline constexpr double kRelativeErrorFloor = 1e-3;  // 1/sr; 0.3% of a white Lambertian's 1/pi
inline constexpr double kDefaultTolerance = 1e-4;
inline constexpr std::uint64_t kDefaultSeed = 20240601;

// n direction pairs, 8 floats each (wi.xyz, 0, wo.xyz, 0), deterministic for a seed. The mix: 60% both
// directions uniform over the upper hemisphere, 15% wi near the mirror direction of wo (angles from 1e-4 to
// 0.5 rad, where sharp lobes peak), 10% one direction grazing (z from 1e-5 to 0.03), 5% both grazing, 10% one
// or both on (z = 0) or below the horizon; the first pairs are fixed (normal incidence, the mirror pair, ...).
std::vector<float> verification_pairs(std::size_t n, std::uint64_t seed);

struct CaseResult {
  std::array<float, 3> wi{}, wo{};
  std::array<float, 3> shader{};
  std::array<double, 3> reference{};
  double rel_error = 0.0;
};

struct DeviceReport {
  std::string device;
  std::size_t cases = 0;
  double max_rel_error = 0.0;   // over the finite outputs
  double mean_rel_error = 0.0;  // over the finite outputs
  std::size_t nonfinite = 0;    // cases with a NaN or infinite component
  std::optional<CaseResult> worst;  // the first non-finite case if any, else the largest error
};

// Compares shader outputs (4 floats per case) with a reference on the same inputs (8 floats per case).
DeviceReport compare_outputs(const std::string& device, const std::vector<float>& input, const std::vector<float>& output,
                             const std::function<Rgb(const Vec3& wi, const Vec3& wo)>& reference);

// Several devices' reports as one: one device, that device; two, the worse of each figure (docs/shaders.md).
DeviceReport combine_reports(const std::vector<DeviceReport>& reports);

enum class VerifyDevice { all, vulkan, webgl2 };

struct VerifyOptions {
  std::string model;
  ParamAssignments params;
  Lang lang = Lang::glsl;
  std::string source;  // a user's shader file; empty: verify the exported shader
  std::string entry;   // empty: the export's default (brdf_<model>)
  std::size_t cases = 100000;
  bool uniforms = false;  // the shader reads the parameters from the uniform block (std140, binding 0)
  VerifyDevice device = VerifyDevice::all;  // GLSL ES: lavapipe and WebGL 2; the others run on Vulkan only
  double tolerance = kDefaultTolerance;
  std::uint64_t seed = kDefaultSeed;
  // Non-empty: verify the environment lighting (verify_ibl.h) with the files `bake ibl` wrote in this
  // directory, on a sphere of ibl_size x ibl_size pixels, instead of f_r on direction pairs.
  std::string ibl_dir;
  int ibl_size = 128;
};

struct VerifyReport {
  Lang lang = Lang::glsl;
  std::vector<DeviceReport> devices;
  DeviceReport combined;  // one device: that device; two: the worse of each figure (docs/shaders.md)
  double tolerance = kDefaultTolerance;
  bool passed = false;
  std::size_t pixels = 0;  // ibl: the pixels compared (cases of each device)
};

// Bad input (unknown model or parameter, unreadable --source, a file that does not compile, a missing entry)
// and unavailable tools are errors; a shader that runs and differs is a report with passed = false.
Result<VerifyReport> verify_shader(const VerifyOptions& options);

// Comments out a leading #version line (the harness supplies its own), keeping the line numbering.
std::string strip_version_directive(const std::string& code);

}  // namespace shadelab::shaders
