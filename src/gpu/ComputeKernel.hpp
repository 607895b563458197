// One compute pipeline with its descriptor set of storage buffers and a push
// constant block: the unit every pass (render, test kernels) is built from.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace rt {

class Buffer;
class VulkanContext;

// One binding of descriptor set 0.
struct KernelBinding {
  uint32_t binding = 0;
  // or UNIFORM_BUFFER (bound with bind), UNIFORM_TEXEL_BUFFER or
  // STORAGE_TEXEL_BUFFER (bound with bindTexels), ACCELERATION_STRUCTURE_KHR
  // (bound with bindAccelerationStructure)
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
};

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

  // Points a storage- or uniform-buffer binding at a buffer; only while no
  // dispatch is in flight.
  void bind(uint32_t binding, const Buffer& buffer);
  // Points a uniform- or storage-texel-buffer binding at a buffer seen as `format` texels.
  void bindTexels(uint32_t binding, const Buffer& buffer, VkFormat format);
  // Points an ACCELERATION_STRUCTURE_KHR binding at a top level.
  void bindAccelerationStructure(uint32_t binding, VkAccelerationStructureKHR structure);

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
  void destroy();
  VkDescriptorType declaredType(uint32_t binding, VkDescriptorType fallback) const;
  void writeDescriptor(uint32_t binding, VkDescriptorType type,
                       const VkDescriptorBufferInfo* bufferInfo, const VkBufferView* texelView);

  VulkanContext& context_;
  uint32_t pushConstantBytes_ = 0;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  std::vector<VkBufferView> views_;  // owned, one per bindTexels call
  std::vector<KernelBinding> declared_;
};

}  // namespace rt
