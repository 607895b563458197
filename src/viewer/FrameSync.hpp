// The Vulkan objects of the one frame in flight: its command buffer, the
// fence that says the GPU finished it and the semaphore that says its
// swapchain image was acquired.
#pragma once

#include <vulkan/vulkan.h>

namespace rt {
class VulkanContext;
}

namespace rt::viewer {

class FrameSync {
 public:
  explicit FrameSync(VulkanContext& context);
  ~FrameSync();
  FrameSync(const FrameSync&) = delete;
  FrameSync& operator=(const FrameSync&) = delete;

  // Waits until the frame in flight is done; false when none was in flight.
  bool wait();
  VkSemaphore imageAcquired() const { return imageAcquired_; }
  // The command buffer, reset and begun for a new frame.
  VkCommandBuffer begin();
  // Ends the command buffer and submits it, waiting for the acquired image
  // and signalling `renderFinished`; the frame is then in flight.
  void submit(VkSemaphore renderFinished);

 private:
  VulkanContext& context_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkFence done_ = VK_NULL_HANDLE;
  VkSemaphore imageAcquired_ = VK_NULL_HANDLE;
  bool inFlight_ = false;
};

}  // namespace rt::viewer
