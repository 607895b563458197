// Runs closest-hit and any-hit queries for a batch of rays on the GPU through
// the renderer's own intersection and traversal shaders (shaders/
// intersect_batch.comp). Tests use it to check the real shader code against
// double-precision references; the viewer picks its focus distance with it.
#pragma once

#include <vector>

#include "gpu_types.h"
#include "render/BatchKernel.hpp"

namespace rt {

class BatchIntersector {
 public:
  BatchIntersector(VulkanContext& context, const ShaderCompiler& compiler, const Scene& scene,
                   const FlattenOptions& options = {})
      : kernel_(context, compiler, scene, "intersect_batch.comp", options) {}

  // World-space rays; one hit each.
  std::vector<gpu::GpuHit> intersect(const std::vector<WorldRay>& rays);
  std::vector<gpu::GpuHit> intersect(const std::vector<gpu::GpuRay>& rays);  // float origins

  // Primitives in GPU order: GpuHit::primitiveIndex indexes this.
  const FlatScene& flatScene() const { return kernel_.flatScene(); }

 private:
  BatchKernel kernel_;
};

}  // namespace rt
