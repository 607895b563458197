#include "render/Renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "render/FlatScene.hpp"
#include "render/ProgressiveRenderer.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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

}  // namespace

Renderer::Renderer(VulkanContext& context, const ShaderCompiler& compiler)
    : context_(context), compiler_(compiler) {}

namespace {

// Adds one pass of `samples` over every row, in dispatches the planner sizes.
// Returns false if stopped part way.
bool renderPass(VulkanContext& context, ProgressiveRenderer& job, DispatchPlanner& planner,
                uint32_t samples, const RenderOptions& options, const ProgressCallback& onProgress,
                Clock::time_point start, RenderStats& stats) {
  const uint32_t height = job.height();
  const uint32_t end = options.endSample ? options.endSample : options.samplesPerPixel;
  for (uint32_t row = 0; row < height;) {
    if (options.shouldStop && options.shouldStop()) return false;
    uint32_t rows = std::min(planner.rowsPerDispatch(samples), height - row);
    auto dispatchStart = Clock::now();
    context.submitAndWait(
        [&](VkCommandBuffer commands) { job.recordSamples(commands, row, rows, samples); });
    planner.record(rows, samples, secondsSince(dispatchStart));
    ++stats.dispatches;
    row += rows;
    if (options.countRays) stats.raysTraced = job.raysTraced();
    if (onProgress) {
      double done = job.samplesDone() - options.firstSample + samples * double(row) / height;
      onProgress({done, end - options.firstSample, secondsSince(start)});
    }
  }
  return true;
}

}  // namespace

ImageF Renderer::render(const Scene& scene, const RenderOptions& options,
                        const ProgressCallback& onProgress, RenderStats* stats) {
  RenderStats local;
  RenderStats& s = stats ? *stats : local;
  auto start = Clock::now();
  const uint32_t total = std::max(options.samplesPerPixel, 1u);
  const uint32_t end = options.endSample ? std::min(options.endSample, total) : total;
  if (options.firstSample >= end) {
    throw Error(fmt::format("empty sample range {}:{} (of {} samples)", options.firstSample, end,
                            total));
  }
  ProgressiveOptions progressive{options.width,   options.height,  total,
                                 options.seed,    options.sampler, options.shading,
                                 options.countRays, options.firstSample, options.accel};
  ProgressiveRenderer job(context_, compiler_, scene, progressive);
  s.primitives = job.flatScene().info.primitiveCount;
  s.bvhNodes = job.flatScene().info.bvhNodeCount;
  s.bvhDepth = job.flatScene().bvhDepth;
  s.warnings = job.flatScene().warnings;
  s.features = job.features();
  s.setupSeconds = secondsSince(start);

  DispatchPlanner planner(job.width(), job.height(), options.secondsPerDispatch);
  auto renderStart = Clock::now();
  while (job.samplesDone() < end) {
    uint32_t samples = planner.samplesPerPass(end - job.samplesDone());
    if (!renderPass(context_, job, planner, samples, options, onProgress, renderStart, s)) {
      s.stoppedEarly = true;
      break;
    }
    job.finishPass(samples);
  }
  s.samplesDone = job.samplesDone() - options.firstSample;
  s.renderSeconds = secondsSince(renderStart);
  return job.resolve();
}

}  // namespace rt
