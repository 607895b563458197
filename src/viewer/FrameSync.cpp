#include "viewer/FrameSync.hpp"

#include <cstdint>

#include "gpu/VulkanContext.hpp"

namespace rt::viewer {
namespace {
constexpr uint64_t kFenceTimeoutNs = 600ull * 1000 * 1000 * 1000;
}  // namespace

FrameSync::FrameSync(VulkanContext& context) : context_(context) {
  VkDevice device = context_.device();
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = context_.queueFamily();
  vkCheck(vkCreateCommandPool(device, &poolInfo, nullptr, &pool_), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool_;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  vkCheck(vkAllocateCommandBuffers(device, &allocInfo, &commands_), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  vkCheck(vkCreateFence(device, &fenceInfo, nullptr, &done_), "vkCreateFence");
  VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  vkCheck(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &imageAcquired_), "vkCreateSemaphore");
}

FrameSync::~FrameSync() {
  VkDevice device = context_.device();
  vkDeviceWaitIdle(device);
  vkDestroySemaphore(device, imageAcquired_, nullptr);
  vkDestroyFence(device, done_, nullptr);
  vkDestroyCommandPool(device, pool_, nullptr);
}

bool FrameSync::wait() {
  if (!inFlight_) return false;
  vkCheck(vkWaitForFences(context_.device(), 1, &done_, VK_TRUE, kFenceTimeoutNs),
          "vkWaitForFences");
  inFlight_ = false;
  return true;
}

VkCommandBuffer FrameSync::begin() {
  vkCheck(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkCheck(vkBeginCommandBuffer(commands_, &begin), "vkBeginCommandBuffer");
  return commands_;
}

void FrameSync::submit(VkSemaphore renderFinished) {
  vkCheck(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
  // The first use of the swapchain image is the blit's layout transition.
  VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &imageAcquired_;
  submit.pWaitDstStageMask = &waitStage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands_;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &renderFinished;
  vkCheck(vkResetFences(context_.device(), 1, &done_), "vkResetFences");
  vkCheck(vkQueueSubmit(context_.queue(), 1, &submit, done_), "vkQueueSubmit");
  inFlight_ = true;
}

}  // namespace rt::viewer
