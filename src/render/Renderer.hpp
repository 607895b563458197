// Renders a scene into a float image: flattens and uploads it, compiles the
// render kernel for the scene's features, and accumulates samples over many
// short dispatches (none runs long, so a display GPU stays responsive and
// progress can be reported).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "io/Image.hpp"
#include "render/Conventions.hpp"
#include "render/Features.hpp"
#include "scene/Scene.hpp"

namespace rt {

class ShaderCompiler;
class VulkanContext;

struct RenderOptions {
  uint32_t width = 0;  // 0: the scene camera's size
  uint32_t height = 0;
  uint32_t samplesPerPixel = 16;  // the whole render's count (jittered strata)
  // Renders only sample indices [first, end) of the samplesPerPixel: pieces of
  // one render can run on several machines and be merged (`raytracer merge`).
  uint32_t firstSample = 0;
  uint32_t endSample = 0;  // 0: samplesPerPixel
  uint32_t seed = 0;
  SamplerKind sampler = SamplerKind::Jittered;
  std::optional<ShadingModel> shading;  // default: the scene family's
  double secondsPerDispatch = 0.1;      // target duration of one dispatch
  bool countRays = false;               // compile in a ray counter (benchmarks)
  AccelKind accel = AccelKind::Bvh;     // none: brute force, to compare against
  // Polled between dispatches; returning true ends the render early with
  // the samples accumulated so far (SIGINT, time budgets).
  std::function<bool()> shouldStop;
};

struct RenderProgress {
  double samplesDone = 0;  // per pixel, fractional while a pass is under way
  uint32_t samplesTotal = 0;
  double elapsedSeconds = 0;
};

struct RenderStats {
  double setupSeconds = 0;   // flatten, BVH build, upload, shader compile
  double renderSeconds = 0;  // dispatches only
  uint32_t dispatches = 0;
  uint64_t raysTraced = 0;  // only with RenderOptions::countRays
  uint32_t samplesDone = 0;  // full passes completed (per pixel)
  bool stoppedEarly = false;
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
