// Runs shaders/spawn_batch.comp: for each probe, a ray to its closest hit,
// then a ray spawned from that hit with the renderer's own hitPoint and
// spawnRay, traced again. Tests use it to check that rays leaving a surface
// never hit it again.
#pragma once

#include <vector>

#include "gpu_types.h"
#include "render/BatchKernel.hpp"

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
      : kernel_(context, compiler, scene, "spawn_batch.comp") {}

  std::vector<SpawnResult> run(const std::vector<SpawnQuery>& queries) {
    // Two rays per query: the first, and the spawned ray's direction (the
    // kernel finds its origin).
    std::vector<gpu::GpuRay> rays;
    for (const SpawnQuery& query : queries) {
      const gpu::GpuRay& first = query.first;
      rays.push_back(kernel_.toFrame({WorldPoint(first.origin), first.direction, first.tMax}));
      rays.push_back({glm::vec3(0.0f), 0.0f, query.leaving, 0.0f});
    }
    static_assert(sizeof(SpawnResult) == 2 * sizeof(gpu::GpuHit));
    return kernel_.run<SpawnResult>(rays, queries.size());
  }

 private:
  BatchKernel kernel_;
};

}  // namespace rt::test
