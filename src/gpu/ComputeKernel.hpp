// One compute pipeline with its descriptor set and push constant block
// (KernelLayout): the unit every pass (render, test kernels) is built from.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "gpu/KernelLayout.hpp"

namespace rt {

// A compute pipeline for SPIR-V whose entry point is `main`; the shader
// module lives only while the pipeline is created. Throws on failure.
VkPipeline createComputePipeline(VkDevice device, const std::vector<uint32_t>& spirv,
                                 VkPipelineLayout layout);

class ComputeKernel {
 public:
  ComputeKernel(VulkanContext& context, const std::vector<uint32_t>& spirv,
                const std::vector<KernelBinding>& bindings, uint32_t pushConstantBytes);
  // All bindings storage buffers.
  ComputeKernel(VulkanContext& context, const std::vector<uint32_t>& spirv,
                const std::vector<uint32_t>& storageBindings, uint32_t pushConstantBytes);
  ~ComputeKernel();
  ComputeKernel(const ComputeKernel&) = delete;
  ComputeKernel& operator=(const ComputeKernel&) = delete;

  // See KernelLayout: only while no dispatch is in flight.
  void bind(uint32_t binding, const Buffer& buffer) { layout_.bind(binding, buffer); }
  void bindTexels(uint32_t binding, const Buffer& buffer, VkFormat format) {
    layout_.bindTexels(binding, buffer, format);
  }
  void bindAccelerationStructure(uint32_t binding, VkAccelerationStructureKHR structure) {
    layout_.bindAccelerationStructure(binding, structure);
  }

  // Records a dispatch followed by a barrier that makes its writes visible to
  // the next dispatch and to transfers.
  void recordDispatch(VkCommandBuffer commands, const void* pushConstants, uint32_t groupsX,
                      uint32_t groupsY = 1, uint32_t groupsZ = 1) const;

  // Runs one workgroup with `idlePushConstants`, which must make every
  // invocation return without touching memory, and waits. Lavapipe turns a
  // pipeline into machine code at its first dispatch, not when it is
  // created: done at set-up, that time is not counted as work (1 s for
  // default.json's render kernel with Mesa's shader cache off).
  void compileNow(const void* idlePushConstants) const;

 private:
  VulkanContext& context_;
  KernelLayout layout_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace rt
