#include "gpu/VulkanContext.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <vector>

#include "util/Error.hpp"

namespace rt {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint64_t kFenceTimeoutNs = 600ull * 1000 * 1000 * 1000;  // a hung device is an error

const char* resultName(VkResult result) {
  switch (result) {
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      return "VK_ERROR_INCOMPATIBLE_DRIVER (no Vulkan driver found)";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    default: return "VkResult error";
  }
}

const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

// Lower is better: real GPUs first, software rasterisers last.
int deviceTypeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

bool layerAvailable(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
    return std::strcmp(l.layerName, name) == 0;
  });
}

std::vector<VkPhysicalDevice> enumeratePhysicalDevices(VkInstance instance) {
  uint32_t count = 0;
  vkCheck(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  vkCheck(vkEnumeratePhysicalDevices(instance, &count, devices.data()),
          "vkEnumeratePhysicalDevices");
  return devices;
}

// A queue family that computes and, with a surface, also draws and presents.
std::optional<uint32_t> usableQueueFamily(VkPhysicalDevice device, VkSurfaceKHR surface) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (uint32_t i = 0; i < count; ++i) {
    if (!(families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
    if (surface) {
      VkBool32 presents = VK_FALSE;
      vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &presents);
      if (!presents || !(families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT)) continue;
    }
    return i;
  }
  return std::nullopt;
}

// The driver's identity (Vulkan 1.2 core); zeroed on older devices.
VkPhysicalDeviceDriverProperties driverProperties(VkPhysicalDevice device,
                                                  const VkPhysicalDeviceProperties& props) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  if (props.apiVersion < VK_API_VERSION_1_2) return driver;
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &driver;
  vkGetPhysicalDeviceProperties2(device, &props2);
  return driver;
}

// Driver name and version as the driver reports them (Vulkan 1.2 core); the
// version is what sets a CPU driver's speed (Mesa 22.3 vs 25: 2.4-4.3x).
std::string driverText(VkPhysicalDevice device, const VkPhysicalDeviceProperties& props) {
  if (props.apiVersion < VK_API_VERSION_1_2) return "unknown driver";
  const VkPhysicalDeviceDriverProperties driver = driverProperties(device, props);
  std::string info = driver.driverInfo;
  return info.empty() ? std::string(driver.driverName)
                      : fmt::format("{}, {}", driver.driverName, info);
}

// The major version in a Mesa driver's info, "Mesa 25.0.7-2~bpo12+1 (LLVM
// 15.0.6)": lavapipe reports 1 as its driverVersion, so only the text says.
std::optional<uint32_t> mesaMajorVersion(const std::string& info) {
  const std::string prefix = "Mesa ";
  const size_t at = info.find(prefix);
  if (at == std::string::npos) return std::nullopt;
  uint32_t major = 0;
  size_t digits = 0;
  for (size_t i = at + prefix.size(); i < info.size() && std::isdigit(uint8_t(info[i])); ++i) {
    major = major * 10 + uint32_t(info[i] - '0');
    ++digits;
  }
  if (digits == 0 || digits > 4) return std::nullopt;
  return major;
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

const char* const kRayQueryExtensions[] = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
                                           VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                           VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};

// The features ray queries need, as the device reports them.
struct RayQueryFeatures {
  VkPhysicalDeviceRayQueryFeaturesKHR rayQuery{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR structures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};

  explicit RayQueryFeatures(VkPhysicalDevice device) {
    structures.pNext = &rayQuery;
    vulkan12.pNext = &structures;
    features.pNext = &vulkan12;
    vkGetPhysicalDeviceFeatures2(device, &features);
  }
  RayQueryFeatures(const RayQueryFeatures&) = delete;
  RayQueryFeatures& operator=(const RayQueryFeatures&) = delete;

  bool complete() const {
    return rayQuery.rayQuery && structures.accelerationStructure && vulkan12.bufferDeviceAddress;
  }
};

bool supportsRayQueries(VkPhysicalDevice device, const VkPhysicalDeviceProperties& props) {
  if (props.apiVersion < VK_API_VERSION_1_2) return false;
  for (const char* name : kRayQueryExtensions) {
    if (!hasDeviceExtension(device, name)) return false;
  }
  return RayQueryFeatures(device).complete();
}

DeviceDescription describe(VkPhysicalDevice device, uint32_t index) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(device, &props);
  return {index,
          props.deviceName,
          deviceTypeName(props.deviceType),
          props.apiVersion,
          driverText(device, props),
          supportsRayQueries(device, props)};
}

VkInstance createBareInstance(const std::vector<const char*>& layers,
                              const std::vector<const char*>& extensions) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "raytracer";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  vkCheck(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
  return instance;
}

}  // namespace

void vkCheck(VkResult result, const char* call) {
  if (result != VK_SUCCESS) {
    throw Error(fmt::format("Vulkan: {} failed: {} ({})", call, resultName(result),
                            static_cast<int>(result)));
  }
}

std::vector<DeviceDescription> VulkanContext::listDevices() {
  VkInstance instance = createBareInstance({}, {});
  std::vector<DeviceDescription> result;
  auto devices = enumeratePhysicalDevices(instance);
  for (uint32_t i = 0; i < devices.size(); ++i) result.push_back(describe(devices[i], i));
  vkDestroyInstance(instance, nullptr);
  return result;
}

VulkanContext::VulkanContext(const ContextOptions& options) {
  try {
    createInstance(options);
    if (options.createSurface) surface_ = options.createSurface(instance_);
    pickPhysicalDevice(options);
    createDevice(options);
  } catch (...) {
    destroy();
    throw;
  }
}

VulkanContext::~VulkanContext() { destroy(); }

void VulkanContext::destroy() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    if (fence_) vkDestroyFence(device_, fence_, nullptr);
    if (commandPool_) vkDestroyCommandPool(device_, commandPool_, nullptr);
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (surface_) {
    vkDestroySurfaceKHR(instance_, surface_, nullptr);
    surface_ = VK_NULL_HANDLE;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_) {
    vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
  }
}

void VulkanContext::createInstance(const ContextOptions& options) {
  std::vector<const char*> layers;
  std::vector<const char*> extensions = options.instanceExtensions;
  bool validation = options.validation && layerAvailable(kValidationLayer);
  if (options.validation && !validation) {
    std::fprintf(stderr, "warning: %s is not installed; running without validation\n",
                 kValidationLayer);
  }
  if (validation) {
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  instance_ = createBareInstance(layers, extensions);
  if (!validation) return;
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = &VulkanContext::onValidationMessage;
  info.pUserData = this;
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
  if (!create) throw Error("Vulkan: vkCreateDebugUtilsMessengerEXT is not available");
  vkCheck(create(instance_, &info, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanContext::onValidationMessage(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
  auto* context = static_cast<VulkanContext*>(self);
  ++context->validationMessages_;
  const char* level =
      severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
  std::fprintf(stderr, "validation %s: %s\n", level, data->pMessage);
  return VK_FALSE;
}

void VulkanContext::pickPhysicalDevice(const ContextOptions& options) {
  auto devices = enumeratePhysicalDevices(instance_);
  if (devices.empty())
    throw Error("Vulkan: no physical device found (is mesa-vulkan-drivers installed?)");
  std::optional<uint32_t> chosen;
  if (options.deviceIndex) {
    if (*options.deviceIndex >= devices.size()) {
      throw Error(fmt::format("--device {}: only {} Vulkan device(s) present (see --device list)",
                              *options.deviceIndex, devices.size()));
    }
    if (!usableQueueFamily(devices[*options.deviceIndex], surface_)) {
      throw Error(fmt::format("--device {}: device has no suitable queue", *options.deviceIndex));
    }
    chosen = options.deviceIndex;
  } else {
    int bestRank = 1 << 30;
    for (uint32_t i = 0; i < devices.size(); ++i) {
      VkPhysicalDeviceProperties props;
      vkGetPhysicalDeviceProperties(devices[i], &props);
      int rank = deviceTypeRank(props.deviceType);
      if (usableQueueFamily(devices[i], surface_) && rank < bestRank) {
        bestRank = rank;
        chosen = i;
      }
    }
    if (!chosen) throw Error("Vulkan: no device with a suitable queue");
  }
  physicalDevice_ = devices[*chosen];
  description_ = describe(physicalDevice_, *chosen);
  vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
  VkPhysicalDeviceSubgroupProperties subgroups{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                          &subgroups};
  vkGetPhysicalDeviceProperties2(physicalDevice_, &properties2);
  const VkPhysicalDeviceDriverProperties driver = driverProperties(physicalDevice_, properties_);
  if (driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE) {
    lavapipeMesaMajor_ = mesaMajorVersion(driver.driverInfo);
  }
  subgroupArithmetic_ = (subgroups.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                        (subgroups.supportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT);
  subgroupBallot_ = (subgroups.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                    (subgroups.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT);
  subgroupSize_ = subgroups.subgroupSize;
  subgroupVote_ = (subgroups.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                  (subgroups.supportedOperations & VK_SUBGROUP_FEATURE_VOTE_BIT);
  queueFamily_ = *usableQueueFamily(physicalDevice_, surface_);
}

void VulkanContext::createDevice(const ContextOptions& options) {
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queueInfo;
  std::vector<const char*> extensions = options.deviceExtensions;
  rayQueries_ = options.rayQueries != RayQueries::Off && description_.rayQueries;
  if (options.rayQueries == RayQueries::Required && !rayQueries_) {
    throw Error(fmt::format("--accel hardware: {} has no ray queries (needs {}, {} and {})",
                            description_.name, kRayQueryExtensions[0], kRayQueryExtensions[1],
                            kRayQueryExtensions[2]));
  }
  // Only what ray queries need is enabled, and only when they are asked for.
  RayQueryFeatures features(physicalDevice_);
  if (rayQueries_) {
    extensions.insert(extensions.end(), std::begin(kRayQueryExtensions),
                      std::end(kRayQueryExtensions));
    features.vulkan12 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                         &features.structures};
    features.vulkan12.bufferDeviceAddress = VK_TRUE;
    features.structures = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR,
                           &features.rayQuery};
    features.structures.accelerationStructure = VK_TRUE;
    features.rayQuery = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
    features.rayQuery.rayQuery = VK_TRUE;
    info.pNext = &features.vulkan12;
  }
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  vkCheck(vkCreateDevice(physicalDevice_, &info, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  vkCheck(vkCreateCommandPool(device_, &poolInfo, nullptr, &commandPool_), "vkCreateCommandPool");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  vkCheck(vkCreateFence(device_, &fenceInfo, nullptr, &fence_), "vkCreateFence");
}

uint32_t VulkanContext::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                       VkMemoryPropertyFlags preferred) const {
  std::optional<uint32_t> fallback;
  for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
    VkMemoryPropertyFlags flags = memoryProperties_.memoryTypes[i].propertyFlags;
    if (!(typeBits & (1u << i)) || (flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (!fallback) fallback = i;
  }
  if (!fallback) throw Error("Vulkan: no memory type with the required properties");
  return *fallback;
}

VkMemoryPropertyFlags VulkanContext::memoryTypeFlags(uint32_t typeIndex) const {
  return memoryProperties_.memoryTypes[typeIndex].propertyFlags;
}

void VulkanContext::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = commandPool_;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  vkCheck(vkAllocateCommandBuffers(device_, &allocInfo, &commands), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkCheck(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
  record(commands);
  vkCheck(vkEndCommandBuffer(commands), "vkEndCommandBuffer");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  vkCheck(vkResetFences(device_, 1, &fence_), "vkResetFences");
  VkResult submitted = vkQueueSubmit(queue_, 1, &submit, fence_);
  VkResult waited = submitted == VK_SUCCESS
                        ? vkWaitForFences(device_, 1, &fence_, VK_TRUE, kFenceTimeoutNs)
                        : submitted;
  vkFreeCommandBuffers(device_, commandPool_, 1, &commands);
  vkCheck(submitted, "vkQueueSubmit");
  vkCheck(waited, "vkWaitForFences");
}

}  // namespace rt
