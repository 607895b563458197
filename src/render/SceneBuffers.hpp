// A FlatScene uploaded to GPU storage buffers, bindable to any kernel that
// includes shaders/bindings.glsl.
#pragma once

#include "gpu/Buffer.hpp"
#include "render/FlatScene.hpp"

namespace rt {

class ComputeKernel;
class VulkanContext;

class SceneBuffers {
 public:
  SceneBuffers(VulkanContext& context, const FlatScene& scene);
  void bindTo(ComputeKernel& kernel) const;
  // Replaces the per-scene constants (camera moves); no dispatch may be in flight.
  void updateInfo(const gpu::GpuSceneInfo& info);
  size_t bytes() const;

 private:
  Buffer info_;
  Buffer primitives_;
  Buffer bvhNodes_;
  Buffer materials_;
  Buffer pointLights_;
};

}  // namespace rt
