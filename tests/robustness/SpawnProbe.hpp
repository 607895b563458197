// Runs shaders/spawn_batch.comp: for each probe, a ray to its closest hit,
// then a ray spawned from that hit with the renderer's own hitPoint and
// spawnRay, traced again. Tests use it to check that rays leaving a surface
// never hit it again.
#pragma once

#include <memory>
#include <vector>

#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "gpu_types.h"
#include "render/Features.hpp"
#include "render/FlatScene.hpp"
#include "render/SceneBuffers.hpp"

namespace rt::test {

struct SpawnQuery {
  gpu::GpuRay first;  // world space
  glm::vec3 leaving;  // direction of the ray spawned at the first hit
};

struct SpawnResult {
  gpu::GpuHit first;
  gpu::GpuHit spawned;  // t < 0: no hit; then normal holds the spawned origin
};

class SpawnProbe {
 public:
  SpawnProbe(VulkanContext& context, const ShaderCompiler& compiler, const Scene& scene)
      : context_(context), flat_(flattenScene(scene)) {
    buffers_ = std::make_unique<SceneBuffers>(context, flat_);
    std::vector<KernelBinding> bindings = SceneBuffers::bindings();
    bindings.push_back({RT_BINDING_RAYS});
    bindings.push_back({RT_BINDING_HITS});
    kernel_ = std::make_unique<ComputeKernel>(
        context, compiler.compile("spawn_batch.comp", detectFeatures(scene, flat_).defines()),
        bindings, static_cast<uint32_t>(sizeof(gpu::GpuBatchParams)));
    buffers_->bindTo(*kernel_);
  }

  std::vector<SpawnResult> run(const std::vector<SpawnQuery>& queries) {
    std::vector<SpawnResult> results(queries.size());
    if (queries.empty()) return results;
    std::vector<gpu::GpuRay> rays;
    for (const SpawnQuery& query : queries) {
      gpu::GpuRay first = query.first;
      first.origin -= flat_.frameOrigin;  // into the flat scene's frame
      rays.push_back(first);
      rays.push_back({glm::vec3(0.0f), 0.0f, query.leaving, 0.0f});
    }
    static_assert(sizeof(SpawnResult) == 2 * sizeof(gpu::GpuHit));
    Buffer rayBuffer(context_, rays.size() * sizeof(gpu::GpuRay),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Buffer hitBuffer(context_, results.size() * sizeof(SpawnResult),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    rayBuffer.upload(rays.data(), rays.size() * sizeof(gpu::GpuRay));
    kernel_->bind(RT_BINDING_RAYS, rayBuffer);
    kernel_->bind(RT_BINDING_HITS, hitBuffer);
    gpu::GpuBatchParams params{static_cast<uint32_t>(queries.size()), 0, 0, 0};
    uint32_t groups = (params.rayCount + RT_BATCH_WORKGROUP_SIZE - 1) / RT_BATCH_WORKGROUP_SIZE;
    context_.submitAndWait(
        [&](VkCommandBuffer commands) { kernel_->recordDispatch(commands, &params, groups); });
    hitBuffer.download(results.data(), results.size() * sizeof(SpawnResult));
    return results;
  }

 private:
  VulkanContext& context_;
  FlatScene flat_;
  std::unique_ptr<SceneBuffers> buffers_;
  std::unique_ptr<ComputeKernel> kernel_;
};

}  // namespace rt::test
