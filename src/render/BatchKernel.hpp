// A batch kernel over a flattened scene: shaders such as intersect_batch.comp
// and spawn_batch.comp that read rays (RT_BINDING_RAYS), walk the scene with
// the renderer's own traversal and write one result per item
// (RT_BINDING_HITS). Tests and the viewer's focus picking run scene queries
// through it.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "encode/FlatScene.hpp"
#include "gpu_types.h"
#include "scene/Scene.hpp"

namespace rt {

class ComputeKernel;
class SceneBuffers;
class ShaderCompiler;
class VulkanContext;

// A ray in world coordinates, its origin in the model's double precision.
struct WorldRay {
  WorldPoint origin{0.0};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};
  float tMax = RT_FAR_VALUE;
};

class BatchKernel {
 public:
  BatchKernel(VulkanContext& context, const ShaderCompiler& compiler, const Scene& scene,
              const std::string& shaderName, const FlattenOptions& options = {});
  ~BatchKernel();
  BatchKernel(const BatchKernel&) = delete;
  BatchKernel& operator=(const BatchKernel&) = delete;

  // Runs `items` invocations over `rays` (already in the flat scene's
  // camera-relative frame, see toFrame) and returns their results.
  template <typename Result>
  std::vector<Result> run(const std::vector<gpu::GpuRay>& rays, size_t items) {
    std::vector<Result> results(items);
    if (items > 0) dispatch(rays, items, results.data(), results.size() * sizeof(Result));
    return results;
  }

  // A world-space ray moved into the flat scene's frame.
  gpu::GpuRay toFrame(const WorldRay& ray) const;

  const FlatScene& flatScene() const { return flat_; }

 private:
  void dispatch(const std::vector<gpu::GpuRay>& rays, size_t items, void* results,
                size_t resultBytes);

  VulkanContext& context_;
  FlatScene flat_;
  std::unique_ptr<SceneBuffers> buffers_;
  std::unique_ptr<ComputeKernel> kernel_;
};

}  // namespace rt
