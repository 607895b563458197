// The host scene flattened into the arrays the GPU reads (std430 structs of
// shaders/gpu_types.h), with primitives reordered by the BVH.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bvh/Bvh.hpp"
#include "encode/Conventions.hpp"
#include "encode/GpuFrame.hpp"
#include "gpu_types.h"
#include "scene/Scene.hpp"

namespace rt {

// Bvh: binned SAH trees. None: every ray tests every primitive (a chain of
// nodes that prunes nothing), to compare against. Hardware: the driver's
// acceleration structures through ray queries (GPUs with ray tracing units;
// render/HardwareScene), the BVH path's hits on every shape.
enum class AccelKind { Bvh, None, Hardware };

// A mesh's triangles in FlatScene::items (its BVH's leaf order).
struct FlatMesh {
  uint32_t firstItem = 0;
  uint32_t triangleCount = 0;
};

// A mesh instance: its top-level primitive, its mesh (FlatScene::meshes)
// and where it puts the mesh's items (identity: they are in world space).
struct FlatInstance {
  uint32_t primitive = 0;
  uint32_t mesh = 0;
  glm::mat4 objectToWorld{1.0f};
};

struct FlatScene {
  gpu::GpuSceneInfo info{};
  std::vector<gpu::GpuPrimitive> primitives;  // top level: shapes' primitives, mesh instances
  std::vector<gpu::GpuItem> items;            // what BVH leaves point at (see gpu_types.h)
  std::vector<gpu::GpuBvhNode> bvhNodes;      // top level first, then one tree per mesh
  // The two levels again as meshes and their instances (the hardware path
  // builds its own structures from them). Instances are the first primitives.
  std::vector<FlatMesh> meshes;
  std::vector<FlatInstance> instances;
  std::vector<gpu::GpuMaterial> materials;
  std::vector<gpu::GpuPointLight> pointLights;
  std::vector<gpu::GpuAreaLight> areaLights;
  std::vector<gpu::GpuEmitter> emitters;  // pieces of the area lights' surfaces
  std::vector<gpu::GpuVertex> vertices;   // shading data of some triangles
  std::vector<gpu::GpuTextureInfo> textureInfos;
  std::vector<uint32_t> texels;       // RGBA8 of every texture, packed
  uint32_t bvhDepth = 0;              // top level plus the deepest mesh
  GpuFrame frame;                     // GPU coordinates: relative to the camera's position
  std::vector<std::string> warnings;  // scene features the GPU scene leaves out
  AccelKind accel = AccelKind::Bvh;   // what the kernels walk
};

struct FlattenOptions {
  uint32_t width = 0;  // override the camera's image size when non-zero
  uint32_t height = 0;
  std::optional<ShadingModel> shading;  // override the family's shading model
  AccelKind accel = AccelKind::Bvh;
  uint32_t maxLeafSize = 4;   // BVH leaves (<= RT_REF_MAX_LEAF_SIZE)
  uint32_t buildThreads = 0;  // BVH build threads, 0: one per core
  // Origin of the GPU's coordinates (GpuFrame); default the camera's
  // position. The viewer and a camera path's frames keep the scene's own
  // camera's, wherever the camera has moved: positions round alike, so a
  // frame renders bit for bit as the viewer showed it.
  std::optional<WorldPoint> frameOrigin;
  // How the image is shown (default: toneMappingFor(scene)): the ray tree's
  // bailout is in steps of it, so `--exposure 4` quarters the weight below
  // which branches and light samples are dropped.
  std::optional<ToneMapping> displayMapping;
};

FlatScene flattenScene(const Scene& scene, const FlattenOptions& options = {});

// Whether a material samples a texture (colour, normals, glow, metallic-
// roughness): its triangles then need texture coordinates, and the kernels
// the texture code.
bool samplesTextures(const gpu::GpuMaterial& material);

// Whether a material's alpha cuts holes (MASK, BLEND): its mesh instances
// are flagged RT_PRIM_ALPHA_CUTOUT, and the walks ask it about their hits.
bool hasAlphaCutout(const gpu::GpuMaterial& material);

// Bounds of a top-level primitive that is not a mesh instance (its BVH box).
Aabb primitiveBounds(const gpu::GpuPrimitive& primitive);

// Writes the camera fields of `info` (basis, field of view, lens, image size),
// the position in the flat scene's `frame`.
void fillCamera(const Camera& camera, uint32_t width, uint32_t height, const GpuFrame& frame,
                gpu::GpuSceneInfo& info);

}  // namespace rt
