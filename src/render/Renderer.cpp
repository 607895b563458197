#include "render/Renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <optional>

#include "encode/FlatScene.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "imaging/ImageError.hpp"
#include "render/AdaptiveSampling.hpp"
#include "render/ProgressiveRenderer.hpp"
#include "scene/Limits.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double processCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return double(now.tv_sec) + double(now.tv_nsec) * 1e-9;
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
    double rows = workPerDispatch() / (double(width_) * samples);
    return std::clamp<uint32_t>(static_cast<uint32_t>(rows), 1, height_);
  }

  // Pixel-samples one dispatch should add.
  double workPerDispatch() const {
    return costPerPixelSample_ > 0 ? target_ / costPerPixelSample_ : 16384.0;
  }

  void record(double pixelSamples, double seconds) {
    double cost = seconds / pixelSamples;
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

uint32_t nextRmseCheckpoint(uint32_t samplesDone) {
  if (samplesDone < 2) return 2;
  if (samplesDone < 4) return 4;
  for (int k = 0;; ++k) {
    double checkpoint = std::round(8.0 * std::exp2(k / 4.0));
    if (checkpoint > samplesDone) return static_cast<uint32_t>(std::min(checkpoint, 4294967295.0));
  }
}

Renderer::Renderer(VulkanContext& context, const ShaderCompiler& compiler)
    : context_(context), compiler_(compiler) {}

namespace {

// One render's sample loop: passes of a few samples over every row of the
// region, in dispatches the planner sizes, with progress reports and the
// error estimate at checkpoints.
class RenderLoop {
 public:
  RenderLoop(VulkanContext& context, ProgressiveRenderer& job, const RenderOptions& options,
             const ToneMapping& mapping, const ProgressCallback& onProgress, RenderStats& stats)
      : context_(context),
        job_(job),
        options_(options),
        mapping_(mapping),
        onProgress_(onProgress),
        stats_(stats),
        planner_(job.region().width, job.region().height, options.secondsPerDispatch),
        end_(options.endSample ? options.endSample : options.samplesPerPixel),
        estimating_(options.estimateError || options.targetRmse > 0) {}

  void run() {
    while (job_.samplesDone() < end_) {
      uint32_t samples = planner_.samplesPerPass(samplesToNextStop());
      if (!renderPass(samples)) {
        stats_.stoppedEarly = true;
        break;
      }
      job_.finishPass(samples);
      if (estimating_ && isCheckpoint(samplesDone()) && updateEstimate()) break;
    }
    if (estimating_ && estimatedAt_ != samplesDone()) updateEstimate();
    stats_.rmseEstimate = estimate_;
  }

 private:
  uint32_t samplesDone() const { return job_.samplesDone() - options_.firstSample; }

  static bool isCheckpoint(uint32_t done) {
    return done > 0 && nextRmseCheckpoint(done - 1) == done;
  }

  uint32_t samplesToNextStop() const {
    uint32_t remaining = end_ - job_.samplesDone();
    if (!estimating_) return remaining;
    return std::min(remaining, nextRmseCheckpoint(samplesDone()) - samplesDone());
  }

  // Returns true when the estimate reached the target.
  bool updateEstimate() {
    estimate_ = job_.estimateRmse(mapping_);
    estimatedAt_ = samplesDone();
    report(samplesDone());
    stats_.reachedTarget = options_.targetRmse > 0 && estimate_ &&
                           *estimate_ <= options_.targetRmse &&
                           samplesDone() >= kMinSamplesForTarget;
    return stats_.reachedTarget;
  }

  void report(double done) const {
    if (!onProgress_) return;
    RenderProgress progress{done, end_ - options_.firstSample, secondsSince(start_), estimate_,
                            options_.targetRmse};
    onProgress_(progress);
  }

  // Adds `samples` to every row of the region; false if stopped part way.
  bool renderPass(uint32_t samples) {
    const uint32_t height = job_.region().height;
    for (uint32_t row = 0; row < height;) {
      if (options_.shouldStop && options_.shouldStop()) return false;
      uint32_t rows = std::min(planner_.rowsPerDispatch(samples), height - row);
      auto dispatchStart = Clock::now();
      context_.submitAndWait(
          [&](VkCommandBuffer commands) { job_.recordSamples(commands, row, rows, samples); });
      planner_.record(double(job_.region().width) * rows * samples, secondsSince(dispatchStart));
      ++stats_.dispatches;
      row += rows;
      if (options_.countRays) stats_.raysTraced = job_.raysTraced();
      report(samplesDone() + samples * double(row) / height);
    }
    return true;
  }

  VulkanContext& context_;
  ProgressiveRenderer& job_;
  const RenderOptions& options_;
  ToneMapping mapping_;
  const ProgressCallback& onProgress_;
  RenderStats& stats_;
  DispatchPlanner planner_;
  const uint32_t end_;
  const bool estimating_;
  const Clock::time_point start_ = Clock::now();
  std::optional<double> estimate_;
  uint32_t estimatedAt_ = 0;
};

// An adaptive render's rounds (AdaptiveSampling.hpp): a uniform first pass,
// then after each round the estimate, the stopping test and the next
// round's per-tile sample counts.
class AdaptiveLoop {
 public:
  AdaptiveLoop(VulkanContext& context, ProgressiveRenderer& job, const RenderOptions& options,
               const ToneMapping& mapping, const ProgressCallback& onProgress, RenderStats& stats)
      : context_(context),
        job_(job),
        options_(options),
        mapping_(mapping),
        onProgress_(onProgress),
        stats_(stats),
        planner_(job.region().width, job.region().height, options.secondsPerDispatch),
        plan_(job.width(), job.height(), job.region()),
        budget_(double(options.samplesPerPixel) * double(plan_.regionPixels())) {}

  void run() {
    std::vector<uint32_t> added =
        plan_.uniformRound(std::min(options_.samplesPerPixel, kAdaptiveFirstPass));
    while (std::any_of(added.begin(), added.end(), [](uint32_t n) { return n > 0; })) {
      if (!renderRound(added)) {
        stats_.stoppedEarly = true;
        break;
      }
      plan_.addRound(added);
      SampleSums sums = job_.sampleSums();
      stats_.rmseEstimate = estimateDisplayRmse(sums, mapping_, job_.region());
      report(meanSamples());
      if (reachedTarget()) break;
      AllocationGoal goal;
      goal.targetMse = options_.targetRmse * options_.targetRmse;
      goal.sampleBudget = budget_ - double(plan_.pixelSamples());
      goal.maxSamples = kMaxSamplesPerPixel;
      added = allocateSamples(plan_.measureNoise(sums, mapping_), goal);
    }
  }

 private:
  double meanSamples() const {
    return double(plan_.pixelSamples()) / double(std::max<uint64_t>(plan_.regionPixels(), 1));
  }

  bool reachedTarget() {
    stats_.reachedTarget = options_.targetRmse > 0 && stats_.rmseEstimate &&
                           *stats_.rmseEstimate <= options_.targetRmse;
    return stats_.reachedTarget;
  }

  void report(double done) const {
    if (!onProgress_) return;
    onProgress_(RenderProgress{done, options_.samplesPerPixel, secondsSince(start_),
                               stats_.rmseEstimate, options_.targetRmse});
  }

  // Bands of whole tile rows, each about one dispatch's work; false if
  // stopped part way.
  bool renderRound(const std::vector<uint32_t>& added) {
    job_.setSamplePlan(plan_.kernelRanges(added));
    const PixelRegion& region = job_.region();
    const uint32_t tile = AdaptivePlan::kTileSize;
    const double done = meanSamples();
    uint32_t y = region.y;
    while (y < region.y + region.height) {
      if (options_.shouldStop && options_.shouldStop()) return false;
      double work = 0;
      uint32_t end = y;
      while (end < region.y + region.height && (end == y || work < planner_.workPerDispatch())) {
        uint32_t next = std::min((end / tile + 1) * tile, region.y + region.height);
        work += rowWork(added, end, next);
        end = next;
      }
      auto dispatchStart = Clock::now();
      context_.submitAndWait([&](VkCommandBuffer commands) {
        job_.recordPlannedSamples(commands, y - region.y, end - y);
      });
      if (work > 0) planner_.record(work, secondsSince(dispatchStart));
      ++stats_.dispatches;
      y = end;
      if (options_.countRays) stats_.raysTraced = job_.raysTraced();
      report(done);
    }
    return true;
  }

  // Pixel-samples `added` puts into image rows [y, end) of the region, all
  // in one row of tiles.
  double rowWork(const std::vector<uint32_t>& added, uint32_t y, uint32_t end) const {
    const PixelRegion& region = job_.region();
    const uint32_t tile = AdaptivePlan::kTileSize;
    double work = 0;
    for (uint32_t tx = region.x / tile; tx * tile < region.x + region.width; ++tx) {
      uint32_t x0 = std::max(tx * tile, region.x);
      uint32_t x1 = std::min((tx + 1) * tile, region.x + region.width);
      work += double(added[size_t(y / tile) * plan_.tilesPerRow() + tx]) * (x1 - x0) * (end - y);
    }
    return work;
  }

  VulkanContext& context_;
  ProgressiveRenderer& job_;
  const RenderOptions& options_;
  ToneMapping mapping_;
  const ProgressCallback& onProgress_;
  RenderStats& stats_;
  DispatchPlanner planner_;
  AdaptivePlan plan_;
  const double budget_;
  const Clock::time_point start_ = Clock::now();
};

// Sample counts over the region from the accumulation, and the per-pixel
// error image when asked for.
void finishStats(ProgressiveRenderer& job, const RenderOptions& options, const ToneMapping& mapping,
                 RenderStats& stats) {
  SampleSums sums = job.sampleSums();
  const PixelRegion& region = job.region();
  double total = 0;
  float fewest = std::numeric_limits<float>::max(), most = 0;
  for (uint32_t y = region.y; y < region.y + region.height; ++y) {
    for (uint32_t x = region.x; x < region.x + region.width; ++x) {
      float count = sums.all[size_t(y) * sums.width + x].w;
      total += count;
      fewest = std::min(fewest, count);
      most = std::max(most, count);
    }
  }
  stats.meanSamples = total / (double(region.width) * region.height);
  stats.samplesDone = static_cast<uint32_t>(fewest);
  stats.maxSamples = static_cast<uint32_t>(most);
  if (options.keepErrorImage && job.halvesIndependent()) {
    stats.estimatedError = estimatedErrorImage(sums, mapping);
  }
}

}  // namespace

ImageF Renderer::render(const Scene& scene, const RenderOptions& options,
                        const ProgressCallback& onProgress, RenderStats* stats) {
  RenderStats local;
  RenderStats& s = stats ? *stats : local;
  auto start = Clock::now();
  const uint32_t total = std::max(options.samplesPerPixel, 1u);
  const uint32_t end = options.endSample ? std::min(options.endSample, total) : total;
  if (options.adaptive && (options.firstSample > 0 || end < total)) {
    throw Error(
        "adaptive sampling decides from the whole render's samples: it cannot render "
        "a sample range");
  }
  if (options.firstSample >= end) {
    throw Error(
        fmt::format("empty sample range {}:{} (of {} samples)", options.firstSample, end, total));
  }
  ProgressiveOptions progressive;
  static_cast<ImageSampling&>(progressive) = options;
  progressive.samplesTotal = total;
  progressive.firstSample = options.firstSample;
  progressive.independentHalves =
      options.estimateError || options.targetRmse > 0 || options.adaptive;
  progressive.adaptive = options.adaptive;
  ProgressiveRenderer job(context_, compiler_, scene, progressive);
  s.primitives = job.flatScene().info.primitiveCount;
  s.bvhNodes = job.flatScene().info.bvhNodeCount;
  s.bvhDepth = job.flatScene().bvhDepth;
  s.warnings = job.flatScene().warnings;
  s.features = job.features();
  s.setupSeconds = secondsSince(start);

  RenderOptions clamped = options;
  clamped.samplesPerPixel = total;
  clamped.endSample = end;
  auto renderStart = Clock::now();
  double cpuStart = processCpuSeconds();
  const ToneMapping mapping = options.displayMapping.value_or(toneMappingFor(scene));
  if (options.adaptive) {
    AdaptiveLoop(context_, job, clamped, mapping, onProgress, s).run();
  } else {
    RenderLoop(context_, job, clamped, mapping, onProgress, s).run();
  }
  s.renderSeconds = secondsSince(renderStart);
  s.renderCpuSeconds = processCpuSeconds() - cpuStart;
  finishStats(job, options, mapping, s);
  return job.resolve();
}

}  // namespace rt
