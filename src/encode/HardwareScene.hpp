// The flattened scene as the driver's acceleration structures, for --accel
// hardware (GPUs with ray tracing units; lavapipe walks them in software):
// one bottom level per mesh over its triangles, one over boxes of the other
// top-level primitives (spheres, cylinders, loose triangles), whose hits the
// shader finds with the renderer's own intersection code, and a top level
// of their instances. shaders/traverse_hardware.glsl walks them.
#pragma once

#include <optional>
#include <vector>

#include "encode/FlatScene.hpp"
#include "gpu/AccelerationStructure.hpp"

namespace rt {

class VulkanContext;

class HardwareScene {
 public:
  // Throws rt::Error when the context has no ray queries, or when the scene
  // exceeds what an instance can encode (2^24 primitives or items).
  HardwareScene(VulkanContext& context, const FlatScene& scene);

  // VK_NULL_HANDLE for a scene with nothing to hit.
  VkAccelerationStructureKHR topLevel() const { return top_ ? top_->handle() : VK_NULL_HANDLE; }
  size_t bytes() const;

 private:
  std::vector<AccelerationStructure> meshes_;  // by FlatScene::meshes
  std::optional<AccelerationStructure> boxes_;
  std::optional<AccelerationStructure> top_;
};

}  // namespace rt
