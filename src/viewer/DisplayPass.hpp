// Shows the accumulation buffer in the window. A compute pass
// (shaders/display.comp) tone maps it into 8-bit RGBA pixels (a storage
// buffer: on lavapipe much cheaper to write than a storage image), which are
// copied into an RGBA8 image of the render's size; the image is then blitted
// into the swapchain image, scaled to fit and centred (1:1, exact, when the
// window and the render have the same size).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "gpu/KernelLayout.hpp"
#include "io/Image.hpp"

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
  // recreates (and clears) the pixels and the image when the size changes.
  // Only while no frame is in flight.
  void setSource(const Buffer& accumulation, uint32_t width, uint32_t height);

  glm::uvec2 imageSize() const { return size_; }

  // Records the tone-mapping dispatch for rows [firstRow, firstRow + rows)
  // (after the render dispatches) and the copy of those pixels into the
  // display image. Rows that got no new samples need no update, unless the
  // tone mapping itself changed (a new exposure, a reloaded shader, a new
  // source): then every row is mapped again.
  // `mapping` gives the exposure, the curve, the sRGB encoding and the quantization.
  void recordToneMap(VkCommandBuffer commands, const ToneMapping& mapping, uint32_t firstRow,
                     uint32_t rows);
  // Records the blit into a swapchain image, which ends in
  // COLOR_ATTACHMENT_OPTIMAL for the overlay pass.
  void recordBlit(VkCommandBuffer commands, VkImage target, VkExtent2D targetExtent) const;

 private:
  VkPipeline createPipeline() const;
  void createTargets(uint32_t width, uint32_t height);
  void destroyTargets();
  void checkFormatSupport() const;

  VulkanContext& context_;
  const ShaderCompiler& compiler_;
  KernelLayout layout_;  // the accumulation and the pixels; GpuDisplayParams
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::vector<VkPipeline> retired_;
  std::unique_ptr<Buffer> pixels_;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  glm::uvec2 size_{0};
  bool allRowsStale_ = true;     // every row is mapped on the next recordToneMap
  float mappedExposure_ = 0.0f;  // the mapping the pixels were made with
  ToneCurve mappedCurve_ = ToneCurve::Clamp;
};

}  // namespace rt::viewer
