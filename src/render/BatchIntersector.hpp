// Runs closest-hit and any-hit queries for a batch of rays on the GPU through
// the renderer's own intersection and traversal shaders (shaders/
// intersect_batch.comp). Tests use it to check the real shader code against
// double-precision references.
#pragma once

#include <memory>
#include <vector>

#include "gpu_types.h"
#include "render/FlatScene.hpp"
#include "scene/Scene.hpp"

namespace rt {

class ComputeKernel;
class SceneBuffers;
class ShaderCompiler;
class VulkanContext;

class BatchIntersector {
 public:
  BatchIntersector(VulkanContext& context, const ShaderCompiler& compiler, const Scene& scene,
                   const FlattenOptions& options = {});
  ~BatchIntersector();

  std::vector<gpu::GpuHit> intersect(const std::vector<gpu::GpuRay>& rays);

  // Primitives in GPU order: GpuHit::primitiveIndex indexes this.
  const FlatScene& flatScene() const { return flat_; }

 private:
  VulkanContext& context_;
  FlatScene flat_;
  std::unique_ptr<SceneBuffers> buffers_;
  std::unique_ptr<ComputeKernel> kernel_;
};

}  // namespace rt
