#include "render/Renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "encode/FlatScene.hpp"
#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "imaging/ImageError.hpp"
#include "render/AdaptiveSampling.hpp"
#include "render/ProgressiveRenderer.hpp"
#include "scene/Limits.hpp"
#include "util/Clock.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

using Clock = SteadyClock;

// Sizes passes and dispatches from the measured cost of one pixel-sample:
// a pass over the image of about `passTarget` seconds, in dispatches of
// about `dispatchTarget` seconds (bands of rows, or several samples over
// the whole image when that is cheap).
class DispatchPlanner {
 public:
  DispatchPlanner(uint32_t width, uint32_t height, double dispatchTarget, double passTarget,
                  uint32_t maxPassSamples)
      : width_(width),
        height_(height),
        dispatchTarget_(dispatchTarget),
        passTarget_(passTarget),
        maxPassSamples_(maxPassSamples) {}

  // Samples of the next pass over the image, which has `done` so far. An
  // invocation that adds several samples to its pixel pays its set-up
  // (the accumulation's load and store, the pixel's sampler keys) once: on
  // lavapipe 16 samples a pass rendered the common scene 1.3x faster than
  // one, and passes of about a second rather than a dispatch's tenth 1.02-
  // 1.04x. After those, passes double (at most maxPassSamples), so that a
  // long render stopped part way holds at least half of its samples in
  // every pixel.
  uint32_t samplesPerPass(uint32_t remaining, uint32_t done) const {
    const uint32_t cap = std::max(maxPassSamples_, 1u);
    uint32_t doubling = std::clamp<uint32_t>(done, 1, cap);
    double pixels = double(width_) * height_;
    double affordable = costPerPixelSample_ > 0 ? passTarget_ / costPerPixelSample_ / pixels : 0.0;
    uint32_t samples = std::max(doubling, static_cast<uint32_t>(std::min(affordable, 1e9)));
    return std::clamp<uint32_t>(samples, 1, std::min(remaining, cap));
  }

  // Whole rows of the kernel's 8x8 workgroups: a band that ends inside one
  // leaves the lanes of its last rows idle in SIMD vectors that still run
  // (each run of eight invocations renders a 4x2 block), once per band.
  uint32_t rowsPerDispatch(uint32_t samples) const {
    // Before any measurement, a first band of about 16k pixels finds the cost.
    double rows = workPerDispatch() / (double(width_) * samples);
    const uint32_t groupRows = RT_WORKGROUP_SIZE_Y;
    uint32_t groups = static_cast<uint32_t>(std::min(rows, double(height_))) / groupRows;
    return std::max(groups, 1u) * groupRows;
  }

  // Pixel-samples one dispatch should add.
  double workPerDispatch() const {
    return costPerPixelSample_ > 0 ? dispatchTarget_ / costPerPixelSample_ : 16384.0;
  }

  void record(double pixelSamples, double seconds) {
    double cost = seconds / pixelSamples;
    // Smooth, but let the first measurement count fully.
    costPerPixelSample_ = costPerPixelSample_ > 0 ? 0.5 * (costPerPixelSample_ + cost) : cost;
  }

 private:
  uint32_t width_;
  uint32_t height_;
  double dispatchTarget_;
  double passTarget_;
  uint32_t maxPassSamples_;
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

// What both sample loops share: the job, the options, progress reports and
// dispatches timed for the planner.
class SampleLoop {
 protected:
  SampleLoop(VulkanContext& context, ProgressiveRenderer& job, const RenderOptions& options,
             const ToneMapping& mapping, const ProgressCallback& onProgress, RenderStats& stats)
      : context_(context),
        job_(job),
        options_(options),
        mapping_(mapping),
        onProgress_(onProgress),
        stats_(stats),
        planner_(job.region().width, job.region().height, options.secondsPerDispatch,
                 options.secondsPerPass, options.maxPassSamples) {}

  // A stop counts once every pixel has a sample (the first pass or round):
  // a render stopped while it is set up or in its first pass (a --time
  // budget spent on compiling kernels) still writes an image, never an
  // empty one. shouldStop is asked all the same.
  bool stopRequested() const {
    bool asked = options_.shouldStop && options_.shouldStop();
    return asked && everyPixelSampled_;
  }

  void report(double done, uint32_t total, std::optional<double> estimate) const {
    if (!onProgress_) return;
    onProgress_(RenderProgress{done, total, secondsSince(start_), estimate, options_.targetRmse});
  }

  // Submits one dispatch and waits; its time, per `pixelSamples`, sizes the
  // next ones.
  template <typename Record>
  void dispatch(Record record, double pixelSamples) {
    auto dispatchStart = Clock::now();
    context_.submitAndWait(record);
    if (pixelSamples > 0) planner_.record(pixelSamples, secondsSince(dispatchStart));
    ++stats_.dispatches;
    if (options_.countRays) stats_.raysTraced = job_.raysTraced();
  }

  VulkanContext& context_;
  ProgressiveRenderer& job_;
  const RenderOptions& options_;
  ToneMapping mapping_;
  const ProgressCallback& onProgress_;
  RenderStats& stats_;
  DispatchPlanner planner_;
  const Clock::time_point start_ = Clock::now();
  bool everyPixelSampled_ = false;  // set by the loops after their first pass or round
};

// One render's sample loop: passes of a few samples over every row of the
// region, in dispatches the planner sizes, with progress reports and the
// error estimate at checkpoints.
class RenderLoop : SampleLoop {
 public:
  RenderLoop(VulkanContext& context, ProgressiveRenderer& job, const RenderOptions& options,
             const ToneMapping& mapping, const ProgressCallback& onProgress, RenderStats& stats)
      : SampleLoop(context, job, options, mapping, onProgress, stats),
        end_(options.endSample ? options.endSample : options.samplesPerPixel),
        estimating_(options.estimateError || options.targetRmse > 0) {}

  void run() {
    while (job_.samplesDone() < end_) {
      uint32_t samples = planner_.samplesPerPass(samplesToNextStop(), samplesDone());
      if (!renderPass(samples)) {
        stats_.stoppedEarly = true;
        break;
      }
      job_.finishPass(samples);
      everyPixelSampled_ = true;
      if (estimating_ && isCheckpoint(samplesDone()) && updateEstimate()) break;
    }
    if (estimating_ && estimatedAt_ != samplesDone()) updateEstimate();
    stats_.rmseEstimate = estimate_;
  }

 private:
  uint32_t samplesDone() const { return job_.samplesDone() - options_.firstSample; }
  uint32_t samplesWanted() const { return end_ - options_.firstSample; }

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
    report(samplesDone(), samplesWanted(), estimate_);
    stats_.reachedTarget = options_.targetRmse > 0 && estimate_ &&
                           *estimate_ <= options_.targetRmse &&
                           samplesDone() >= kMinSamplesForTarget;
    return stats_.reachedTarget;
  }

  // Adds `samples` to every row of the region; false if stopped part way.
  bool renderPass(uint32_t samples) {
    const uint32_t height = job_.region().height;
    for (uint32_t row = 0; row < height;) {
      if (stopRequested()) return false;
      uint32_t rows = std::min(planner_.rowsPerDispatch(samples), height - row);
      dispatch([&](VkCommandBuffer commands) { job_.recordSamples(commands, row, rows, samples); },
               double(job_.region().width) * rows * samples);
      row += rows;
      report(samplesDone() + samples * double(row) / height, samplesWanted(), estimate_);
    }
    return true;
  }

  const uint32_t end_;
  const bool estimating_;
  std::optional<double> estimate_;
  uint32_t estimatedAt_ = 0;
};

// An adaptive render (AdaptiveSampling.hpp): each round in bands of whole
// tile rows, each about one dispatch's work.
class AdaptiveLoop : SampleLoop {
 public:
  AdaptiveLoop(VulkanContext& context, ProgressiveRenderer& job, const RenderOptions& options,
               const ToneMapping& mapping, const ProgressCallback& onProgress, RenderStats& stats)
      : SampleLoop(context, job, options, mapping, onProgress, stats),
        rounds_(job.width(), job.height(), job.region(),
                {options.samplesPerPixel, options.targetRmse, kMaxSamplesPerPixel,
                 options.openEndedBudget}) {}

  void run() {
    while (!rounds_.finished()) {
      if (!renderRound()) {
        stats_.stoppedEarly = true;
        // The estimate and the error layer from the samples the stop left.
        job_.stopAdaptiveRound(rounds_, mapping_);
        stats_.rmseEstimate = rounds_.rmseEstimate();
        stats_.reachedTarget = rounds_.reachedTarget();
        return;
      }
      job_.finishAdaptiveRound(rounds_, mapping_);
      everyPixelSampled_ = true;
      stats_.rmseEstimate = rounds_.rmseEstimate();
      stats_.reachedTarget = rounds_.reachedTarget();
      report(rounds_.meanSamples(), options_.samplesPerPixel, stats_.rmseEstimate);
    }
  }

  const AdaptiveRounds& rounds() const { return rounds_; }

 private:
  // False if stopped part way.
  bool renderRound() {
    job_.setSamplePlan(rounds_.kernelRanges(), rounds_.pixelExtras());
    const PixelRegion& region = job_.region();
    for (uint32_t y = region.y; y < region.y + region.height;) {
      if (stopRequested()) return false;
      uint32_t end = rounds_.bandEnd(y, planner_.workPerDispatch());
      dispatch(
          [&](VkCommandBuffer commands) {
            job_.recordPlannedSamples(commands, y - region.y, end - y);
          },
          rounds_.rowWork(y, end));
      y = end;
      report(rounds_.meanSamples(), options_.samplesPerPixel, stats_.rmseEstimate);
    }
    return true;
  }

  AdaptiveRounds rounds_;
};

// Sample counts over the region from the accumulation, and the per-pixel
// error image when asked for (`adaptive`: the rounds of an adaptive render,
// whose pixels of one sample take their tile's noise).
void finishStats(ProgressiveRenderer& job, const RenderOptions& options, const ToneMapping& mapping,
                 const AdaptiveRounds* adaptive, RenderStats& stats) {
  const bool uniform = !options.adaptive && !stats.stoppedEarly;
  if (uniform && !options.keepErrorImage) {
    // Every pixel got every pass: no need to read the counts back.
    stats.samplesDone = job.samplesDone() - options.firstSample;
    stats.meanSamples = stats.samplesDone;
    stats.maxSamples = stats.samplesDone;
    return;
  }
  const SampleSums sums = job.sampleSums();
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
    stats.estimatedError =
        adaptive ? adaptive->errorImage(sums, mapping) : estimatedErrorImage(sums, mapping);
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
  // The error image of a random-sampler render needs them too (its halves
  // are always independent).
  progressive.oddSums = progressive.independentHalves || options.keepErrorImage;
  ProgressiveRenderer job(context_, compiler_, scene, progressive);
  s.primitives = job.flatScene().info.primitiveCount;
  s.bvhNodes = job.flatScene().info.bvhNodeCount;
  s.bvhDepth = job.flatScene().bvhDepth;
  s.warnings = job.warnings();
  s.features = job.features();
  s.setupSeconds = secondsSince(start);

  RenderOptions clamped = options;
  clamped.samplesPerPixel = total;
  clamped.endSample = end;
  auto renderStart = Clock::now();
  double cpuStart = processCpuSeconds();
  const ToneMapping mapping = options.displayMapping.value_or(toneMappingFor(scene));
  std::optional<AdaptiveLoop> adaptive;
  if (options.adaptive) {
    adaptive.emplace(context_, job, clamped, mapping, onProgress, s);
    adaptive->run();
  } else {
    RenderLoop(context_, job, clamped, mapping, onProgress, s).run();
  }
  s.renderSeconds = secondsSince(renderStart);
  s.renderCpuSeconds = processCpuSeconds() - cpuStart;
  finishStats(job, options, mapping, adaptive ? &adaptive->rounds() : nullptr, s);
  return job.resolve();
}

}  // namespace rt
