// A Vulkan acceleration structure (VK_KHR_acceleration_structure) built on
// the device: a bottom level over triangles or over axis-aligned boxes
// (procedural primitives, whose hits the shader computes), or a top level
// over instances of bottom levels. For --accel hardware: GPUs with ray
// tracing units walk these themselves; lavapipe walks them in software.
#pragma once

#include <vulkan/vulkan.h>

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "gpu/Buffer.hpp"

namespace rt {

class VulkanContext;

class AccelerationStructure {
 public:
  // Non-indexed triangles: corners 3i, 3i+1, 3i+2 make triangle i (its
  // primitive index in hits). Opaque: hits are committed without the shader.
  static AccelerationStructure triangles(VulkanContext& context,
                                         const std::vector<glm::vec3>& corners);
  // Box i is procedural primitive i: candidates the shader intersects.
  static AccelerationStructure boxes(VulkanContext& context,
                                     const std::vector<VkAabbPositionsKHR>& boxes);
  // A top level; each instance names a bottom level by its device address.
  static AccelerationStructure instances(
      VulkanContext& context, const std::vector<VkAccelerationStructureInstanceKHR>& instances);

  ~AccelerationStructure();
  AccelerationStructure(AccelerationStructure&& other) noexcept;
  AccelerationStructure& operator=(AccelerationStructure&& other) noexcept;
  AccelerationStructure(const AccelerationStructure&) = delete;
  AccelerationStructure& operator=(const AccelerationStructure&) = delete;

  VkAccelerationStructureKHR handle() const { return handle_; }
  VkDeviceAddress deviceAddress() const { return address_; }
  VkDeviceSize bytes() const { return storage_ ? storage_->size() : 0; }

 private:
  AccelerationStructure(VulkanContext& context, VkAccelerationStructureTypeKHR type,
                        const VkAccelerationStructureGeometryKHR& geometry, uint32_t count);
  void release();

  VulkanContext* context_ = nullptr;
  std::unique_ptr<Buffer> storage_;
  VkAccelerationStructureKHR handle_ = VK_NULL_HANDLE;
  VkDeviceAddress address_ = 0;
};

}  // namespace rt
