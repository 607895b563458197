// The host scene flattened into the arrays the GPU reads (std430 structs of
// shaders/gpu_types.h), with primitives reordered by the BVH.
#pragma once

#include <vector>

#include "gpu_types.h"
#include "scene/Scene.hpp"

namespace rt {

struct FlatScene {
  gpu::GpuSceneInfo info{};
  std::vector<gpu::GpuPrimitive> primitives;
  std::vector<gpu::GpuBvhNode> bvhNodes;
  std::vector<gpu::GpuMaterial> materials;
  std::vector<gpu::GpuPointLight> pointLights;
  uint32_t bvhDepth = 0;
};

// `width`/`height` override the camera's image size when non-zero.
FlatScene flattenScene(const Scene& scene, uint32_t width = 0, uint32_t height = 0);

}  // namespace rt
