// The window's swapchain, one view and framebuffer per image for the overlay
// render pass, and a "render finished" semaphore per image (a present may
// still wait on one after the frame fence signalled, so they are not shared).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace rt {
class VulkanContext;
}

namespace rt::viewer {

class Swapchain {
 public:
  // Picks the format and creates the overlay render pass, which depends only
  // on the format and so outlives recreations. Call recreate() before use.
  explicit Swapchain(VulkanContext& context);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // (Re)creates the swapchain for a framebuffer of the given size; waits for
  // the device to be idle first.
  void recreate(VkExtent2D framebufferSize);

  VkSwapchainKHR handle() const { return swapchain_; }
  VkFormat format() const { return format_.format; }
  VkExtent2D extent() const { return extent_; }
  VkRenderPass renderPass() const { return renderPass_; }
  uint32_t imageCount() const { return static_cast<uint32_t>(images_.size()); }
  uint32_t minImageCount() const { return minImageCount_; }
  VkImage image(uint32_t index) const { return images_[index]; }
  VkFramebuffer framebuffer(uint32_t index) const { return framebuffers_[index]; }
  VkSemaphore renderFinished(uint32_t index) const { return renderFinished_[index]; }
  // Whether images can be read back (screenshots).
  bool readable() const { return readable_; }

 private:
  void chooseFormat();
  void createRenderPass();
  void createSwapchain(VkExtent2D framebufferSize);
  void createPerImageObjects();
  void destroyPerImageObjects();

  VulkanContext& context_;
  VkSurfaceFormatKHR format_{};
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkExtent2D extent_{};
  uint32_t minImageCount_ = 2;
  bool readable_ = false;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  std::vector<VkSemaphore> renderFinished_;
};

}  // namespace rt::viewer
