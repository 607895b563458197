// Instance, device and queue for compute work. Picks a discrete or
// integrated GPU when one is present, otherwise a CPU implementation
// (lavapipe); needs no display.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rt {

// Throws rt::Error naming the call when a Vulkan function fails.
void vkCheck(VkResult result, const char* call);

struct DeviceDescription {
  uint32_t index = 0;
  std::string name;
  std::string typeName;  // "discrete GPU", "integrated GPU", "CPU", ...
  uint32_t apiVersion = 0;
  std::string driver;       // driver name and version, e.g. "llvmpipe, Mesa 25.0.7 (LLVM 15.0.6)"
  bool rayQueries = false;  // VK_KHR_ray_query with acceleration structures

  // "<name> (driver <driver>)", for summaries and benchmark tables.
  std::string summary() const { return name + " (driver " + driver + ")"; }
};

// Ray queries through the driver's acceleration structures (--accel
// hardware): off, on where the device has them, or required (an Error when not).
enum class RayQueries { Off, IfSupported, Required };

struct ContextOptions {
  bool validation = false;  // enable VK_LAYER_KHRONOS_validation
  RayQueries rayQueries = RayQueries::Off;
  std::optional<uint32_t> deviceIndex;          // as listed by listDevices(); default: best
  std::vector<const char*> instanceExtensions;  // e.g. for a window surface
  std::vector<const char*> deviceExtensions;
  // For a window: creates the surface once the instance exists. The context
  // then picks a queue family that can compute, draw and present to it, and
  // destroys the surface with itself.
  std::function<VkSurfaceKHR(VkInstance)> createSurface;
};

class VulkanContext {
 public:
  explicit VulkanContext(const ContextOptions& options = {});
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  static std::vector<DeviceDescription> listDevices();

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const DeviceDescription& description() const { return description_; }
  const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
  bool rayQueriesEnabled() const { return rayQueries_; }
  // Compute kernels may use subgroup arithmetic (GL_KHR_shader_subgroup_arithmetic).
  bool subgroupArithmetic() const { return subgroupArithmetic_; }
  // Compute kernels may elect a lane and broadcast from it (GL_KHR_shader_subgroup_ballot).
  bool subgroupBallot() const { return subgroupBallot_; }
  // Compute kernels may ask whether any lane of the subgroup holds a
  // condition (GL_KHR_shader_subgroup_vote).
  bool subgroupVote() const { return subgroupVote_; }
  // Invocations in a subgroup (lavapipe: its vector width in 32-bit lanes).
  uint32_t subgroupSize() const { return subgroupSize_; }
  // The device is a CPU (lavapipe, SwiftShader): its worker threads each take
  // one contiguous share of a dispatch's workgroups.
  bool isCpu() const { return properties_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  // The Mesa major version of lavapipe (llvmpipe); nullopt for other drivers.
  std::optional<uint32_t> lavapipeMesaMajor() const { return lavapipeMesaMajor_; }
  VkSurfaceKHR surface() const { return surface_; }

  // Validation warnings and errors reported so far (0 when validation is off).
  uint32_t validationMessageCount() const { return validationMessages_; }

  // Index of a memory type allowed by typeBits with all `required` flags,
  // preferring one that also has `preferred`. Throws when none exists.
  uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                          VkMemoryPropertyFlags preferred = 0) const;
  VkMemoryPropertyFlags memoryTypeFlags(uint32_t typeIndex) const;

  // Records commands with `record`, submits them and waits for completion.
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record);

 private:
  void destroy();
  void createInstance(const ContextOptions& options);
  void pickPhysicalDevice(const ContextOptions& options);
  void createDevice(const ContextOptions& options);
  static VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(
      VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
      const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memoryProperties_{};
  DeviceDescription description_;
  VkDevice device_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool commandPool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  bool rayQueries_ = false;
  bool subgroupArithmetic_ = false;
  bool subgroupBallot_ = false;
  bool subgroupVote_ = false;
  uint32_t subgroupSize_ = 1;
  std::optional<uint32_t> lavapipeMesaMajor_;
  uint32_t validationMessages_ = 0;
};

}  // namespace rt
