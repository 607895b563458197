#include "render/Renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "render/FlatScene.hpp"
#include "render/SceneBuffers.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

uint32_t divideRoundUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

// Sizes dispatches from the measured cost of one pixel-sample so that each
// takes about `target` seconds: several samples over the whole image when
// that is cheap, otherwise one sample over a band of rows.
class DispatchPlanner {
 public:
  DispatchPlanner(uint32_t width, uint32_t height, double target)
      : width_(width), height_(height), target_(target) {}

  uint32_t samplesPerPass(uint32_t remaining) const {
    if (costPerPixelSample_ <= 0) return 1;
    double work = target_ / costPerPixelSample_;
    double pixels = double(width_) * height_;
    return std::clamp<uint32_t>(static_cast<uint32_t>(work / pixels), 1, remaining);
  }

  uint32_t rowsPerDispatch(uint32_t samples) const {
    // Before any measurement, a first band of about 16k pixels finds the cost.
    double work = costPerPixelSample_ > 0 ? target_ / costPerPixelSample_ : 16384.0;
    double rows = work / (double(width_) * samples);
    return std::clamp<uint32_t>(static_cast<uint32_t>(rows), 1, height_);
  }

  void record(uint32_t rows, uint32_t samples, double seconds) {
    double cost = seconds / (double(width_) * rows * samples);
    // Smooth, but let the first measurement count fully.
    costPerPixelSample_ = costPerPixelSample_ > 0 ? 0.5 * (costPerPixelSample_ + cost) : cost;
  }

 private:
  uint32_t width_;
  uint32_t height_;
  double target_;
  double costPerPixelSample_ = 0;
};

ImageF resolve(const std::vector<glm::vec4>& sums, uint32_t width, uint32_t height) {
  ImageF image{width, height, {}};
  image.rgba.resize(size_t(width) * height * 4);
  for (size_t i = 0; i < sums.size(); ++i) {
    float count = std::max(sums[i].w, 1.0f);
    image.rgba[i * 4 + 0] = sums[i].x / count;
    image.rgba[i * 4 + 1] = sums[i].y / count;
    image.rgba[i * 4 + 2] = sums[i].z / count;
    image.rgba[i * 4 + 3] = 1.0f;
  }
  return image;
}

uint32_t samplerCode(SamplerKind kind) {
  return kind == SamplerKind::Random ? RT_SAMPLER_RANDOM : RT_SAMPLER_JITTERED;
}

// The kernel with its buffers for one render: built once, dispatched many times.
class RenderJob {
 public:
  RenderJob(VulkanContext& context, const ShaderCompiler& compiler, const FlatScene& flat,
            const ShaderFeatures& features)
      : context_(context),
        width_(flat.info.width),
        height_(flat.info.height),
        sceneBuffers_(context, flat),
        accumulation_(context, accumulationBytes(context, flat),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
    accumulation_.fillZero();
    std::vector<uint32_t> bindings = {RT_BINDING_SCENE_INFO,   RT_BINDING_PRIMITIVES,
                                      RT_BINDING_BVH_NODES,    RT_BINDING_MATERIALS,
                                      RT_BINDING_POINT_LIGHTS, RT_BINDING_ACCUMULATION};
    if (features.countRays) {
      rayCounter_.emplace(context, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
      rayCounter_->fillZero();
      bindings.push_back(RT_BINDING_RAY_COUNTER);
    }
    kernel_.emplace(context, compiler.compile("trace.comp", features.defines()), bindings,
                    static_cast<uint32_t>(sizeof(gpu::GpuFrameParams)));
    sceneBuffers_.bindTo(*kernel_);
    kernel_->bind(RT_BINDING_ACCUMULATION, accumulation_);
    if (rayCounter_) kernel_->bind(RT_BINDING_RAY_COUNTER, *rayCounter_);
  }

  // Adds samples [begin, begin + count) to rows [row, row + rows).
  void dispatch(uint32_t row, uint32_t rows, uint32_t begin, uint32_t count, uint32_t total,
                const RenderOptions& options) {
    gpu::GpuFrameParams frame{};
    frame.tileOrigin = {0, row};
    frame.tileSize = {width_, rows};
    frame.sampleBegin = begin;
    frame.sampleCount = count;
    frame.samplesTotal = total;
    frame.seed = options.seed;
    frame.samplerKind = samplerCode(options.sampler);
    context_.submitAndWait([&](VkCommandBuffer commands) {
      kernel_->recordDispatch(commands, &frame, divideRoundUp(width_, RT_WORKGROUP_SIZE_X),
                              divideRoundUp(rows, RT_WORKGROUP_SIZE_Y));
    });
    if (rayCounter_) collectRayCount();
  }

  uint64_t raysTraced() const { return raysTraced_; }

  ImageF resolveImage() {
    std::vector<glm::vec4> sums(size_t(width_) * height_);
    accumulation_.download(sums.data(), sums.size() * sizeof(glm::vec4));
    return resolve(sums, width_, height_);
  }

 private:
  static VkDeviceSize accumulationBytes(VulkanContext& context, const FlatScene& flat) {
    VkDeviceSize bytes = VkDeviceSize(flat.info.width) * flat.info.height * sizeof(glm::vec4);
    if (bytes > context.limits().maxStorageBufferRange) {
      throw Error(fmt::format("image {}x{} is too large for one accumulation buffer on this device",
                              flat.info.width, flat.info.height));
    }
    return bytes;
  }

  // The 32-bit counter is read and cleared after every dispatch, so it never
  // overflows however long the render.
  void collectRayCount() {
    uint32_t count = 0;
    rayCounter_->download(&count, sizeof(count));
    raysTraced_ += count;
    rayCounter_->fillZero();
  }

  VulkanContext& context_;
  uint32_t width_;
  uint32_t height_;
  SceneBuffers sceneBuffers_;
  Buffer accumulation_;
  std::optional<Buffer> rayCounter_;
  std::optional<ComputeKernel> kernel_;
  uint64_t raysTraced_ = 0;
};

}  // namespace

Renderer::Renderer(VulkanContext& context, const ShaderCompiler& compiler)
    : context_(context), compiler_(compiler) {}

ImageF Renderer::render(const Scene& scene, const RenderOptions& options,
                        const ProgressCallback& onProgress, RenderStats* stats) {
  RenderStats local;
  RenderStats& s = stats ? *stats : local;
  auto start = Clock::now();
  FlatScene flat = flattenScene(scene, {options.width, options.height, options.shading});
  s.primitives = flat.info.primitiveCount;
  s.bvhNodes = flat.info.bvhNodeCount;
  s.bvhDepth = flat.bvhDepth;
  s.warnings = flat.warnings;
  s.features = detectFeatures(scene);
  s.features.countRays = options.countRays;
  RenderJob job(context_, compiler_, flat, s.features);
  s.setupSeconds = secondsSince(start);

  const uint32_t width = flat.info.width;
  const uint32_t height = flat.info.height;
  const uint32_t total = std::max(options.samplesPerPixel, 1u);
  DispatchPlanner planner(width, height, options.secondsPerDispatch);
  auto renderStart = Clock::now();
  for (uint32_t done = 0; done < total;) {
    uint32_t samples = planner.samplesPerPass(total - done);
    for (uint32_t row = 0; row < height;) {
      uint32_t rows = std::min(planner.rowsPerDispatch(samples), height - row);
      auto dispatchStart = Clock::now();
      job.dispatch(row, rows, done, samples, total, options);
      planner.record(rows, samples, secondsSince(dispatchStart));
      ++s.dispatches;
      row += rows;
      if (onProgress) {
        onProgress({done + samples * double(row) / height, total, secondsSince(renderStart)});
      }
    }
    done += samples;
  }
  s.renderSeconds = secondsSince(renderStart);
  s.raysTraced = job.raysTraced();
  return job.resolveImage();
}

}  // namespace rt
