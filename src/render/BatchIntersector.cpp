#include "render/BatchIntersector.hpp"

#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "render/Features.hpp"
#include "render/SceneBuffers.hpp"

namespace rt {

BatchIntersector::BatchIntersector(VulkanContext& context, const ShaderCompiler& compiler,
                                   const Scene& scene, const FlattenOptions& options)
    : context_(context), flat_(flattenScene(scene, options)) {
  buffers_ = std::make_unique<SceneBuffers>(context, flat_);
  std::vector<uint32_t> spirv =
      compiler.compile("intersect_batch.comp", detectFeatures(scene, flat_).defines());
  std::vector<KernelBinding> bindings = SceneBuffers::bindings();
  bindings.push_back({RT_BINDING_RAYS});
  bindings.push_back({RT_BINDING_HITS});
  kernel_ = std::make_unique<ComputeKernel>(context, spirv, bindings,
                                            static_cast<uint32_t>(sizeof(gpu::GpuBatchParams)));
  buffers_->bindTo(*kernel_);
}

BatchIntersector::~BatchIntersector() = default;

std::vector<gpu::GpuHit> BatchIntersector::intersect(const std::vector<gpu::GpuRay>& rays) {
  std::vector<gpu::GpuHit> hits(rays.size());
  if (rays.empty()) return hits;
  Buffer rayBuffer(context_, rays.size() * sizeof(gpu::GpuRay), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  Buffer hitBuffer(context_, hits.size() * sizeof(gpu::GpuHit), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  std::vector<gpu::GpuRay> framed = rays;  // into the flat scene's camera-relative frame
  for (gpu::GpuRay& ray : framed) ray.origin -= flat_.frameOrigin;
  rayBuffer.upload(framed.data(), framed.size() * sizeof(gpu::GpuRay));
  kernel_->bind(RT_BINDING_RAYS, rayBuffer);
  kernel_->bind(RT_BINDING_HITS, hitBuffer);
  gpu::GpuBatchParams params{static_cast<uint32_t>(rays.size()), 0, 0, 0};
  uint32_t groups = (params.rayCount + RT_BATCH_WORKGROUP_SIZE - 1) / RT_BATCH_WORKGROUP_SIZE;
  context_.submitAndWait(
      [&](VkCommandBuffer commands) { kernel_->recordDispatch(commands, &params, groups); });
  hitBuffer.download(hits.data(), hits.size() * sizeof(gpu::GpuHit));
  return hits;
}

}  // namespace rt
