#include "viewer/SwapchainReadback.hpp"

#include <fmt/format.h>

#include "gpu/Buffer.hpp"
#include "gpu/VulkanContext.hpp"
#include "io/Image.hpp"
#include "util/Error.hpp"

namespace rt::viewer {
namespace {

// Byte position of red, green and blue in a pixel of the swapchain format.
struct ChannelOrder {
  int red;
  int green;
  int blue;
};

ChannelOrder channelOrder(VkFormat format) {
  switch (format) {
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB: return {2, 1, 0};
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_A8B8G8R8_UNORM_PACK32:
    case VK_FORMAT_A8B8G8R8_SRGB_PACK32: return {0, 1, 2};
    default: throw Error(fmt::format("screenshot: unsupported swapchain format {}", int(format)));
  }
}

}  // namespace

SwapchainReadback::SwapchainReadback(VulkanContext& context) : context_(context) {}

SwapchainReadback::~SwapchainReadback() = default;

void SwapchainReadback::record(VkCommandBuffer commands, VkImage image, VkExtent2D extent,
                               VkFormat format) {
  VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
  if (!buffer_ || buffer_->size() != bytes) {
    buffer_ = std::make_unique<Buffer>(context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  }
  extent_ = extent;
  format_ = format;

  VkImageMemoryBarrier toSource{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  toSource.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  toSource.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  toSource.oldLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  toSource.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  toSource.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toSource.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toSource.image = image;
  toSource.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toSource);

  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyImageToBuffer(commands, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer_->handle(),
                         1, &region);

  // Back to the layout the present expects; the host reads the buffer after
  // the frame fence.
  VkImageMemoryBarrier toPresent = toSource;
  toPresent.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  toPresent.dstAccessMask = 0;
  toPresent.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  toPresent.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkBufferMemoryBarrier toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  toHost.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toHost.buffer = buffer_->handle();
  toHost.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                       nullptr, 1, &toHost, 1, &toPresent);
}

void SwapchainReadback::write(const std::vector<std::filesystem::path>& paths) {
  if (paths.empty() || !buffer_) return;
  std::vector<uint8_t> pixels(buffer_->size());
  buffer_->download(pixels.data(), pixels.size());
  ChannelOrder order = channelOrder(format_);
  // Through the float image writer so the file appears atomically; k / 255
  // quantises back to exactly k.
  ImageF image{extent_.width, extent_.height, {}};
  image.rgba.resize(pixels.size());
  for (size_t i = 0; i < pixels.size(); i += 4) {
    image.rgba[i + 0] = pixels[i + order.red] / 255.0f;
    image.rgba[i + 1] = pixels[i + order.green] / 255.0f;
    image.rgba[i + 2] = pixels[i + order.blue] / 255.0f;
    image.rgba[i + 3] = 1.0f;
  }
  ToneMapping identity{1.0f, ToneCurve::Clamp, false};
  for (const std::filesystem::path& path : paths) writeImage(path, image, identity);
}

}  // namespace rt::viewer
