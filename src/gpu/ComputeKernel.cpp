#include "gpu/ComputeKernel.hpp"

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
                             const std::vector<KernelBinding>& bindings, uint32_t pushConstantBytes)
    : context_(context),
      layout_(context, bindings, pushConstantBytes),
      pipeline_(createComputePipeline(context.device(), spirv, layout_.pipelineLayout())) {}

ComputeKernel::~ComputeKernel() { vkDestroyPipeline(context_.device(), pipeline_, nullptr); }

void ComputeKernel::compileNow(const void* idlePushConstants) const {
  context_.submitAndWait(
      [&](VkCommandBuffer commands) { recordDispatch(commands, idlePushConstants, 1); });
}

void ComputeKernel::recordDispatch(VkCommandBuffer commands, const void* pushConstants,
                                   uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) const {
  layout_.recordBind(commands, pipeline_, pushConstants);
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
