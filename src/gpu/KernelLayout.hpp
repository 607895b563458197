// A compute pipeline's layout with its one descriptor set (set 0) and push
// constant block: what a kernel's buffers are bound to. ComputeKernel adds
// its pipeline; the viewer's display pass adds one that a shader reload
// replaces while the bindings stay.
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

class KernelLayout {
 public:
  // Throws on failure.
  KernelLayout(VulkanContext& context, const std::vector<KernelBinding>& bindings,
               uint32_t pushConstantBytes);
  ~KernelLayout();
  KernelLayout(const KernelLayout&) = delete;
  KernelLayout& operator=(const KernelLayout&) = delete;

  VkPipelineLayout pipelineLayout() const { return pipelineLayout_; }

  // Points a storage- or uniform-buffer binding at a buffer; only while no
  // dispatch is in flight.
  void bind(uint32_t binding, const Buffer& buffer);
  // Points a uniform- or storage-texel-buffer binding at a buffer seen as `format` texels.
  void bindTexels(uint32_t binding, const Buffer& buffer, VkFormat format);
  // Points an ACCELERATION_STRUCTURE_KHR binding at a top level.
  void bindAccelerationStructure(uint32_t binding, VkAccelerationStructureKHR structure);

  // Records binding `pipeline` (made with pipelineLayout()), the descriptor
  // set and the push constants, ready for a dispatch.
  void recordBind(VkCommandBuffer commands, VkPipeline pipeline, const void* pushConstants) const;

 private:
  void destroy();
  VkDescriptorType declaredType(uint32_t binding, VkDescriptorType fallback) const;
  void writeDescriptor(uint32_t binding, VkDescriptorType type,
                       const VkDescriptorBufferInfo* bufferInfo, const VkBufferView* texelView);

  VulkanContext& context_;
  uint32_t pushConstantBytes_ = 0;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  std::vector<VkBufferView> views_;  // owned, one per bindTexels call
  std::vector<KernelBinding> declared_;
};

}  // namespace rt
