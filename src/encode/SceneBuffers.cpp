#include "encode/SceneBuffers.hpp"

#include <fmt/format.h>

#include "gpu/ComputeKernel.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

// Records read as texels of `TexelBytes` bytes each: RGBA32 for the structs
// of gpu_types.h (see shaders/bindings.glsl), R32 for packed texture texels.
// Never empty (Vulkan forbids zero-sized buffers), and checked against the
// device's texel buffer limit.
template <size_t TexelBytes = 16, typename T>
Buffer makeTexels(VulkanContext& context, const SceneBufferLimits& limits,
                  const std::vector<T>& items, const char* what) {
  static_assert(sizeof(T) % TexelBytes == 0, "texel records are whole texels");
  VkDeviceSize texels = std::max<VkDeviceSize>(1, items.size()) * (sizeof(T) / TexelBytes);
  VkDeviceSize limit = limits.texels ? limits.texels : context.limits().maxTexelBufferElements;
  if (texels > limit) {
    throw Error(fmt::format("scene too large: {} need {} texels, the device allows {}", what,
                            texels, limit));
  }
  Buffer buffer(context, texels * TexelBytes, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
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
      materials_(makeTexels(context, limits, scene.materials, "materials")),
      pointLights_(makeTexels(context, limits, scene.pointLights, "point lights")),
      areaLights_(makeTexels(context, limits, scene.areaLights, "area lights")),
      emitters_(makeTexels(context, limits, scene.emitters, "area light surfaces")),
      vertices_(makeTexels(context, limits, scene.vertices, "vertices")),
      textureInfos_(makeTexels(context, limits, scene.textureInfos, "texture table")),
      texels_(makeTexels<sizeof(uint32_t)>(context, limits, scene.texels, "texture texels")) {
  info_.upload(&scene.info, sizeof(scene.info));
  if (scene.accel == AccelKind::Hardware)
    hardware_ = std::make_unique<HardwareScene>(context, scene);
}

void SceneBuffers::bindTo(ComputeKernel& kernel) const {
  kernel.bind(RT_BINDING_SCENE_INFO, info_);
  kernel.bindTexels(RT_BINDING_PRIMITIVES, primitives_, VK_FORMAT_R32G32B32A32_SFLOAT);
  kernel.bindTexels(RT_BINDING_BVH_NODES, bvhNodes_, VK_FORMAT_R32G32B32A32_UINT);
  kernel.bindTexels(RT_BINDING_ITEMS, items_, VK_FORMAT_R32G32B32A32_SFLOAT);
  kernel.bindTexels(RT_BINDING_MATERIALS, materials_, VK_FORMAT_R32G32B32A32_UINT);
  kernel.bindTexels(RT_BINDING_POINT_LIGHTS, pointLights_, VK_FORMAT_R32G32B32A32_SFLOAT);
  kernel.bindTexels(RT_BINDING_AREA_LIGHTS, areaLights_, VK_FORMAT_R32G32B32A32_UINT);
  kernel.bindTexels(RT_BINDING_EMITTERS, emitters_, VK_FORMAT_R32G32B32A32_UINT);
  kernel.bindTexels(RT_BINDING_VERTICES, vertices_, VK_FORMAT_R32G32B32A32_SFLOAT);
  kernel.bindTexels(RT_BINDING_TEXTURE_INFO, textureInfos_, VK_FORMAT_R32G32B32A32_UINT);
  kernel.bindTexels(RT_BINDING_TEXELS, texels_, VK_FORMAT_R32_UINT);
  if (hardware_ && hardware_->topLevel()) {
    kernel.bindAccelerationStructure(RT_BINDING_TLAS, hardware_->topLevel());
  }
}

std::vector<KernelBinding> SceneBuffers::bindings(AccelKind accel) {
  constexpr VkDescriptorType kTexels = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  // Scene constants are a uniform buffer, everything else texel buffers: CPU
  // drivers read a storage buffer one lane at a time, even at an index every
  // lane shares, once the read is inside a loop or branch.
  std::vector<KernelBinding> bindings = {{RT_BINDING_SCENE_INFO, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                                         {RT_BINDING_PRIMITIVES, kTexels},
                                         {RT_BINDING_BVH_NODES, kTexels},
                                         {RT_BINDING_ITEMS, kTexels},
                                         {RT_BINDING_MATERIALS, kTexels},
                                         {RT_BINDING_POINT_LIGHTS, kTexels},
                                         {RT_BINDING_AREA_LIGHTS, kTexels},
                                         {RT_BINDING_EMITTERS, kTexels},
                                         {RT_BINDING_VERTICES, kTexels},
                                         {RT_BINDING_TEXTURE_INFO, kTexels},
                                         {RT_BINDING_TEXELS, kTexels}};
  if (accel == AccelKind::Hardware) {
    bindings.push_back({RT_BINDING_TLAS, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR});
  }
  return bindings;
}

void SceneBuffers::updateInfo(const gpu::GpuSceneInfo& info) { info_.upload(&info, sizeof(info)); }

size_t SceneBuffers::bytes() const {
  return info_.size() + primitives_.size() + bvhNodes_.size() + items_.size() + materials_.size() +
         pointLights_.size() + areaLights_.size() + emitters_.size() + vertices_.size() +
         textureInfos_.size() + texels_.size();
}

}  // namespace rt
