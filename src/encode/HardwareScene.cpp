#include "encode/HardwareScene.hpp"

#include <fmt/format.h>

#include "bvh/Bvh.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

// Instance custom indices and binding-table offsets are 24-bit fields.
constexpr uint32_t kMaxInstanceField = (1u << 24) - 1;

uint32_t instanceField(uint32_t value, const char* what) {
  if (value > kMaxInstanceField) {
    throw Error(fmt::format("scene too large for --accel hardware: {} {} (at most {})", what, value,
                            kMaxInstanceField));
  }
  return value;
}

VkTransformMatrixKHR rowsOf(const glm::mat4& transform) {
  VkTransformMatrixKHR rows{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) rows.matrix[r][c] = transform[c][r];  // glm is column-major
  }
  return rows;
}

// `cutout`: the instance's triangles are candidates that the shader decides
// (alpha cutouts, shaders/alpha.glsl); the rest are opaque.
VkAccelerationStructureInstanceKHR instanceOf(const AccelerationStructure& bottom,
                                              const glm::mat4& transform, uint32_t customIndex,
                                              uint32_t tableOffset, bool cutout = false) {
  VkAccelerationStructureInstanceKHR instance{};
  instance.transform = rowsOf(transform);
  instance.instanceCustomIndex = customIndex & kMaxInstanceField;  // checked by instanceField
  instance.mask = 0xff;
  instance.instanceShaderBindingTableRecordOffset = tableOffset & kMaxInstanceField;
  // Surfaces are two-sided, as in the BVH path.
  instance.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR |
                   (cutout ? VK_GEOMETRY_INSTANCE_FORCE_NO_OPAQUE_BIT_KHR
                           : VK_GEOMETRY_INSTANCE_FORCE_OPAQUE_BIT_KHR);
  instance.accelerationStructureReference = bottom.deviceAddress();
  return instance;
}

std::vector<glm::vec3> cornersOf(const FlatScene& scene, const FlatMesh& mesh) {
  std::vector<glm::vec3> corners;
  corners.reserve(size_t(mesh.triangleCount) * 3);
  for (uint32_t i = 0; i < mesh.triangleCount; ++i) {
    const gpu::GpuItem& item = scene.items.at(mesh.firstItem + i);
    for (const glm::vec4& row : {item.row0, item.row1, item.row2}) corners.emplace_back(row);
  }
  return corners;
}

// The same boxes the BVH path's top level is built over.
VkAabbPositionsKHR boxOf(const gpu::GpuPrimitive& primitive) {
  Aabb box = primitiveBounds(primitive);
  return {box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z};
}

}  // namespace

HardwareScene::HardwareScene(VulkanContext& context, const FlatScene& scene) {
  std::vector<VkAccelerationStructureInstanceKHR> instances;
  for (const FlatMesh& mesh : scene.meshes) {
    instanceField(mesh.firstItem + mesh.triangleCount, "items");
    meshes_.push_back(AccelerationStructure::triangles(context, cornersOf(scene, mesh)));
  }
  for (const FlatInstance& instance : scene.instances) {
    bool cutout = (scene.primitives.at(instance.primitive).flags & RT_PRIM_ALPHA_CUTOUT) != 0u;
    instances.push_back(instanceOf(meshes_.at(instance.mesh), instance.objectToWorld,
                                   instanceField(instance.primitive, "primitives"),
                                   scene.meshes.at(instance.mesh).firstItem, cutout));
  }
  // Instances are the first primitives; the rest are loose, in one box list.
  const auto firstLoose = static_cast<uint32_t>(scene.instances.size());
  std::vector<VkAabbPositionsKHR> boxes;
  for (size_t i = firstLoose; i < scene.primitives.size(); ++i) {
    boxes.push_back(boxOf(scene.primitives[i]));
  }
  if (!boxes.empty()) {
    instanceField(static_cast<uint32_t>(scene.primitives.size()), "primitives");
    boxes_ = AccelerationStructure::boxes(context, boxes);
    instances.push_back(instanceOf(*boxes_, glm::mat4(1.0f), firstLoose, 0));
  }
  if (!instances.empty()) top_ = AccelerationStructure::instances(context, instances);
}

size_t HardwareScene::bytes() const {
  size_t total = (boxes_ ? boxes_->bytes() : 0) + (top_ ? top_->bytes() : 0);
  for (const AccelerationStructure& mesh : meshes_) total += mesh.bytes();
  return total;
}

}  // namespace rt
