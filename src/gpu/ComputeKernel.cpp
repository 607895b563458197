#include "gpu/ComputeKernel.hpp"

#include "gpu/Buffer.hpp"
#include "gpu/VulkanContext.hpp"

namespace rt {

namespace {

std::vector<KernelBinding> storageOnly(const std::vector<uint32_t>& bindings) {
  std::vector<KernelBinding> result;
  for (uint32_t binding : bindings) result.push_back({binding});
  return result;
}

}  // namespace

VkPipeline createComputePipeline(VkDevice device, const std::vector<uint32_t>& spirv,
                                 VkPipelineLayout layout) {
  VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  moduleInfo.codeSize = spirv.size() * sizeof(uint32_t);
  moduleInfo.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  vkCheck(vkCreateShaderModule(device, &moduleInfo, nullptr, &module), "vkCreateShaderModule");

  VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipelineInfo.stage.module = module;
  pipelineInfo.stage.pName = "main";
  pipelineInfo.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult result =
      vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline);
  vkDestroyShaderModule(device, module, nullptr);
  vkCheck(result, "vkCreateComputePipelines");
  return pipeline;
}

ComputeKernel::ComputeKernel(VulkanContext& context, const std::vector<uint32_t>& spirv,
                             const std::vector<uint32_t>& storageBindings,
                             uint32_t pushConstantBytes)
    : ComputeKernel(context, spirv, storageOnly(storageBindings), pushConstantBytes) {}

ComputeKernel::ComputeKernel(VulkanContext& context, const std::vector<uint32_t>& spirv,
                             const std::vector<KernelBinding>& kernelBindings,
                             uint32_t pushConstantBytes)
    : context_(context), pushConstantBytes_(pushConstantBytes) {
  VkDevice device = context.device();
  try {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    std::vector<VkDescriptorPoolSize> poolSizes;
    for (const KernelBinding& binding : kernelBindings) {
      declared_.push_back(binding);
      bindings.push_back({binding.binding, binding.type, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
      poolSizes.push_back({binding.type, 1});
    }
    VkDescriptorSetLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layoutInfo.bindingCount = static_cast<uint32_t>(bindings.size());
    layoutInfo.pBindings = bindings.data();
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

    pipeline_ = createComputePipeline(device, spirv, pipelineLayout_);

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

ComputeKernel::~ComputeKernel() { destroy(); }

void ComputeKernel::destroy() {
  VkDevice device = context_.device();
  for (VkBufferView view : views_) vkDestroyBufferView(device, view, nullptr);
  views_.clear();
  if (pool_) vkDestroyDescriptorPool(device, pool_, nullptr);
  if (pipeline_) vkDestroyPipeline(device, pipeline_, nullptr);
  if (pipelineLayout_) vkDestroyPipelineLayout(device, pipelineLayout_, nullptr);
  if (setLayout_) vkDestroyDescriptorSetLayout(device, setLayout_, nullptr);
  pool_ = VK_NULL_HANDLE;
  pipeline_ = VK_NULL_HANDLE;
  pipelineLayout_ = VK_NULL_HANDLE;
  setLayout_ = VK_NULL_HANDLE;
}

void ComputeKernel::writeDescriptor(uint32_t binding, VkDescriptorType type,
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

VkDescriptorType ComputeKernel::declaredType(uint32_t binding, VkDescriptorType fallback) const {
  for (const KernelBinding& declared : declared_) {
    if (declared.binding == binding) return declared.type;
  }
  return fallback;
}

void ComputeKernel::bind(uint32_t binding, const Buffer& buffer) {
  VkDescriptorBufferInfo bufferInfo{buffer.handle(), 0, VK_WHOLE_SIZE};
  writeDescriptor(binding, declaredType(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), &bufferInfo,
                  nullptr);
}

void ComputeKernel::bindTexels(uint32_t binding, const Buffer& buffer, VkFormat format) {
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

void ComputeKernel::bindAccelerationStructure(uint32_t binding,
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

void ComputeKernel::compileNow(const void* idlePushConstants) const {
  context_.submitAndWait(
      [&](VkCommandBuffer commands) { recordDispatch(commands, idlePushConstants, 1); });
}

void ComputeKernel::recordDispatch(VkCommandBuffer commands, const void* pushConstants,
                                   uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) const {
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &set_, 0,
                          nullptr);
  if (pushConstantBytes_ > 0) {
    vkCmdPushConstants(commands, pipelineLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0,
                       pushConstantBytes_, pushConstants);
  }
  vkCmdDispatch(commands, groupsX, groupsY, groupsZ);
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  // Transfers after a dispatch read what it wrote (downloads) or overwrite
  // it (the render kernel's work queue is zeroed before each dispatch).
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                          VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                       &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace rt
