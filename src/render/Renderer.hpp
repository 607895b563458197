// Renders a scene into a float image: flattens and uploads it, compiles the
// render kernel for the scene's features, and accumulates samples over many
// short dispatches (none runs long, so a display GPU stays responsive and
// progress can be reported).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "encode/Conventions.hpp"
#include "encode/Features.hpp"
#include "imaging/PixelRegion.hpp"
#include "io/Image.hpp"
#include "render/ImageSampling.hpp"
#include "scene/Scene.hpp"

namespace rt {

class ShaderCompiler;
class VulkanContext;

struct RenderOptions : ImageSampling {
  uint32_t samplesPerPixel = 16;  // the whole render's count (jittered strata)
  // Renders only sample indices [first, end) of the samplesPerPixel: pieces of
  // one render can run on several machines and be merged (`raytracer merge`).
  uint32_t firstSample = 0;
  uint32_t endSample = 0;  // 0: samplesPerPixel
  // Error estimate (ImageError.hpp): computed at checkpoints of the sample
  // count (nextRmseCheckpoint) and at the end, in the display space of
  // `displayMapping` (default: toneMappingFor(scene)). It renders even and
  // odd samples as independent replicates (RT_SAMPLER_REPLICATES), which
  // makes jittered and Sobol images noisier than without. A positive target
  // also ends the render at the first checkpoint whose estimate is <= the
  // target (never before kMinSamplesForTarget samples); the sample budget
  // and shouldStop still apply, whichever comes first.
  bool estimateError = false;
  double targetRmse = 0;
  // Adaptive sampling (render/AdaptiveSampling.hpp): after a first pass of
  // 1.25 samples a pixel (one, and one more on two 4x2 blocks of every 8x8
  // tile), rounds give more samples to the noisiest tiles. samplesPerPixel
  // is then the budget of the mean count per pixel, targetRmse (if any) the
  // goal; the estimate is always made. Cannot be combined with sample
  // ranges (firstSample/endSample).
  bool adaptive = false;
  // Adaptive renders without a budget of their own (a time budget alone):
  // samplesPerPixel is the first stage's budget, which doubles each time it
  // is spent, until shouldStop (AdaptiveRounds::Goal::openEnded).
  bool openEndedBudget = false;
  // Fill RenderStats::estimatedError (needs estimateError or adaptive).
  bool keepErrorImage = false;
  double secondsPerDispatch = 0.1;  // target duration of one dispatch
  // Target duration of one pass over the image (a pass is one or more
  // dispatches; the render loops in Renderer.cpp).
  double secondsPerPass = 1.0;
  // The most samples one pass over the image adds (passes double from 1 up
  // to this once they take secondsPerPass). 1 keeps every pixel within one
  // sample of the others whenever shouldStop ends the render (--time).
  uint32_t maxPassSamples = 16;
  // Polled between dispatches; returning true ends the render early with
  // the samples accumulated so far (SIGINT, time budgets), once every pixel
  // has a sample: a stopped render's image is never empty.
  std::function<bool()> shouldStop;
};

struct RenderProgress {
  double samplesDone = 0;  // per pixel, fractional while a pass is under way
  uint32_t samplesTotal = 0;
  double elapsedSeconds = 0;
  std::optional<double> rmseEstimate;  // the latest, with RenderOptions::estimateError
  double targetRmse = 0;               // RenderOptions::targetRmse
};

// The sample counts (counted from RenderOptions::firstSample) at which the
// error is estimated: 8 * 2^(k/4) rounded, so a render stopped by
// --target-rmse has at most ~19% more samples than it needed, the stopping
// point does not depend on timing, and estimates cost little.
uint32_t nextRmseCheckpoint(uint32_t samplesDone);
constexpr uint32_t kMinSamplesForTarget = 8;

struct RenderStats {
  double setupSeconds = 0;   // flatten, BVH build, upload, shader compile
  double renderSeconds = 0;  // dispatches only
  // CPU time of this process over the same span (all threads): the work a
  // CPU Vulkan device (lavapipe) did, unaffected by other processes.
  double renderCpuSeconds = 0;
  uint32_t dispatches = 0;
  uint64_t raysTraced = 0;     // only with RenderOptions::countRays
  uint32_t samplesDone = 0;    // full passes completed (per pixel): the fewest any pixel has
  double meanSamples = 0;      // per pixel of the region (adaptive: varies)
  uint32_t maxSamples = 0;     // the most any pixel of the region got
  bool stoppedEarly = false;   // by shouldStop
  bool reachedTarget = false;  // ended by RenderOptions::targetRmse
  std::optional<double> rmseEstimate;  // at the end, with RenderOptions::estimateError
  // Per-pixel estimated display RMSE (estimatedErrorImage), row-major; with
  // RenderOptions::keepErrorImage.
  std::vector<float> estimatedError;
  uint32_t primitives = 0;
  uint32_t bvhNodes = 0;
  uint32_t bvhDepth = 0;
  ShaderFeatures features;
  std::vector<std::string> warnings;
};

using ProgressCallback = std::function<void(const RenderProgress&)>;

class Renderer {
 public:
  Renderer(VulkanContext& context, const ShaderCompiler& compiler);

  // Returns the per-pixel mean radiance; alpha holds each pixel's sample count.
  ImageF render(const Scene& scene, const RenderOptions& options,
                const ProgressCallback& onProgress = {}, RenderStats* stats = nullptr);

 private:
  VulkanContext& context_;
  const ShaderCompiler& compiler_;
};

}  // namespace rt
