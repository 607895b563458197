// A FlatScene uploaded to GPU texel buffers (and a uniform buffer for its
// constants), bindable to any kernel that includes shaders/bindings.glsl;
// for --accel hardware also as the driver's acceleration structures.
#pragma once

#include <memory>
#include <vector>

#include "encode/FlatScene.hpp"
#include "encode/HardwareScene.hpp"
#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"

namespace rt {

class VulkanContext;

// Largest buffers a scene may use; 0: the device's limit (tests set less).
struct SceneBufferLimits {
  VkDeviceSize texels = 0;  // per texel buffer (maxTexelBufferElements)
};

class SceneBuffers {
 public:
  // A buffer that would exceed the limits is a one-line "scene too large"
  // Error naming it (nothing is rendered).
  SceneBuffers(VulkanContext& context, const FlatScene& scene,
               const SceneBufferLimits& limits = {});
  void bindTo(ComputeKernel& kernel) const;
  // The binding numbers bindTo() fills (set 0), for kernel layouts.
  static std::vector<KernelBinding> bindings(AccelKind accel = AccelKind::Bvh);
  // Replaces the per-scene constants (camera moves); no dispatch may be in flight.
  void updateInfo(const gpu::GpuSceneInfo& info);
  size_t bytes() const;

 private:
  Buffer info_;
  Buffer primitives_;
  Buffer bvhNodes_;
  Buffer items_;
  Buffer materials_;
  Buffer pointLights_;
  Buffer areaLights_;
  Buffer emitters_;
  Buffer vertices_;
  Buffer textureInfos_;
  Buffer texels_;
  std::unique_ptr<HardwareScene> hardware_;  // --accel hardware only
};

}  // namespace rt
