#include "render/ProgressiveRenderer.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

uint32_t divideRoundUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

VkDeviceSize accumulationBytes(VulkanContext& context, const FlatScene& flat) {
  VkDeviceSize bytes = VkDeviceSize(flat.info.width) * flat.info.height * sizeof(glm::vec4);
  if (bytes > context.limits().maxStorageBufferRange) {
    throw Error(fmt::format("image {}x{} is too large for one accumulation buffer on this device",
                            flat.info.width, flat.info.height));
  }
  return bytes;
}

ShaderFeatures featuresFor(const Scene& scene, const FlatScene& flat,
                           const ProgressiveOptions& options) {
  ShaderFeatures features = detectFeatures(scene, flat);
  features.countRays = options.countRays;
  return features;
}

}  // namespace

ProgressiveRenderer::ProgressiveRenderer(VulkanContext& context, const ShaderCompiler& compiler,
                                         const Scene& scene, const ProgressiveOptions& options)
    : context_(context),
      compiler_(compiler),
      options_(options),
      flat_(flattenScene(scene, {options.width, options.height, options.shading})),
      features_(featuresFor(scene, flat_, options)),
      width_(flat_.info.width),
      height_(flat_.info.height),
      sceneBuffers_(context, flat_),
      accumulation_(context, accumulationBytes(context, flat_), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
  accumulation_.fillZero();
  samplesDone_ = options.firstSample;
  if (options.countRays) {
    rayCounter_.emplace(context, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    rayCounter_->fillZero();
  }
  kernel_ = buildKernel();
}

std::unique_ptr<ComputeKernel> ProgressiveRenderer::buildKernel() const {
  std::vector<KernelBinding> bindings = SceneBuffers::bindings();
  bindings.push_back({RT_BINDING_ACCUMULATION});
  if (rayCounter_) bindings.push_back({RT_BINDING_RAY_COUNTER});
  auto kernel = std::make_unique<ComputeKernel>(
      context_, compiler_.compile("trace.comp", features_.defines()), bindings,
      static_cast<uint32_t>(sizeof(gpu::GpuFrameParams)));
  sceneBuffers_.bindTo(*kernel);
  kernel->bind(RT_BINDING_ACCUMULATION, accumulation_);
  if (rayCounter_) kernel->bind(RT_BINDING_RAY_COUNTER, *rayCounter_);
  return kernel;
}

void ProgressiveRenderer::recordSamples(VkCommandBuffer commands, uint32_t row, uint32_t rows,
                                        uint32_t count) const {
  gpu::GpuFrameParams frame{};
  frame.tileOrigin = {0, row};
  frame.tileSize = {width_, rows};
  frame.sampleBegin = samplesDone_;
  frame.sampleCount = count;
  frame.samplesTotal = std::max(options_.samplesTotal, samplesDone_ + count);
  frame.seed = options_.seed;
  frame.samplerKind =
      options_.sampler == SamplerKind::Random ? RT_SAMPLER_RANDOM : RT_SAMPLER_JITTERED;
  kernel_->recordDispatch(commands, &frame, divideRoundUp(width_, RT_WORKGROUP_SIZE_X),
                          divideRoundUp(rows, RT_WORKGROUP_SIZE_Y));
}

void ProgressiveRenderer::addSamples(uint32_t count) {
  context_.submitAndWait(
      [&](VkCommandBuffer commands) { recordSamples(commands, 0, height_, count); });
  finishPass(count);
}

void ProgressiveRenderer::recordReset(VkCommandBuffer commands) {
  vkCmdFillBuffer(commands, accumulation_.handle(), 0, VK_WHOLE_SIZE, 0);
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0, nullptr, 0,
                       nullptr);
  samplesDone_ = options_.firstSample;
}

void ProgressiveRenderer::reset() {
  context_.submitAndWait([&](VkCommandBuffer commands) { recordReset(commands); });
}

void ProgressiveRenderer::setCamera(const Camera& camera) {
  fillCamera(camera, width_, height_, flat_.info, flat_.frameOrigin);
  sceneBuffers_.updateInfo(flat_.info);
  reset();
}

void ProgressiveRenderer::reloadShaders() {
  std::unique_ptr<ComputeKernel> fresh = buildKernel();  // throws, leaving kernel_ as it was
  retired_.push_back(std::move(kernel_));
  kernel_ = std::move(fresh);
}

ImageF ProgressiveRenderer::resolve() {
  std::vector<glm::vec4> sums(size_t(width_) * height_);
  accumulation_.download(sums.data(), sums.size() * sizeof(glm::vec4));
  ImageF image{width_, height_, {}};
  image.rgba.resize(sums.size() * 4);
  for (size_t i = 0; i < sums.size(); ++i) {
    float count = std::max(sums[i].w, 1.0f);
    image.rgba[i * 4 + 0] = sums[i].x / count;
    image.rgba[i * 4 + 1] = sums[i].y / count;
    image.rgba[i * 4 + 2] = sums[i].z / count;
    image.rgba[i * 4 + 3] = sums[i].w;  // samples behind the mean, for merging
  }
  return image;
}

uint64_t ProgressiveRenderer::raysTraced() {
  if (!rayCounter_) return 0;
  // The 32-bit counter is folded into 64 bits and cleared whenever it is
  // read, so it cannot overflow as long as it is read every few dispatches.
  uint32_t count = 0;
  rayCounter_->download(&count, sizeof(count));
  raysTraced_ += count;
  rayCounter_->fillZero();
  return raysTraced_;
}

}  // namespace rt
