#include "render/BatchKernel.hpp"

#include "encode/Features.hpp"
#include "encode/SceneBuffers.hpp"
#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "render/ProgressiveRenderer.hpp"

namespace rt {

BatchKernel::BatchKernel(VulkanContext& context, const ShaderCompiler& compiler, const Scene& scene,
                         const std::string& shaderName, const FlattenOptions& options)
    : context_(context), flat_(flattenScene(scene, options)) {
  buffers_ = std::make_unique<SceneBuffers>(context, flat_);
  ShaderFeatures features = detectFeatures(scene, flat_);
  features.laneVotes = laneVotesPay(context);
  std::vector<uint32_t> spirv = compiler.compile(shaderName, features.defines());
  std::vector<KernelBinding> bindings = SceneBuffers::bindings(flat_.accel);
  bindings.push_back({RT_BINDING_RAYS});
  bindings.push_back({RT_BINDING_HITS});
  kernel_ = std::make_unique<ComputeKernel>(context, spirv, bindings,
                                            static_cast<uint32_t>(sizeof(gpu::GpuBatchParams)));
  buffers_->bindTo(*kernel_);
}

BatchKernel::~BatchKernel() = default;

gpu::GpuRay BatchKernel::toFrame(const WorldRay& ray) const {
  return {flat_.frame.point(ray.origin), 0.0f, ray.direction, ray.tMax};
}

void BatchKernel::dispatch(const std::vector<gpu::GpuRay>& rays, size_t items, void* results,
                           size_t resultBytes) {
  Buffer rayBuffer(context_, rays.size() * sizeof(gpu::GpuRay), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  Buffer resultBuffer(context_, resultBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  rayBuffer.upload(rays.data(), rays.size() * sizeof(gpu::GpuRay));
  kernel_->bind(RT_BINDING_RAYS, rayBuffer);
  kernel_->bind(RT_BINDING_HITS, resultBuffer);
  gpu::GpuBatchParams params{static_cast<uint32_t>(items), 0, 0, 0};
  uint32_t groups = (params.rayCount + RT_BATCH_WORKGROUP_SIZE - 1) / RT_BATCH_WORKGROUP_SIZE;
  context_.submitAndWait(
      [&](VkCommandBuffer commands) { kernel_->recordDispatch(commands, &params, groups); });
  resultBuffer.download(results, resultBytes);
}

}  // namespace rt
