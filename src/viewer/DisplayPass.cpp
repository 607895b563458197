#include "viewer/DisplayPass.hpp"

#include <algorithm>
#include <cmath>

#include "display_types.h"
#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Arithmetic.hpp"
#include "util/Error.hpp"

namespace rt::viewer {
namespace {

constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;

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

void recordBufferBarrier(VkCommandBuffer commands, VkBuffer buffer, VkAccessFlags srcAccess,
                         VkAccessFlags dstAccess, VkPipelineStageFlags srcStage,
                         VkPipelineStageFlags dstStage) {
  VkBufferMemoryBarrier barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
  barrier.srcAccessMask = srcAccess;
  barrier.dstAccessMask = dstAccess;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.buffer = buffer;
  barrier.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(commands, srcStage, dstStage, 0, 0, nullptr, 1, &barrier, 0, nullptr);
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
    : context_(context),
      compiler_(compiler),
      layout_(context,
              {{RT_DISPLAY_BINDING_ACCUMULATION, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
               {RT_DISPLAY_BINDING_PIXELS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
              sizeof(gpu::GpuDisplayParams)) {
  checkFormatSupport();
  pipeline_ = createPipeline();
}

DisplayPass::~DisplayPass() {
  VkDevice device = context_.device();
  vkDeviceWaitIdle(device);
  releaseRetired();
  destroyTargets();
  if (pipeline_) vkDestroyPipeline(device, pipeline_, nullptr);
}

void DisplayPass::checkFormatSupport() const {
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(context_.physicalDevice(), kDisplayFormat, &properties);
  VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_TRANSFER_DST_BIT |
                                VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  if ((properties.optimalTilingFeatures & needed) != needed) {
    throw Error("Vulkan: this device cannot use RGBA8 images as blit sources");
  }
}

VkPipeline DisplayPass::createPipeline() const {
  std::vector<uint32_t> spirv = compiler_.compile("display.comp", {});
  return createComputePipeline(context_.device(), spirv, layout_.pipelineLayout());
}

void DisplayPass::reloadShader() {
  VkPipeline fresh = createPipeline();  // throws, leaving pipeline_ as it was
  retired_.push_back(pipeline_);
  pipeline_ = fresh;
  allRowsStale_ = true;
}

void DisplayPass::releaseRetired() {
  for (VkPipeline pipeline : retired_) vkDestroyPipeline(context_.device(), pipeline, nullptr);
  retired_.clear();
}

void DisplayPass::createTargets(uint32_t width, uint32_t height) {
  VkDevice device = context_.device();
  pixels_ = std::make_unique<Buffer>(context_, VkDeviceSize(width) * height * sizeof(uint32_t),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  pixels_->fillZero();  // black until the first samples arrive

  VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  imageInfo.imageType = VK_IMAGE_TYPE_2D;
  imageInfo.format = kDisplayFormat;
  imageInfo.extent = {width, height, 1};
  imageInfo.mipLevels = 1;
  imageInfo.arrayLayers = 1;
  imageInfo.samples = VK_SAMPLE_COUNT_1_BIT;
  imageInfo.tiling = VK_IMAGE_TILING_OPTIMAL;
  imageInfo.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
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
  size_ = {width, height};

  // Between frames the image waits in TRANSFER_SRC_OPTIMAL for the blit.
  context_.submitAndWait([&](VkCommandBuffer commands) {
    recordImageBarrier(
        commands,
        imageBarrier(image_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                     VK_ACCESS_TRANSFER_WRITE_BIT),
        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    VkClearColorValue black{};
    black.float32[3] = 1.0f;
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &range);
    recordImageBarrier(commands,
                       imageBarrier(image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT),
                       VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
  });
}

void DisplayPass::destroyTargets() {
  VkDevice device = context_.device();
  if (image_) vkDestroyImage(device, image_, nullptr);
  if (memory_) vkFreeMemory(device, memory_, nullptr);
  image_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  pixels_.reset();
  size_ = glm::uvec2(0);
}

void DisplayPass::setSource(const Buffer& accumulation, uint32_t width, uint32_t height) {
  allRowsStale_ = true;
  if (size_ != glm::uvec2(width, height)) {
    destroyTargets();
    createTargets(width, height);
  }
  layout_.bind(RT_DISPLAY_BINDING_ACCUMULATION, accumulation);
  layout_.bind(RT_DISPLAY_BINDING_PIXELS, *pixels_);
}

void DisplayPass::recordToneMap(VkCommandBuffer commands, const ToneMapping& mapping,
                                uint32_t firstRow, uint32_t rows) {
  if (allRowsStale_ || mapping.exposure != mappedExposure_ || mapping.curve != mappedCurve_) {
    firstRow = 0;
    rows = size_.y;
    allRowsStale_ = false;
    mappedExposure_ = mapping.exposure;
    mappedCurve_ = mapping.curve;
  }
  rows = std::min(rows, size_.y - std::min(firstRow, size_.y));
  if (rows == 0) return;
  // The previous frame's copy read the pixels; this pass updates them.
  recordBufferBarrier(commands, pixels_->handle(), VK_ACCESS_TRANSFER_READ_BIT,
                      VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  gpu::GpuDisplayParams params{};
  params.size = size_;
  params.exposure = mapping.exposure;
  params.firstRow = firstRow;
  params.truncate = mapping.quantization == Quantization::Truncate ? 1u : 0u;
  params.srgbEncode = mapping.srgbEncode ? 1u : 0u;
  params.toneCurve = static_cast<uint32_t>(mapping.curve);
  layout_.recordBind(commands, pipeline_, &params);
  vkCmdDispatch(commands, divideRoundUp(size_.x, RT_DISPLAY_WORKGROUP_SIZE),
                divideRoundUp(rows, RT_DISPLAY_WORKGROUP_SIZE), 1);

  // Pixels into the image, which the previous frame's blit read.
  recordBufferBarrier(commands, pixels_->handle(), VK_ACCESS_SHADER_WRITE_BIT,
                      VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT);
  recordImageBarrier(commands,
                     imageBarrier(image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                  VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_ACCESS_TRANSFER_READ_BIT,
                                  VK_ACCESS_TRANSFER_WRITE_BIT),
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
  VkBufferImageCopy region{};
  region.bufferOffset = VkDeviceSize(firstRow) * size_.x * sizeof(uint32_t);
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageOffset = {0, static_cast<int32_t>(firstRow), 0};
  region.imageExtent = {size_.x, rows, 1};
  vkCmdCopyBufferToImage(commands, pixels_->handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         1, &region);
  recordImageBarrier(commands,
                     imageBarrier(image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                  VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT),
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
}

void DisplayPass::recordBlit(VkCommandBuffer commands, VkImage target,
                             VkExtent2D targetExtent) const {
  // The acquire semaphore is waited for at the transfer stage; the old
  // contents of the swapchain image do not matter.
  recordImageBarrier(
      commands,
      imageBarrier(target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
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
    vkCmdClearColorImage(commands, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &range);
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
    vkCmdBlitImage(commands, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region,
                   sameSize ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
  }
  recordImageBarrier(
      commands,
      imageBarrier(target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT),
      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT);
}

}  // namespace rt::viewer
