#include "gpu/KernelLayout.hpp"

#include "gpu/Buffer.hpp"
#include "gpu/VulkanContext.hpp"

namespace rt {

KernelLayout::KernelLayout(VulkanContext& context, const std::vector<KernelBinding>& bindings,
                           uint32_t pushConstantBytes)
    : context_(context), pushConstantBytes_(pushConstantBytes), declared_(bindings) {
  VkDevice device = context.device();
  try {
    std::vector<VkDescriptorSetLayoutBinding> setBindings;
    std::vector<VkDescriptorPoolSize> poolSizes;
    for (const KernelBinding& binding : bindings) {
      setBindings.push_back(
          {binding.binding, binding.type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
      poolSizes.push_back({binding.type, 1});
    }
    VkDescriptorSetLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layoutInfo.bindingCount = static_cast<uint32_t>(setBindings.size());
    layoutInfo.pBindings = setBindings.data();
    vkCheck(vkCreateDescriptorSetLayout(device, &layoutInfo, nullptr, &setLayout_),
            "vkCreateDescriptorSetLayout");

    VkPushConstantRange pushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo pipelineLayoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pipelineLayoutInfo.setLayoutCount = 1;
    pipelineLayoutInfo.pSetLayouts = &setLayout_;
    pipelineLayoutInfo.pushConstantRangeCount = pushConstantBytes > 0 ? 1 : 0;
    pipelineLayoutInfo.pPushConstantRanges = &pushRange;
    vkCheck(vkCreatePipelineLayout(device, &pipelineLayoutInfo, nullptr, &pipelineLayout_),
            "vkCreatePipelineLayout");

    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = static_cast<uint32_t>(poolSizes.size());
    poolInfo.pPoolSizes = poolSizes.data();
    vkCheck(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool_), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    setInfo.descriptorPool = pool_;
    setInfo.descriptorSetCount = 1;
    setInfo.pSetLayouts = &setLayout_;
    vkCheck(vkAllocateDescriptorSets(device, &setInfo, &set_), "vkAllocateDescriptorSets");
  } catch (...) {
    destroy();
    throw;
  }
}

KernelLayout::~KernelLayout() { destroy(); }

void KernelLayout::destroy() {
  VkDevice device = context_.device();
  for (VkBufferView view : views_) vkDestroyBufferView(device, view, nullptr);
  views_.clear();
  if (pool_) vkDestroyDescriptorPool(device, pool_, nullptr);
  if (pipelineLayout_) vkDestroyPipelineLayout(device, pipelineLayout_, nullptr);
  if (setLayout_) vkDestroyDescriptorSetLayout(device, setLayout_, nullptr);
  pool_ = VK_NULL_HANDLE;
  pipelineLayout_ = VK_NULL_HANDLE;
  setLayout_ = VK_NULL_HANDLE;
}

void KernelLayout::writeDescriptor(uint32_t binding, VkDescriptorType type,
                                   const VkDescriptorBufferInfo* bufferInfo,
                                   const VkBufferView* texelView) {
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = set_;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = type;
  write.pBufferInfo = bufferInfo;
  write.pTexelBufferView = texelView;
  vkUpdateDescriptorSets(context_.device(), 1, &write, 0, nullptr);
}

VkDescriptorType KernelLayout::declaredType(uint32_t binding, VkDescriptorType fallback) const {
  for (const KernelBinding& declared : declared_) {
    if (declared.binding == binding) return declared.type;
  }
  return fallback;
}

void KernelLayout::bind(uint32_t binding, const Buffer& buffer) {
  VkDescriptorBufferInfo bufferInfo{buffer.handle(), 0, VK_WHOLE_SIZE};
  writeDescriptor(binding, declaredType(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), &bufferInfo,
                  nullptr);
}

void KernelLayout::bindTexels(uint32_t binding, const Buffer& buffer, VkFormat format) {
  VkBufferViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  viewInfo.buffer = buffer.handle();
  viewInfo.format = format;
  viewInfo.range = VK_WHOLE_SIZE;
  VkBufferView view = VK_NULL_HANDLE;
  vkCheck(vkCreateBufferView(context_.device(), &viewInfo, nullptr, &view), "vkCreateBufferView");
  views_.push_back(view);
  writeDescriptor(binding, declaredType(binding, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER), nullptr,
                  &view);
}

void KernelLayout::bindAccelerationStructure(uint32_t binding,
                                             VkAccelerationStructureKHR structure) {
  VkWriteDescriptorSetAccelerationStructureKHR structures{
      VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  structures.accelerationStructureCount = 1;
  structures.pAccelerationStructures = &structure;
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.pNext = &structures;
  write.dstSet = set_;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  vkUpdateDescriptorSets(context_.device(), 1, &write, 0, nullptr);
}

void KernelLayout::recordBind(VkCommandBuffer commands, VkPipeline pipeline,
                              const void* pushConstants) const {
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &set_, 0,
                          nullptr);
  if (pushConstantBytes_ > 0) {
    vkCmdPushConstants(commands, pipelineLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       pushConstantBytes_, pushConstants);
  }
}

}  // namespace rt
