// shadelab shader tools: a small Vulkan compute runner (the Vulkan loader from Debian's libvulkan-dev) that runs
// a SPIR-V compute harness (glslang.h) over a batch of direction pairs. By default it uses Mesa's lavapipe,
// the CPU Vulkan device of Debian's mesa-vulkan-drivers, which every machine (and CI) has; the environment
// variable SHADELAB_VULKAN_DEVICE picks another device by a part of its name (a real GPU).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "shadelab/core/error.h"

namespace shadelab::shaders {

class VulkanDevice;

// One pipeline over fixed inputs: created once, executed any number of times (the benchmark times execute()).
class ComputeJob {
 public:
  ~ComputeJob();
  ComputeJob(const ComputeJob&) = delete;
  ComputeJob& operator=(const ComputeJob&) = delete;
  // Records nothing new: submits the dispatch and waits for it.
  Result<bool> execute();
  // Four floats per case, from the last execute().
  std::vector<float> output() const;
  std::size_t cases() const { return m_cases; }

 private:
  friend class VulkanDevice;
  ComputeJob() = default;
  struct Impl;
  std::unique_ptr<Impl> m_impl;
  std::size_t m_cases = 0;
};

class VulkanDevice {
 public:
  // Opens the device: SHADELAB_VULKAN_DEVICE's match if set, else the first CPU device (lavapipe). Errors say
  // what to install.
  static Result<std::shared_ptr<VulkanDevice>> open();
  ~VulkanDevice();
  VulkanDevice(const VulkanDevice&) = delete;
  VulkanDevice& operator=(const VulkanDevice&) = delete;

  const std::string& name() const { return m_name; }
  // input: 8 floats per case (wi.xyz, 0, wo.xyz, 0); uniform: the bytes of the uniform block at binding 0
  // (may be empty); tables: those of the GGX energy tables' block at binding 3 (may be empty). The harness's
  // work groups are 64 wide; the buffers are padded to a whole number of them.
  // texels: a read-only storage buffer at binding 4 (the IBL verification's baked textures; may be empty).
  Result<std::unique_ptr<ComputeJob>> prepare(const std::vector<std::uint32_t>& spirv, const std::vector<float>& input,
                                              const std::vector<std::uint8_t>& uniform,
                                              const std::vector<std::uint8_t>& tables = {},
                                              const std::vector<float>& texels = {});
  // prepare + execute + output.
  Result<std::vector<float>> run(const std::vector<std::uint32_t>& spirv, const std::vector<float>& input,
                                 const std::vector<std::uint8_t>& uniform, const std::vector<std::uint8_t>& tables = {},
                                 const std::vector<float>& texels = {});

  struct Impl;  // the Vulkan handles, shared with the jobs (a job keeps the device alive)

 private:
  VulkanDevice() = default;
  std::shared_ptr<Impl> m_impl;
  std::string m_name;
};

}  // namespace shadelab::shaders
