#include "encode/SceneBuffers.hpp"

#include <fmt/format.h>

#include <optional>

#include "gpu/ComputeKernel.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

// Records of `RowBytes`-byte rows: RGBA32 texels (or vec4/uvec4 storage
// rows) for the structs of gpu_types.h, R32 texels (uints) for packed
// texture texels (see shaders/bindings.glsl). Never empty (Vulkan forbids
// zero-sized buffers), and checked against the device's limit for the way
// the kernels read it.
template <size_t RowBytes = 16, typename T>
Buffer makeRows(VulkanContext& context, SceneArrays arrays, const SceneBufferLimits& limits,
                const std::vector<T>& items, const char* what) {
  static_assert(sizeof(T) % RowBytes == 0, "records are whole rows");
  VkDeviceSize rows = std::max<VkDeviceSize>(1, items.size()) * (sizeof(T) / RowBytes);
  const bool storage = arrays == SceneArrays::StorageBuffers;
  VkDeviceSize limit = limits.rows ? limits.rows
                       : storage   ? context.limits().maxStorageBufferRange / RowBytes
                                   : context.limits().maxTexelBufferElements;
  if (rows > limit) {
    throw Error(fmt::format("scene too large: {} need {} {}, the device allows {}", what, rows,
                            storage ? "storage buffer rows" : "texels", limit));
  }
  Buffer buffer(
      context, rows * RowBytes,
      storage ? VK_BUFFER_USAGE_STORAGE_BUFFER_BIT : VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
  if (!items.empty()) buffer.upload(items.data(), items.size() * sizeof(T));
  return buffer;
}

}  // namespace

bool texelBuffersMisread(const VulkanContext& context) {
  const std::optional<uint32_t> mesa = context.lavapipeMesaMajor();
  return mesa && *mesa >= 25 && context.subgroupSize() != 8;
}

SceneArrays readableSceneArrays(const VulkanContext& context, SceneArrays requested) {
  return texelBuffersMisread(context) ? SceneArrays::StorageBuffers : requested;
}

SceneBuffers::SceneBuffers(VulkanContext& context, const FlatScene& scene, SceneArrays arrays,
                           const SceneBufferLimits& limits)
    : arrays_(arrays),
      info_(context, sizeof(gpu::GpuSceneInfo), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT),
      primitives_(makeRows(context, arrays, limits, scene.primitives, "primitives")),
      bvhNodes_(makeRows(context, arrays, limits, scene.bvhNodes, "BVH nodes")),
      items_(makeRows(context, arrays, limits, scene.items, "BVH leaf items")),
      materials_(makeRows(context, arrays, limits, scene.materials, "materials")),
      pointLights_(makeRows(context, arrays, limits, scene.pointLights, "point lights")),
      areaLights_(makeRows(context, arrays, limits, scene.areaLights, "area lights")),
      emitters_(makeRows(context, arrays, limits, scene.emitters, "area light surfaces")),
      vertices_(makeRows(context, arrays, limits, scene.vertices, "vertices")),
      textureInfos_(makeRows(context, arrays, limits, scene.textureInfos, "texture table")),
      texels_(makeRows<sizeof(uint32_t)>(context, arrays, limits, scene.texels, "texture texels")) {
  info_.upload(&scene.info, sizeof(scene.info));
  if (scene.accel == AccelKind::Hardware)
    hardware_ = std::make_unique<HardwareScene>(context, scene);
}

void SceneBuffers::bindTo(ComputeKernel& kernel) const {
  kernel.bind(RT_BINDING_SCENE_INFO, info_);
  auto bindRows = [&](uint32_t binding, const Buffer& buffer, VkFormat texelFormat) {
    if (arrays_ == SceneArrays::StorageBuffers) {
      kernel.bind(binding, buffer);
    } else {
      kernel.bindTexels(binding, buffer, texelFormat);
    }
  };
  bindRows(RT_BINDING_PRIMITIVES, primitives_, VK_FORMAT_R32G32B32A32_SFLOAT);
  bindRows(RT_BINDING_BVH_NODES, bvhNodes_, VK_FORMAT_R32G32B32A32_UINT);
  bindRows(RT_BINDING_ITEMS, items_, VK_FORMAT_R32G32B32A32_SFLOAT);
  bindRows(RT_BINDING_MATERIALS, materials_, VK_FORMAT_R32G32B32A32_UINT);
  bindRows(RT_BINDING_POINT_LIGHTS, pointLights_, VK_FORMAT_R32G32B32A32_SFLOAT);
  bindRows(RT_BINDING_AREA_LIGHTS, areaLights_, VK_FORMAT_R32G32B32A32_UINT);
  bindRows(RT_BINDING_EMITTERS, emitters_, VK_FORMAT_R32G32B32A32_UINT);
  bindRows(RT_BINDING_VERTICES, vertices_, VK_FORMAT_R32G32B32A32_SFLOAT);
  bindRows(RT_BINDING_TEXTURE_INFO, textureInfos_, VK_FORMAT_R32G32B32A32_UINT);
  bindRows(RT_BINDING_TEXELS, texels_, VK_FORMAT_R32_UINT);
  if (hardware_ && hardware_->topLevel()) {
    kernel.bindAccelerationStructure(RT_BINDING_TLAS, hardware_->topLevel());
  }
}

std::vector<KernelBinding> SceneBuffers::bindings(AccelKind accel, SceneArrays arrays) {
  const VkDescriptorType rows = arrays == SceneArrays::StorageBuffers
                                    ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                    : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
  // Scene constants are a uniform buffer even where the arrays are storage
  // buffers: CPU drivers read a storage buffer one lane at a time, even at an
  // index every lane shares, once the read is inside a loop or branch.
  std::vector<KernelBinding> bindings = {{RT_BINDING_SCENE_INFO, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                                         {RT_BINDING_PRIMITIVES, rows},
                                         {RT_BINDING_BVH_NODES, rows},
                                         {RT_BINDING_ITEMS, rows},
                                         {RT_BINDING_MATERIALS, rows},
                                         {RT_BINDING_POINT_LIGHTS, rows},
                                         {RT_BINDING_AREA_LIGHTS, rows},
                                         {RT_BINDING_EMITTERS, rows},
                                         {RT_BINDING_VERTICES, rows},
                                         {RT_BINDING_TEXTURE_INFO, rows},
                                         {RT_BINDING_TEXELS, rows}};
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
