// Reads back the image that is presented (overlay included), for
// --screenshot and camera-path screenshots: the copy is recorded in the frame
// itself, after the overlay pass and before the present.
#pragma once

#include <vulkan/vulkan.h>

#include <filesystem>
#include <memory>
#include <vector>

namespace rt {
class Buffer;
class VulkanContext;
}  // namespace rt

namespace rt::viewer {

class SwapchainReadback {
 public:
  explicit SwapchainReadback(VulkanContext& context);
  ~SwapchainReadback();

  // Records the copy of `image` (in PRESENT_SRC_KHR layout, left so).
  void record(VkCommandBuffer commands, VkImage image, VkExtent2D extent, VkFormat format);
  // Once the frame's fence signalled: writes the copy as PNG to each path.
  void write(const std::vector<std::filesystem::path>& paths);

 private:
  VulkanContext& context_;
  std::unique_ptr<Buffer> buffer_;
  VkExtent2D extent_{};
  VkFormat format_ = VK_FORMAT_UNDEFINED;
};

}  // namespace rt::viewer
