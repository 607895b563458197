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
  std::vector<gpu::GpuPrimitive> primitives;  // top level: shapes' primitives, mesh instances
  std::vector<gpu::GpuItem> items;            // what BVH leaves point at (see gpu_types.h)
  std::vector<gpu::GpuBvhNode> bvhNodes;      // top level first, then one tree per mesh
  std::vector<gpu::GpuMaterial> materials;
  std::vector<gpu::GpuPointLight> pointLights;
  std::vector<gpu::GpuAreaLight> areaLights;
  std::vector<gpu::GpuEmitter> emitters;  // pieces of the area lights' surfaces
  std::vector<gpu::GpuVertex> vertices;   // shading data of some triangles
  std::vector<gpu::GpuTextureInfo> textureInfos;
  std::vector<uint32_t> texels;       // RGBA8 of every texture, packed
  uint32_t bvhDepth = 0;              // top level plus the deepest mesh
  glm::vec3 frameOrigin{0.0f};        // world point at the GPU coordinates' origin (the camera)
  std::vector<std::string> warnings;  // scene features the GPU scene leaves out
};

// Bvh: binned SAH trees. None: every ray tests every primitive (a chain of
// nodes that prunes nothing), to compare against.
enum class AccelKind { Bvh, None };

struct FlattenOptions {
  uint32_t width = 0;  // override the camera's image size when non-zero
  uint32_t height = 0;
  std::optional<ShadingModel> shading;  // override the family's shading model
  AccelKind accel = AccelKind::Bvh;
  uint32_t maxLeafSize = 4;   // BVH leaves (<= RT_REF_MAX_LEAF_SIZE)
  uint32_t buildThreads = 0;  // BVH build threads, 0: one per core
};

FlatScene flattenScene(const Scene& scene, const FlattenOptions& options = {});

// Writes the camera fields of `info` (basis, field of view, lens, image size),
// the position relative to the flat scene's frameOrigin.
void fillCamera(const Camera& camera, uint32_t width, uint32_t height, gpu::GpuSceneInfo& info,
                const glm::vec3& frameOrigin = glm::vec3(0.0f));

}  // namespace rt
