#include "viewer/Swapchain.hpp"

#include <algorithm>
#include <cstdio>

#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"

namespace rt::viewer {
namespace {

// The display image is tone mapped to 8-bit values already; a UNORM target
// shows them as they are (an sRGB one would gamma-encode them a second time).
constexpr VkFormat kPreferredFormats[] = {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM,
                                          VK_FORMAT_A8B8G8R8_UNORM_PACK32};

std::vector<VkSurfaceFormatKHR> surfaceFormats(const VulkanContext& context) {
  uint32_t count = 0;
  vkCheck(vkGetPhysicalDeviceSurfaceFormatsKHR(context.physicalDevice(), context.surface(), &count,
                                               nullptr),
          "vkGetPhysicalDeviceSurfaceFormatsKHR");
  std::vector<VkSurfaceFormatKHR> formats(count);
  vkCheck(vkGetPhysicalDeviceSurfaceFormatsKHR(context.physicalDevice(), context.surface(), &count,
                                               formats.data()),
          "vkGetPhysicalDeviceSurfaceFormatsKHR");
  return formats;
}

// The render reaches the window by vkCmdBlitImage.
bool canBlitInto(const VulkanContext& context, VkFormat format) {
  VkFormatProperties properties{};
  vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), format, &properties);
  return (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) != 0;
}

}  // namespace

Swapchain::Swapchain(VulkanContext& context) : context_(context) {
  chooseFormat();
  createRenderPass();
}

Swapchain::~Swapchain() {
  VkDevice device = context_.device();
  vkDeviceWaitIdle(device);
  destroyPerImageObjects();
  if (swapchain_) vkDestroySwapchainKHR(device, swapchain_, nullptr);
  if (renderPass_) vkDestroyRenderPass(device, renderPass_, nullptr);
}

void Swapchain::chooseFormat() {
  std::vector<VkSurfaceFormatKHR> formats = surfaceFormats(context_);
  if (formats.empty()) throw Error("Vulkan: the window surface offers no formats");
  for (VkFormat wanted : kPreferredFormats) {
    for (const VkSurfaceFormatKHR& offered : formats) {
      if (offered.format == wanted && offered.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR &&
          canBlitInto(context_, wanted)) {
        format_ = offered;
        return;
      }
    }
  }
  format_ = formats.front();
  if (!canBlitInto(context_, format_.format)) {
    throw Error("Vulkan: no window surface format can be a blit destination");
  }
  std::fprintf(stderr,
               "warning: the window offers no 8-bit UNORM format; colours may differ from the "
               "PNG output\n");
}

void Swapchain::createRenderPass() {
  // The image already holds the blitted render when the pass begins
  // (COLOR_ATTACHMENT_OPTIMAL, loaded); the overlay is drawn on top and the
  // pass leaves the image ready to present.
  VkAttachmentDescription color{};
  color.format = format_.format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;

  VkAttachmentReference colorReference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colorReference;

  // The blit (a transfer) must have landed before the overlay blends over it.
  VkSubpassDependency dependency{};
  dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
  dependency.dstSubpass = 0;
  dependency.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependency.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  dependency.dstAccessMask =
      VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;

  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 1;
  info.pAttachments = &color;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 1;
  info.pDependencies = &dependency;
  vkCheck(vkCreateRenderPass(context_.device(), &info, nullptr, &renderPass_),
          "vkCreateRenderPass");
}

void Swapchain::recreate(VkExtent2D framebufferSize) {
  vkDeviceWaitIdle(context_.device());
  destroyPerImageObjects();
  createSwapchain(framebufferSize);
  createPerImageObjects();
}

void Swapchain::createSwapchain(VkExtent2D framebufferSize) {
  VkSurfaceCapabilitiesKHR caps{};
  vkCheck(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physicalDevice(), context_.surface(),
                                                    &caps),
          "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  // 0xFFFFFFFF means the surface takes its size from the swapchain.
  if (caps.currentExtent.width != UINT32_MAX) {
    extent_ = caps.currentExtent;
  } else {
    extent_.width =
        std::clamp(framebufferSize.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height =
        std::clamp(framebufferSize.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  minImageCount_ = std::max(caps.minImageCount + 1, 2u);
  if (caps.maxImageCount > 0) minImageCount_ = std::min(minImageCount_, caps.maxImageCount);

  // Transfer destination: the render is blitted in. Transfer source: the
  // presented image can be read back for --screenshot.
  VkImageUsageFlags required =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if ((caps.supportedUsageFlags & required) != required) {
    throw Error("Vulkan: the window surface cannot be a transfer destination");
  }
  readable_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;

  VkSwapchainKHR old = swapchain_;
  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = context_.surface();
  info.minImageCount = minImageCount_;
  info.imageFormat = format_.format;
  info.imageColorSpace = format_.colorSpace;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  info.imageUsage = required | (readable_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always available; frames are slow anyway
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  vkCheck(vkCreateSwapchainKHR(context_.device(), &info, nullptr, &swapchain_),
          "vkCreateSwapchainKHR");
  if (old) vkDestroySwapchainKHR(context_.device(), old, nullptr);

  uint32_t count = 0;
  vkCheck(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, nullptr),
          "vkGetSwapchainImagesKHR");
  images_.resize(count);
  vkCheck(vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, images_.data()),
          "vkGetSwapchainImagesKHR");
}

void Swapchain::createPerImageObjects() {
  VkDevice device = context_.device();
  for (VkImage image : images_) {
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format_.format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    vkCheck(vkCreateImageView(device, &viewInfo, nullptr, &view), "vkCreateImageView");
    views_.push_back(view);

    VkFramebufferCreateInfo framebufferInfo{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    framebufferInfo.renderPass = renderPass_;
    framebufferInfo.attachmentCount = 1;
    framebufferInfo.pAttachments = &view;
    framebufferInfo.width = extent_.width;
    framebufferInfo.height = extent_.height;
    framebufferInfo.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    vkCheck(vkCreateFramebuffer(device, &framebufferInfo, nullptr, &framebuffer),
            "vkCreateFramebuffer");
    framebuffers_.push_back(framebuffer);

    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    vkCheck(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &semaphore), "vkCreateSemaphore");
    renderFinished_.push_back(semaphore);
  }
}

void Swapchain::destroyPerImageObjects() {
  VkDevice device = context_.device();
  for (VkSemaphore semaphore : renderFinished_) vkDestroySemaphore(device, semaphore, nullptr);
  for (VkFramebuffer framebuffer : framebuffers_)
    vkDestroyFramebuffer(device, framebuffer, nullptr);
  for (VkImageView view : views_) vkDestroyImageView(device, view, nullptr);
  renderFinished_.clear();
  framebuffers_.clear();
  views_.clear();
}

}  // namespace rt::viewer
