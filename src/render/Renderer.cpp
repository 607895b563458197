#include "render/Renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

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

}  // namespace

Renderer::Renderer(VulkanContext& context, const ShaderCompiler& compiler)
    : context_(context), compiler_(compiler) {}

ImageF Renderer::render(const Scene& scene, const RenderOptions& options,
                        const ProgressCallback& onProgress, RenderStats* stats) {
  RenderStats local;
  RenderStats& s = stats ? *stats : local;
  auto start = Clock::now();
  FlatScene flat = flattenScene(scene, options.width, options.height);
  const uint32_t width = flat.info.width;
  const uint32_t height = flat.info.height;
  SceneBuffers sceneBuffers(context_, flat);
  size_t pixels = size_t(width) * height;
  if (pixels * sizeof(glm::vec4) > context_.limits().maxStorageBufferRange) {
    throw Error(fmt::format("image {}x{} is too large for one accumulation buffer on this device",
                            width, height));
  }
  Buffer accumulation(context_, pixels * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  accumulation.fillZero();
  s.uploadSeconds = secondsSince(start);
  s.primitives = flat.info.primitiveCount;
  s.bvhNodes = flat.info.bvhNodeCount;
  s.bvhDepth = flat.bvhDepth;
  s.features = detectFeatures(scene);

  start = Clock::now();
  std::vector<uint32_t> spirv = compiler_.compile("trace.comp", s.features.defines());
  ComputeKernel kernel(context_, spirv,
                       {RT_BINDING_SCENE_INFO, RT_BINDING_PRIMITIVES, RT_BINDING_BVH_NODES,
                        RT_BINDING_MATERIALS, RT_BINDING_POINT_LIGHTS, RT_BINDING_ACCUMULATION},
                       sizeof(gpu::GpuFrameParams));
  sceneBuffers.bindTo(kernel);
  kernel.bind(RT_BINDING_ACCUMULATION, accumulation);
  s.compileSeconds = secondsSince(start);

  const uint32_t total = std::max(options.samplesPerPixel, 1u);
  DispatchPlanner planner(width, height, options.secondsPerDispatch);
  auto renderStart = Clock::now();
  for (uint32_t done = 0; done < total;) {
    uint32_t samples = planner.samplesPerPass(total - done);
    for (uint32_t row = 0; row < height;) {
      uint32_t rows = std::min(planner.rowsPerDispatch(samples), height - row);
      gpu::GpuFrameParams frame{};
      frame.tileOrigin = {0, row};
      frame.tileSize = {width, rows};
      frame.sampleBegin = done;
      frame.sampleCount = samples;
      frame.samplesTotal = total;
      frame.seed = options.seed;
      frame.samplerKind = samplerCode(options.sampler);
      auto dispatchStart = Clock::now();
      context_.submitAndWait([&](VkCommandBuffer commands) {
        kernel.recordDispatch(commands, &frame, divideRoundUp(width, RT_WORKGROUP_SIZE_X),
                              divideRoundUp(rows, RT_WORKGROUP_SIZE_Y));
      });
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

  std::vector<glm::vec4> sums(pixels);
  accumulation.download(sums.data(), pixels * sizeof(glm::vec4));
  return resolve(sums, width, height);
}

}  // namespace rt
