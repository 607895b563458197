#include "viewer/DisplayPass.hpp"

#include <algorithm>
#include <cmath>

#include "display_types.h"
#include "gpu/Buffer.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"

namespace rt::viewer {
namespace {

constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;

uint32_t divideRoundUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

VkImageMemoryBarrier imageBarrier(VkImage image, VkImageLayout oldLayout, VkImageLayout newLayout,
                                  VkAccessFlags srcAccess, VkAccessFlags dstAccess) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = srcAccess;
  barrier.dstAccessMask = dstAccess;
  barrier.oldLayout = oldLayout;
  barrier.newLayout = newLayout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  return barrier;
}

void recordImageBarrier(VkCommandBuffer commands, const VkImageMemoryBarrier& barrier,
                        VkPipelineStageFlags srcStage, VkPipelineStageFlags dstStage) {
  vkCmdPipelineBarrier(commands, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

}  // namespace

FitRect fitInto(glm::uvec2 image, VkExtent2D target) {
  if (image.x == 0 || image.y == 0) return {};
  double scale = std::min(double(target.width) / image.x, double(target.height) / image.y);
  glm::ivec2 size{static_cast<int>(std::lround(image.x * scale)),
                  static_cast<int>(std::lround(image.y * scale))};
  glm::ivec2 offset{(static_cast<int>(target.width) - size.x) / 2,
                    (static_cast<int>(target.height) - size.y) / 2};
  return {offset, size};
}

DisplayPass::DisplayPass(VulkanContext& context, const ShaderCompiler& compiler)
    : context_(context), compiler_(compiler) {
  checkFormatSupport();
  createLayouts();
  pipeline_ = createPipeline();
}

DisplayPass::~DisplayPass() {
  VkDevice device = context_.device();
  vkDeviceWaitIdle(device);
  releaseRetired();
  destroyImage();
  if (pipeline_) vkDestroyPipeline(device, pipeline_, nullptr);
  if (pool_) vkDestroyDescriptorPool(device, pool_, nullptr);
  if (pipelineLayout_) vkDestroyPipelineLayout(device, pipelineLayout_, nullptr);
  if (setLayout_) vkDestroyDescriptorSetLayout(device, setLayout_, nullptr);
}

void DisplayPass::checkFormatSupport() const {
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(context_.physicalDevice(), kDisplayFormat, &properties);
  VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT |
                                VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  if ((properties.optimalTilingFeatures & needed) != needed) {
    throw Error("Vulkan: this device cannot use RGBA8 storage images as blit sources");
  }
}

void DisplayPass::createLayouts() {
  VkDevice device = context_.device();
  VkDescriptorSetLayoutBinding bindings[] = {
      {RT_DISPLAY_BINDING_ACCUMULATION, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
       VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {RT_DISPLAY_BINDING_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr}};
  VkDescriptorSetLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  layoutInfo.bindingCount = 2;
  layoutInfo.pBindings = bindings;
  vkCheck(vkCreateDescriptorSetLayout(device, &layoutInfo, nullptr, &setLayout_),
          "vkCreateDescriptorSetLayout");

  VkPushConstantRange pushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(gpu::GpuDisplayParams)};
  VkPipelineLayoutCreateInfo pipelineLayoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pipelineLayoutInfo.setLayoutCount = 1;
  pipelineLayoutInfo.pSetLayouts = &setLayout_;
  pipelineLayoutInfo.pushConstantRangeCount = 1;
  pipelineLayoutInfo.pPushConstantRanges = &pushRange;
  vkCheck(vkCreatePipelineLayout(device, &pipelineLayoutInfo, nullptr, &pipelineLayout_),
          "vkCreatePipelineLayout");

  VkDescriptorPoolSize poolSizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
                                      {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 2;
  poolInfo.pPoolSizes = poolSizes;
  vkCheck(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool_), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  setInfo.descriptorPool = pool_;
  setInfo.descriptorSetCount = 1;
  setInfo.pSetLayouts = &setLayout_;
  vkCheck(vkAllocateDescriptorSets(device, &setInfo, &set_), "vkAllocateDescriptorSets");
}

VkPipeline DisplayPass::createPipeline() const {
  VkDevice device = context_.device();
  std::vector<uint32_t> spirv = compiler_.compile("display.comp", {});
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
  pipelineInfo.layout = pipelineLayout_;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkResult result =
      vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline);
  // The module is only needed while the pipeline is created.
  vkDestroyShaderModule(device, module, nullptr);
  vkCheck(result, "vkCreateComputePipelines");
  return pipeline;
}

void DisplayPass::reloadShader() {
  VkPipeline fresh = createPipeline();  // throws, leaving pipeline_ as it was
  retired_.push_back(pipeline_);
  pipeline_ = fresh;
}

void DisplayPass::releaseRetired() {
  for (VkPipeline pipeline : retired_) vkDestroyPipeline(context_.device(), pipeline, nullptr);
  retired_.clear();
}

void DisplayPass::createImage(uint32_t width, uint32_t height) {
  VkDevice device = context_.device();
  VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  imageInfo.imageType = VK_IMAGE_TYPE_2D;
  imageInfo.format = kDisplayFormat;
  imageInfo.extent = {width, height, 1};
  imageInfo.mipLevels = 1;
  imageInfo.arrayLayers = 1;
  imageInfo.samples = VK_SAMPLE_COUNT_1_BIT;
  imageInfo.tiling = VK_IMAGE_TILING_OPTIMAL;
  imageInfo.usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  imageInfo.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  imageInfo.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  vkCheck(vkCreateImage(device, &imageInfo, nullptr, &image_), "vkCreateImage");

  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(device, image_, &requirements);
  VkMemoryAllocateInfo allocInfo{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocInfo.allocationSize = requirements.size;
  allocInfo.memoryTypeIndex =
      context_.findMemoryType(requirements.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  vkCheck(vkAllocateMemory(device, &allocInfo, nullptr, &memory_), "vkAllocateMemory");
  vkCheck(vkBindImageMemory(device, image_, memory_, 0), "vkBindImageMemory");

  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = image_;
  viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = kDisplayFormat;
  viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCheck(vkCreateImageView(device, &viewInfo, nullptr, &view_), "vkCreateImageView");
  size_ = {width, height};

  // The image lives in GENERAL (storage writes and blit reads) and starts
  // black: pixels without samples keep their old value (see display.comp).
  context_.submitAndWait([&](VkCommandBuffer commands) {
    recordImageBarrier(commands,
                       imageBarrier(image_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0,
                                    VK_ACCESS_TRANSFER_WRITE_BIT),
                       VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    VkClearColorValue black{};
    black.float32[3] = 1.0f;
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(commands, image_, VK_IMAGE_LAYOUT_GENERAL, &black, 1, &range);
    recordImageBarrier(commands,
                       imageBarrier(image_, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                                    VK_ACCESS_TRANSFER_WRITE_BIT,
                                    VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT),
                       VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT);
  });
}

void DisplayPass::destroyImage() {
  VkDevice device = context_.device();
  if (view_) vkDestroyImageView(device, view_, nullptr);
  if (image_) vkDestroyImage(device, image_, nullptr);
  if (memory_) vkFreeMemory(device, memory_, nullptr);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  size_ = glm::uvec2(0);
}

void DisplayPass::setSource(const Buffer& accumulation, uint32_t width, uint32_t height) {
  if (size_ != glm::uvec2(width, height)) {
    destroyImage();
    createImage(width, height);
  }
  VkDescriptorBufferInfo bufferInfo{accumulation.handle(), 0, VK_WHOLE_SIZE};
  VkDescriptorImageInfo imageInfo{VK_NULL_HANDLE, view_, VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                    {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  writes[0].dstSet = set_;
  writes[0].dstBinding = RT_DISPLAY_BINDING_ACCUMULATION;
  writes[0].descriptorCount = 1;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[0].pBufferInfo = &bufferInfo;
  writes[1].dstSet = set_;
  writes[1].dstBinding = RT_DISPLAY_BINDING_IMAGE;
  writes[1].descriptorCount = 1;
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  writes[1].pImageInfo = &imageInfo;
  vkUpdateDescriptorSets(context_.device(), 2, writes, 0, nullptr);
}

void DisplayPass::recordToneMap(VkCommandBuffer commands, float exposure) const {
  // The previous frame's blit read the image; this pass overwrites it.
  recordImageBarrier(commands,
                     imageBarrier(image_, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                                  VK_ACCESS_TRANSFER_READ_BIT, VK_ACCESS_SHADER_WRITE_BIT),
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  gpu::GpuDisplayParams params{size_, exposure, 0};
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &set_,
                          0, nullptr);
  vkCmdPushConstants(commands, pipelineLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(params),
                     &params);
  vkCmdDispatch(commands, divideRoundUp(size_.x, RT_DISPLAY_WORKGROUP_SIZE),
                divideRoundUp(size_.y, RT_DISPLAY_WORKGROUP_SIZE), 1);
  recordImageBarrier(commands,
                     imageBarrier(image_, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                                  VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT),
                     VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
}

void DisplayPass::recordBlit(VkCommandBuffer commands, VkImage target,
                             VkExtent2D targetExtent) const {
  // The acquire semaphore is waited for at the transfer stage; the old
  // contents of the swapchain image do not matter.
  recordImageBarrier(commands,
                     imageBarrier(target, VK_IMAGE_LAYOUT_UNDEFINED,
                                  VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                                  VK_ACCESS_TRANSFER_WRITE_BIT),
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
  FitRect fit = fitInto(size_, targetExtent);
  bool coversTarget = fit.offset == glm::ivec2(0) &&
                      fit.size == glm::ivec2(targetExtent.width, targetExtent.height);
  if (!coversTarget) {
    // Black bars where the image does not reach (window aspect differs).
    VkClearColorValue black{};
    black.float32[3] = 1.0f;
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(commands, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1,
                         &range);
    recordImageBarrier(commands,
                       imageBarrier(target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_WRITE_BIT),
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
  }
  if (fit.size.x > 0 && fit.size.y > 0) {
    VkImageBlit region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {static_cast<int32_t>(size_.x), static_cast<int32_t>(size_.y), 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstOffsets[0] = {fit.offset.x, fit.offset.y, 0};
    region.dstOffsets[1] = {fit.offset.x + fit.size.x, fit.offset.y + fit.size.y, 1};
    // 1:1 copies stay exact; scaled ones are filtered.
    bool sameSize = fit.size == glm::ivec2(size_);
    vkCmdBlitImage(commands, image_, VK_IMAGE_LAYOUT_GENERAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region,
                   sameSize ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
  }
  recordImageBarrier(commands,
                     imageBarrier(target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                  VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                  VK_ACCESS_TRANSFER_WRITE_BIT,
                                  VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
                                      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT),
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT);
}

}  // namespace rt::viewer
