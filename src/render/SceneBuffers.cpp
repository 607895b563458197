#include "render/SceneBuffers.hpp"

#include <fmt/format.h>

#include "gpu/ComputeKernel.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

// A storage buffer holding `items`; never empty (Vulkan forbids zero-sized
// buffers), and checked against the device's storage buffer range.
template <typename T>
Buffer makeStorage(VulkanContext& context, const SceneBufferLimits& limits,
                   const std::vector<T>& items, const char* what) {
  VkDeviceSize bytes = std::max<VkDeviceSize>(sizeof(T), items.size() * sizeof(T));
  VkDeviceSize limit =
      limits.storageBytes ? limits.storageBytes : context.limits().maxStorageBufferRange;
  if (bytes > limit) {
    throw Error(fmt::format("scene too large: {} need {} MiB, the device allows {} MiB per buffer",
                            what, bytes >> 20, limit >> 20));
  }
  Buffer buffer(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  if (!items.empty()) buffer.upload(items.data(), items.size() * sizeof(T));
  return buffer;
}

// Records read as RGBA32 texels (see shaders/bindings.glsl).
template <typename T>
Buffer makeTexels(VulkanContext& context, const SceneBufferLimits& limits,
                  const std::vector<T>& items, const char* what) {
  static_assert(sizeof(T) % 16 == 0, "texel records are whole RGBA32 texels");
  VkDeviceSize texels = std::max<VkDeviceSize>(1, items.size()) * (sizeof(T) / 16);
  VkDeviceSize limit = limits.texels ? limits.texels : context.limits().maxTexelBufferElements;
  if (texels > limit) {
    throw Error(fmt::format("scene too large: {} need {} texels, the device allows {}", what,
                            texels, limit));
  }
  Buffer buffer(context, texels * 16, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
  if (!items.empty()) buffer.upload(items.data(), items.size() * sizeof(T));
  return buffer;
}

}  // namespace

SceneBuffers::SceneBuffers(VulkanContext& context, const FlatScene& scene,
                           const SceneBufferLimits& limits)
    : info_(context, sizeof(gpu::GpuSceneInfo), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT),
      primitives_(makeTexels(context, limits, scene.primitives, "primitives")),
      bvhNodes_(makeTexels(context, limits, scene.bvhNodes, "BVH nodes")),
      items_(makeTexels(context, limits, scene.items, "BVH leaf items")),
      materials_(makeStorage(context, limits, scene.materials, "materials")),
      pointLights_(makeStorage(context, limits, scene.pointLights, "point lights")),
      areaLights_(makeStorage(context, limits, scene.areaLights, "area lights")),
      emitters_(makeStorage(context, limits, scene.emitters, "area light surfaces")),
      vertices_(makeStorage(context, limits, scene.vertices, "vertices")),
      textureInfos_(makeStorage(context, limits, scene.textureInfos, "texture table")),
      texels_(makeStorage(context, limits, scene.texels, "texture texels")) {
  info_.upload(&scene.info, sizeof(scene.info));
}

void SceneBuffers::bindTo(ComputeKernel& kernel) const {
  kernel.bind(RT_BINDING_SCENE_INFO, info_);
  kernel.bindTexels(RT_BINDING_PRIMITIVES, primitives_, VK_FORMAT_R32G32B32A32_SFLOAT);
  kernel.bindTexels(RT_BINDING_BVH_NODES, bvhNodes_, VK_FORMAT_R32G32B32A32_UINT);
  kernel.bindTexels(RT_BINDING_ITEMS, items_, VK_FORMAT_R32G32B32A32_SFLOAT);
  kernel.bind(RT_BINDING_MATERIALS, materials_);
  kernel.bind(RT_BINDING_POINT_LIGHTS, pointLights_);
  kernel.bind(RT_BINDING_AREA_LIGHTS, areaLights_);
  kernel.bind(RT_BINDING_EMITTERS, emitters_);
  kernel.bind(RT_BINDING_VERTICES, vertices_);
  kernel.bind(RT_BINDING_TEXTURE_INFO, textureInfos_);
  kernel.bind(RT_BINDING_TEXELS, texels_);
}

std::vector<KernelBinding> SceneBuffers::bindings() {
  constexpr VkDescriptorType kTexels = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  // Scene constants are a uniform buffer: CPU drivers read a storage buffer
  // one lane at a time, even at an index every lane shares, once the read is
  // inside a loop or branch.
  return {{RT_BINDING_SCENE_INFO, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
          {RT_BINDING_PRIMITIVES, kTexels},
          {RT_BINDING_BVH_NODES, kTexels},
          {RT_BINDING_ITEMS, kTexels},
          {RT_BINDING_MATERIALS},
          {RT_BINDING_POINT_LIGHTS},
          {RT_BINDING_AREA_LIGHTS},
          {RT_BINDING_EMITTERS},
          {RT_BINDING_VERTICES},
          {RT_BINDING_TEXTURE_INFO},
          {RT_BINDING_TEXELS}};
}

void SceneBuffers::updateInfo(const gpu::GpuSceneInfo& info) { info_.upload(&info, sizeof(info)); }

size_t SceneBuffers::bytes() const {
  return info_.size() + primitives_.size() + bvhNodes_.size() + items_.size() + materials_.size() +
         pointLights_.size() + areaLights_.size() + emitters_.size() + vertices_.size() + textureInfos_.size() + texels_.size();
}

}  // namespace rt
