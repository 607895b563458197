#include "gpu/AccelerationStructure.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

// Extension entry points (the loader exports only core functions).
struct Functions {
  PFN_vkGetAccelerationStructureBuildSizesKHR getBuildSizes;
  PFN_vkCreateAccelerationStructureKHR create;
  PFN_vkDestroyAccelerationStructureKHR destroy;
  PFN_vkCmdBuildAccelerationStructuresKHR build;
  PFN_vkGetAccelerationStructureDeviceAddressKHR getAddress;
};

template <typename F>
F load(VkDevice device, const char* name) {
  auto function = reinterpret_cast<F>(vkGetDeviceProcAddr(device, name));
  if (!function) throw Error(fmt::format("Vulkan: {} is not available", name));
  return function;
}

Functions functions(const VulkanContext& context) {
  if (!context.rayQueriesEnabled()) {
    throw Error("internal: acceleration structures on a context without ray queries");
  }
  VkDevice device = context.device();
  return {
      load<PFN_vkGetAccelerationStructureBuildSizesKHR>(device,
                                                        "vkGetAccelerationStructureBuildSizesKHR"),
      load<PFN_vkCreateAccelerationStructureKHR>(device, "vkCreateAccelerationStructureKHR"),
      load<PFN_vkDestroyAccelerationStructureKHR>(device, "vkDestroyAccelerationStructureKHR"),
      load<PFN_vkCmdBuildAccelerationStructuresKHR>(device, "vkCmdBuildAccelerationStructuresKHR"),
      load<PFN_vkGetAccelerationStructureDeviceAddressKHR>(
          device, "vkGetAccelerationStructureDeviceAddressKHR")};
}

constexpr VkBufferUsageFlags kInputUsage =
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
    VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

// A device buffer holding `bytes` of `data`, readable by builds.
std::unique_ptr<Buffer> inputBuffer(VulkanContext& context, const void* data, size_t bytes) {
  auto buffer = std::make_unique<Buffer>(context, bytes, kInputUsage);
  buffer->upload(data, bytes);
  return buffer;
}

VkDeviceOrHostAddressConstKHR addressOf(const Buffer& buffer) {
  VkDeviceOrHostAddressConstKHR address{};
  address.deviceAddress = buffer.deviceAddress();
  return address;
}

}  // namespace

AccelerationStructure AccelerationStructure::triangles(VulkanContext& context,
                                                       const std::vector<glm::vec3>& corners) {
  if (corners.empty() || corners.size() % 3 != 0) {
    throw Error("internal: a triangle acceleration structure needs whole triangles");
  }
  std::unique_ptr<Buffer> vertices =
      inputBuffer(context, corners.data(), corners.size() * sizeof(glm::vec3));
  VkAccelerationStructureGeometryKHR geometry{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
  geometry.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
  VkAccelerationStructureGeometryTrianglesDataKHR& data = geometry.geometry.triangles;
  data.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
  data.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
  data.vertexData = addressOf(*vertices);
  data.vertexStride = sizeof(glm::vec3);
  data.maxVertex = static_cast<uint32_t>(corners.size() - 1);
  data.indexType = VK_INDEX_TYPE_NONE_KHR;
  return AccelerationStructure(context, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry,
                               static_cast<uint32_t>(corners.size() / 3));
}

AccelerationStructure AccelerationStructure::boxes(VulkanContext& context,
                                                   const std::vector<VkAabbPositionsKHR>& boxes) {
  if (boxes.empty()) throw Error("internal: a box acceleration structure needs boxes");
  std::unique_ptr<Buffer> input =
      inputBuffer(context, boxes.data(), boxes.size() * sizeof(VkAabbPositionsKHR));
  VkAccelerationStructureGeometryKHR geometry{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_AABBS_KHR;
  geometry.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
  VkAccelerationStructureGeometryAabbsDataKHR& data = geometry.geometry.aabbs;
  data.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_AABBS_DATA_KHR;
  data.data = addressOf(*input);
  data.stride = sizeof(VkAabbPositionsKHR);
  return AccelerationStructure(context, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, geometry,
                               static_cast<uint32_t>(boxes.size()));
}

AccelerationStructure AccelerationStructure::instances(
    VulkanContext& context, const std::vector<VkAccelerationStructureInstanceKHR>& instances) {
  if (instances.empty()) throw Error("internal: a top level needs instances");
  std::unique_ptr<Buffer> input = inputBuffer(
      context, instances.data(), instances.size() * sizeof(VkAccelerationStructureInstanceKHR));
  VkAccelerationStructureGeometryKHR geometry{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  VkAccelerationStructureGeometryInstancesDataKHR& data = geometry.geometry.instances;
  data.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  data.arrayOfPointers = VK_FALSE;
  data.data = addressOf(*input);
  return AccelerationStructure(context, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, geometry,
                               static_cast<uint32_t>(instances.size()));
}

// Sizes, allocates and builds in one submission; the inputs (still owned by
// the caller's frame) may go once this returns.
AccelerationStructure::AccelerationStructure(VulkanContext& context,
                                             VkAccelerationStructureTypeKHR type,
                                             const VkAccelerationStructureGeometryKHR& geometry,
                                             uint32_t count)
    : context_(&context) {
  const Functions vk = functions(context);
  VkAccelerationStructureBuildGeometryInfoKHR build{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build.type = type;
  build.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  build.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  build.geometryCount = 1;
  build.pGeometries = &geometry;
  VkAccelerationStructureBuildSizesInfoKHR sizes{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  vk.getBuildSizes(context.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build,
                   &count, &sizes);
  storage_ = std::make_unique<Buffer>(context, sizes.accelerationStructureSize,
                                      VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR |
                                          VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
  VkAccelerationStructureCreateInfoKHR create{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  create.buffer = storage_->handle();
  create.size = sizes.accelerationStructureSize;
  create.type = type;
  vkCheck(vk.create(context.device(), &create, nullptr, &handle_),
          "vkCreateAccelerationStructureKHR");
  Buffer scratch(context, std::max<VkDeviceSize>(sizes.buildScratchSize, 1),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
  build.dstAccelerationStructure = handle_;
  build.scratchData.deviceAddress = scratch.deviceAddress();
  VkAccelerationStructureBuildRangeInfoKHR range{count, 0, 0, 0};
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  context.submitAndWait([&](VkCommandBuffer commands) {
    vk.build(commands, 1, &build, &ranges);
    // The build's writes before any trace reads the structure.
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
    barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                         VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR |
                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
  });
  VkAccelerationStructureDeviceAddressInfoKHR addressInfo{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  addressInfo.accelerationStructure = handle_;
  address_ = vk.getAddress(context.device(), &addressInfo);
}

AccelerationStructure::~AccelerationStructure() { release(); }

AccelerationStructure::AccelerationStructure(AccelerationStructure&& other) noexcept {
  *this = std::move(other);
}

AccelerationStructure& AccelerationStructure::operator=(AccelerationStructure&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    storage_ = std::move(other.storage_);
    handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    address_ = std::exchange(other.address_, 0);
  }
  return *this;
}

void AccelerationStructure::release() {
  if (handle_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyAccelerationStructureKHR>(
        vkGetDeviceProcAddr(context_->device(), "vkDestroyAccelerationStructureKHR"));
    if (destroy) destroy(context_->device(), handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }
  storage_.reset();
}

}  // namespace rt
