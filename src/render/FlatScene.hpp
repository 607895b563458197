// The host scene flattened into the arrays the GPU reads (std430 structs of
// shaders/gpu_types.h), with primitives reordered by the BVH.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gpu_types.h"
#include "render/Conventions.hpp"
#include "scene/Scene.hpp"

namespace rt {

struct FlatScene {
  gpu::GpuSceneInfo info{};
  std::vector<gpu::GpuPrimitive> primitives;
  std::vector<gpu::GpuBvhNode> bvhNodes;
  std::vector<gpu::GpuMaterial> materials;
  std::vector<gpu::GpuPointLight> pointLights;
  std::vector<gpu::GpuVertex> vertices;          // shading data of some triangles
  std::vector<gpu::GpuTextureInfo> textureInfos;
  std::vector<uint32_t> texels;                  // RGBA8 of every texture, packed
  uint32_t bvhDepth = 0;
  glm::vec3 frameOrigin{0.0f};  // world point at the GPU coordinates' origin (the camera)
  std::vector<std::string> warnings;  // scene features the GPU scene leaves out
};

struct FlattenOptions {
  uint32_t width = 0;  // override the camera's image size when non-zero
  uint32_t height = 0;
  std::optional<ShadingModel> shading;  // override the family's shading model
};

FlatScene flattenScene(const Scene& scene, const FlattenOptions& options = {});

// Writes the camera fields of `info` (basis, field of view, lens, image size),
// the position relative to the flat scene's frameOrigin.
void fillCamera(const Camera& camera, uint32_t width, uint32_t height, gpu::GpuSceneInfo& info,
                const glm::vec3& frameOrigin = glm::vec3(0.0f));

}  // namespace rt
