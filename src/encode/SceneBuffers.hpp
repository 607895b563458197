// A FlatScene uploaded to GPU buffers (and a uniform buffer for its
// constants), bindable to any kernel that includes shaders/bindings.glsl;
// for --accel hardware also as the driver's acceleration structures.
#pragma once

#include <memory>
#include <vector>

#include "encode/FlatScene.hpp"
#include "encode/HardwareScene.hpp"
#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"

namespace rt {

class VulkanContext;

// How kernels read the scene arrays (shaders/bindings.glsl): as texel
// buffers or as storage buffers of the same bytes; the images are the same.
// Texel buffers are the default on every device measured: lavapipe gathers
// texels with vector loads but reads storage buffers one lane at a time
// (default.json 2.4x slower with storage buffers), and on an NVIDIA H200
// storage buffers rendered at 0.91-0.98x (though the plain BVH kernel of
// bench/ walked 1.16x faster with them). Storage buffers stay selectable
// (--scene-arrays) to measure other GPUs.
enum class SceneArrays { TexelBuffers, StorageBuffers };

// Mesa 25.0's lavapipe misreads texel buffers in the render kernel at
// vector widths other than its default 256 bits (LP_NATIVE_VECTOR_WIDTH=128
// or 512: subgroups of 4 or 16 lanes; found on Mesa 25.0.7): the upper
// lanes' fetches return another component or zeros, even at the kernel's
// first line, so BVH walks never end (512) or the kernel crashes (128). The
// batch kernels (BatchKernel), which bind fewer of them, read right. Storage
// buffers read right everywhere, and give the same image as texel buffers
// at 256 bits.
bool texelBuffersMisread(const VulkanContext& context);

// `requested`, or storage buffers where the device misreads texel buffers.
SceneArrays readableSceneArrays(const VulkanContext& context, SceneArrays requested);

// Largest buffers a scene may use; 0: the device's limit (tests set less).
struct SceneBufferLimits {
  // Rows per scene array (texels: maxTexelBufferElements; storage-buffer
  // rows: maxStorageBufferRange / row size).
  VkDeviceSize rows = 0;
};

class SceneBuffers {
 public:
  // A buffer that would exceed the limits is a one-line "scene too large"
  // Error naming it (nothing is rendered).
  // Kernels bound to these buffers are compiled with
  // ShaderFeatures::storageBuffers set to match `arrays`.
  SceneBuffers(VulkanContext& context, const FlatScene& scene,
               SceneArrays arrays = SceneArrays::TexelBuffers,
               const SceneBufferLimits& limits = {});
  void bindTo(ComputeKernel& kernel) const;
  // The bindings bindTo() fills (set 0), for kernel layouts.
  static std::vector<KernelBinding> bindings(AccelKind accel = AccelKind::Bvh,
                                             SceneArrays arrays = SceneArrays::TexelBuffers);
  // Replaces the per-scene constants (camera moves); no dispatch may be in flight.
  void updateInfo(const gpu::GpuSceneInfo& info);
  size_t bytes() const;

 private:
  SceneArrays arrays_;
  Buffer info_;
  Buffer primitives_;
  Buffer bvhNodes_;
  Buffer items_;
  Buffer materials_;
  Buffer pointLights_;
  Buffer areaLights_;
  Buffer emitters_;
  Buffer vertices_;
  Buffer textureInfos_;
  Buffer texels_;
  std::unique_ptr<HardwareScene> hardware_;  // --accel hardware only
};

}  // namespace rt
