#include "vulkan_compute.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace shadelab::shaders {

namespace {

constexpr std::size_t kGroup = 64;  // local_size_x of the harness

// A zeroed Vulkan create-info structure with its sType set.
template <typename T>
T vk_struct(VkStructureType type) {
  T v{};
  v.sType = type;
  return v;
}

Error vk_error(const char* what, VkResult r) {
  return make_error(std::string("Vulkan: ") + what + " failed (VkResult " + std::to_string(static_cast<int>(r)) + ")");
}

}  // namespace

struct VulkanDevice::Impl {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  VkPhysicalDeviceMemoryProperties memory{};

  ~Impl() {
    if (device != VK_NULL_HANDLE) vkDestroyDevice(device, nullptr);
    if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
  }

  Result<std::uint32_t> memory_type(std::uint32_t bits) const {
    const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
      if ((bits & (1u << i)) != 0 && (memory.memoryTypes[i].propertyFlags & want) == want) return i;
    }
    return make_error("Vulkan: no host-visible coherent memory type");
  }
};

struct ComputeJob::Impl {
  std::shared_ptr<VulkanDevice::Impl> dev;  // keeps the device alive
  struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;
  };
  Buffer uniform, input, output, tables, texels;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
  VkShaderModule module = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;

  ~Impl() {
    VkDevice d = dev->device;
    if (fence) vkDestroyFence(d, fence, nullptr);
    if (command_pool) vkDestroyCommandPool(d, command_pool, nullptr);
    if (pool) vkDestroyDescriptorPool(d, pool, nullptr);
    if (pipeline) vkDestroyPipeline(d, pipeline, nullptr);
    if (module) vkDestroyShaderModule(d, module, nullptr);
    if (pipeline_layout) vkDestroyPipelineLayout(d, pipeline_layout, nullptr);
    if (set_layout) vkDestroyDescriptorSetLayout(d, set_layout, nullptr);
    for (Buffer* b : {&uniform, &input, &output, &tables, &texels}) {
      if (b->mapped) vkUnmapMemory(d, b->memory);
      if (b->buffer) vkDestroyBuffer(d, b->buffer, nullptr);
      if (b->memory) vkFreeMemory(d, b->memory, nullptr);
    }
  }

  Result<bool> make_buffer(Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage) {
    auto info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    if (VkResult r = vkCreateBuffer(dev->device, &info, nullptr, &b.buffer); r != VK_SUCCESS) return vk_error("vkCreateBuffer", r);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev->device, b.buffer, &req);
    auto type = dev->memory_type(req.memoryTypeBits);
    if (!type) return type.error();
    auto alloc = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = *type;
    if (VkResult r = vkAllocateMemory(dev->device, &alloc, nullptr, &b.memory); r != VK_SUCCESS) return vk_error("vkAllocateMemory", r);
    if (VkResult r = vkBindBufferMemory(dev->device, b.buffer, b.memory, 0); r != VK_SUCCESS) return vk_error("vkBindBufferMemory", r);
    if (VkResult r = vkMapMemory(dev->device, b.memory, 0, size, 0, &b.mapped); r != VK_SUCCESS) return vk_error("vkMapMemory", r);
    b.size = size;
    return true;
  }
};

ComputeJob::~ComputeJob() = default;

Result<bool> ComputeJob::execute() {
  Impl& j = *m_impl;
  VkDevice d = j.dev->device;
  if (VkResult r = vkResetFences(d, 1, &j.fence); r != VK_SUCCESS) return vk_error("vkResetFences", r);
  auto submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &j.commands;
  if (VkResult r = vkQueueSubmit(j.dev->queue, 1, &submit, j.fence); r != VK_SUCCESS) return vk_error("vkQueueSubmit", r);
  const std::uint64_t timeout_ns = 300ull * 1000000000ull;
  if (VkResult r = vkWaitForFences(d, 1, &j.fence, VK_TRUE, timeout_ns); r != VK_SUCCESS) {
    return r == VK_TIMEOUT ? make_error("Vulkan: the compute dispatch did not finish in 300 s") : vk_error("vkWaitForFences", r);
  }
  return true;
}

std::vector<float> ComputeJob::output() const {
  const auto* p = static_cast<const float*>(m_impl->output.mapped);
  return std::vector<float>(p, p + 4 * m_cases);
}

VulkanDevice::~VulkanDevice() = default;

Result<std::shared_ptr<VulkanDevice>> VulkanDevice::open() {
  auto impl = std::make_shared<Impl>();
  auto app = vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = "shadelab shader verify";
  app.apiVersion = VK_API_VERSION_1_1;
  auto ici = vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  ici.pApplicationInfo = &app;
  if (VkResult r = vkCreateInstance(&ici, nullptr, &impl->instance); r != VK_SUCCESS) {
    return make_error("Vulkan: no instance (VkResult " + std::to_string(static_cast<int>(r)) +
                      "); install Debian's mesa-vulkan-drivers for the CPU device lavapipe (scripts/setup.sh)");
  }
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(impl->instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  if (count > 0) vkEnumeratePhysicalDevices(impl->instance, &count, devices.data());
  const char* want = std::getenv("SHADELAB_VULKAN_DEVICE");
  std::string names;
  for (VkPhysicalDevice pd : devices) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    const std::string name = props.deviceName;
    names += (names.empty() ? "" : ", ") + name;
    const bool match = (want != nullptr && *want != '\0') ? name.find(want) != std::string::npos
                                                          : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    if (match && impl->physical == VK_NULL_HANDLE) impl->physical = pd;
  }
  if (impl->physical == VK_NULL_HANDLE) {
    if (want != nullptr && *want != '\0') {
      return make_error(std::string("Vulkan: no device matches SHADELAB_VULKAN_DEVICE='") + want + "' (devices: " +
                        (names.empty() ? "none" : names) + ")");
    }
    return make_error("Vulkan: no CPU device (lavapipe); install Debian's mesa-vulkan-drivers (scripts/setup.sh); devices: " +
                      (names.empty() ? std::string("none") : names));
  }
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(impl->physical, &props);
  vkGetPhysicalDeviceMemoryProperties(impl->physical, &impl->memory);
  std::uint32_t nq = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(impl->physical, &nq, nullptr);
  std::vector<VkQueueFamilyProperties> families(nq);
  vkGetPhysicalDeviceQueueFamilyProperties(impl->physical, &nq, families.data());
  bool found = false;
  for (std::uint32_t i = 0; i < nq && !found; ++i) {
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) != 0) {
      impl->queue_family = i;
      found = true;
    }
  }
  if (!found) return make_error(std::string("Vulkan: device ") + props.deviceName + " has no compute queue");
  const float priority = 1.0f;
  auto qci = vk_struct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  qci.queueFamilyIndex = impl->queue_family;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  auto dci = vk_struct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  if (VkResult r = vkCreateDevice(impl->physical, &dci, nullptr, &impl->device); r != VK_SUCCESS) return vk_error("vkCreateDevice", r);
  vkGetDeviceQueue(impl->device, impl->queue_family, 0, &impl->queue);
  std::shared_ptr<VulkanDevice> dev(new VulkanDevice());
  dev->m_name = props.deviceName;
  dev->m_impl = std::move(impl);
  return dev;
}

Result<std::unique_ptr<ComputeJob>> VulkanDevice::prepare(const std::vector<std::uint32_t>& spirv,
                                                          const std::vector<float>& input,
                                                          const std::vector<std::uint8_t>& uniform,
                                                          const std::vector<std::uint8_t>& tables,
                                                          const std::vector<float>& texels) {
  if (input.size() % 8 != 0) return make_error("Vulkan: the input holds 8 floats per case");
  const std::size_t cases = input.size() / 8;
  const std::size_t padded = std::max<std::size_t>(kGroup, (cases + kGroup - 1) / kGroup * kGroup);
  std::unique_ptr<ComputeJob> job(new ComputeJob());
  job->m_cases = cases;
  job->m_impl = std::make_unique<ComputeJob::Impl>();
  ComputeJob::Impl& j = *job->m_impl;
  j.dev = m_impl;
  VkDevice d = m_impl->device;

  const VkDeviceSize uniform_size = std::max<std::size_t>(16, (uniform.size() + 15) / 16 * 16);
  if (auto ok = j.make_buffer(j.uniform, uniform_size, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT); !ok) return ok.error();
  if (auto ok = j.make_buffer(j.input, padded * 8 * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT); !ok) return ok.error();
  if (auto ok = j.make_buffer(j.output, padded * 4 * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT); !ok) return ok.error();
  const VkDeviceSize tables_size = std::max<std::size_t>(16, (tables.size() + 15) / 16 * 16);
  if (auto ok = j.make_buffer(j.tables, tables_size, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT); !ok) return ok.error();
  std::memset(j.tables.mapped, 0, tables_size);
  const VkDeviceSize texels_size = std::max<std::size_t>(16, texels.size() * sizeof(float));
  if (auto ok = j.make_buffer(j.texels, texels_size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT); !ok) return ok.error();
  std::memset(j.texels.mapped, 0, texels_size);
  if (!texels.empty()) std::memcpy(j.texels.mapped, texels.data(), texels.size() * sizeof(float));
  if (!tables.empty()) std::memcpy(j.tables.mapped, tables.data(), tables.size());
  std::memset(j.uniform.mapped, 0, uniform_size);
  if (!uniform.empty()) std::memcpy(j.uniform.mapped, uniform.data(), uniform.size());
  std::memset(j.input.mapped, 0, j.input.size);
  std::memcpy(j.input.mapped, input.data(), input.size() * sizeof(float));
  std::memset(j.output.mapped, 0xff, j.output.size);  // NaN: a case the shader does not write reads as NaN

  // 0: the parameter block, 1 and 2: the cases and the results, 3: the GGX energy tables' block, 4: texels.
  VkDescriptorSetLayoutBinding bindings[5] = {};
  for (std::uint32_t b = 0; b < 5; ++b) {
    bindings[b].binding = b;
    bindings[b].descriptorType = (b == 0 || b == 3) ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[b].descriptorCount = 1;
    bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  auto dsl = vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  dsl.bindingCount = 5;
  dsl.pBindings = bindings;
  if (VkResult r = vkCreateDescriptorSetLayout(d, &dsl, nullptr, &j.set_layout); r != VK_SUCCESS) return vk_error("vkCreateDescriptorSetLayout", r);
  auto pli = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &j.set_layout;
  if (VkResult r = vkCreatePipelineLayout(d, &pli, nullptr, &j.pipeline_layout); r != VK_SUCCESS) return vk_error("vkCreatePipelineLayout", r);
  auto smi = vk_struct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  smi.codeSize = spirv.size() * sizeof(std::uint32_t);
  smi.pCode = spirv.data();
  if (VkResult r = vkCreateShaderModule(d, &smi, nullptr, &j.module); r != VK_SUCCESS) return vk_error("vkCreateShaderModule", r);
  auto cpi = vk_struct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
  cpi.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  cpi.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  cpi.stage.module = j.module;
  cpi.stage.pName = "main";
  cpi.layout = j.pipeline_layout;
  if (VkResult r = vkCreateComputePipelines(d, VK_NULL_HANDLE, 1, &cpi, nullptr, &j.pipeline); r != VK_SUCCESS) {
    return vk_error("vkCreateComputePipelines", r);
  }
  VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3}};
  auto dpi = vk_struct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  dpi.maxSets = 1;
  dpi.poolSizeCount = 2;
  dpi.pPoolSizes = sizes;
  if (VkResult r = vkCreateDescriptorPool(d, &dpi, nullptr, &j.pool); r != VK_SUCCESS) return vk_error("vkCreateDescriptorPool", r);
  VkDescriptorSet set = VK_NULL_HANDLE;
  auto dsa = vk_struct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  dsa.descriptorPool = j.pool;
  dsa.descriptorSetCount = 1;
  dsa.pSetLayouts = &j.set_layout;
  if (VkResult r = vkAllocateDescriptorSets(d, &dsa, &set); r != VK_SUCCESS) return vk_error("vkAllocateDescriptorSets", r);
  VkDescriptorBufferInfo infos[5] = {{j.uniform.buffer, 0, VK_WHOLE_SIZE},
                                     {j.input.buffer, 0, VK_WHOLE_SIZE},
                                     {j.output.buffer, 0, VK_WHOLE_SIZE},
                                     {j.tables.buffer, 0, VK_WHOLE_SIZE},
                                     {j.texels.buffer, 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[5] = {};
  for (std::uint32_t b = 0; b < 5; ++b) {
    writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[b].dstSet = set;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = bindings[b].descriptorType;
    writes[b].pBufferInfo = &infos[b];
  }
  vkUpdateDescriptorSets(d, 5, writes, 0, nullptr);

  auto cpci = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  cpci.queueFamilyIndex = m_impl->queue_family;
  if (VkResult r = vkCreateCommandPool(d, &cpci, nullptr, &j.command_pool); r != VK_SUCCESS) return vk_error("vkCreateCommandPool", r);
  auto cba = vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  cba.commandPool = j.command_pool;
  cba.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cba.commandBufferCount = 1;
  if (VkResult r = vkAllocateCommandBuffers(d, &cba, &j.commands); r != VK_SUCCESS) return vk_error("vkAllocateCommandBuffers", r);
  auto begin = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  if (VkResult r = vkBeginCommandBuffer(j.commands, &begin); r != VK_SUCCESS) return vk_error("vkBeginCommandBuffer", r);
  vkCmdBindPipeline(j.commands, VK_PIPELINE_BIND_POINT_COMPUTE, j.pipeline);
  vkCmdBindDescriptorSets(j.commands, VK_PIPELINE_BIND_POINT_COMPUTE, j.pipeline_layout, 0, 1, &set, 0, nullptr);
  vkCmdDispatch(j.commands, static_cast<std::uint32_t>(padded / kGroup), 1, 1);
  // Make the shader's writes visible to the host's reads after the fence.
  auto barrier = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(j.commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
  if (VkResult r = vkEndCommandBuffer(j.commands); r != VK_SUCCESS) return vk_error("vkEndCommandBuffer", r);
  auto fci = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  if (VkResult r = vkCreateFence(d, &fci, nullptr, &j.fence); r != VK_SUCCESS) return vk_error("vkCreateFence", r);
  return job;
}

Result<std::vector<float>> VulkanDevice::run(const std::vector<std::uint32_t>& spirv, const std::vector<float>& input,
                                             const std::vector<std::uint8_t>& uniform,
                                             const std::vector<std::uint8_t>& tables, const std::vector<float>& texels) {
  auto job = prepare(spirv, input, uniform, tables, texels);
  if (!job) return job.error();
  if (auto ok = (*job)->execute(); !ok) return ok.error();
  return (*job)->output();
}

}  // namespace shadelab::shaders
