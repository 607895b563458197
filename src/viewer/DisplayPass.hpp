// Shows the accumulation buffer in the window. A compute pass
// (shaders/display.comp) tone maps it into an RGBA8 storage image of the
// render's size; the image is then blitted into the swapchain image, scaled
// to fit and centred (1:1 when the window and the render have the same size).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace rt {
class Buffer;
class ShaderCompiler;
class VulkanContext;
}  // namespace rt

namespace rt::viewer {

// Where an image of `image` pixels lands when fitted into `target` pixels,
// keeping its aspect ratio: offset and size in target pixels.
struct FitRect {
  glm::ivec2 offset{0};
  glm::ivec2 size{0};
};
FitRect fitInto(glm::uvec2 image, VkExtent2D target);

class DisplayPass {
 public:
  DisplayPass(VulkanContext& context, const ShaderCompiler& compiler);
  ~DisplayPass();
  DisplayPass(const DisplayPass&) = delete;
  DisplayPass& operator=(const DisplayPass&) = delete;

  // Recompiles display.comp. Throws on errors and keeps the current pipeline;
  // the replaced one lives until releaseRetired() (no frame may use it then).
  void reloadShader();
  void releaseRetired();

  // Points the pass at a new accumulation buffer of width x height pixels;
  // recreates (and clears) the display image when the size changes. Only
  // while no frame is in flight.
  void setSource(const Buffer& accumulation, uint32_t width, uint32_t height);

  glm::uvec2 imageSize() const { return size_; }

  // Records the tone-mapping dispatch (after the render dispatches).
  void recordToneMap(VkCommandBuffer commands, float exposure) const;
  // Records the blit into a swapchain image, which ends in
  // COLOR_ATTACHMENT_OPTIMAL for the overlay pass.
  void recordBlit(VkCommandBuffer commands, VkImage target, VkExtent2D targetExtent) const;

 private:
  void createLayouts();
  VkPipeline createPipeline() const;
  void createImage(uint32_t width, uint32_t height);
  void destroyImage();
  void checkFormatSupport() const;

  VulkanContext& context_;
  const ShaderCompiler& compiler_;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::vector<VkPipeline> retired_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  glm::uvec2 size_{0};
};

}  // namespace rt::viewer
