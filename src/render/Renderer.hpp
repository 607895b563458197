// Renders a scene into a float image: flattens and uploads it, compiles the
// render kernel for the scene's features, and accumulates samples over many
// short dispatches (none runs long, so a display GPU stays responsive and
// progress can be reported).
#pragma once

#include <cstdint>
#include <functional>

#include "io/Image.hpp"
#include "render/Features.hpp"
#include "scene/Scene.hpp"

namespace rt {

class ShaderCompiler;
class VulkanContext;

struct RenderOptions {
  uint32_t width = 0;  // 0: the scene camera's size
  uint32_t height = 0;
  uint32_t samplesPerPixel = 16;
  uint32_t seed = 0;
  SamplerKind sampler = SamplerKind::Jittered;
  double secondsPerDispatch = 0.1;  // target duration of one dispatch
};

struct RenderProgress {
  double samplesDone = 0;  // per pixel, fractional while a pass is under way
  uint32_t samplesTotal = 0;
  double elapsedSeconds = 0;
};

struct RenderStats {
  double compileSeconds = 0;
  double uploadSeconds = 0;
  double renderSeconds = 0;  // dispatches only
  uint32_t dispatches = 0;
  uint32_t primitives = 0;
  uint32_t bvhNodes = 0;
  uint32_t bvhDepth = 0;
  ShaderFeatures features;
};

using ProgressCallback = std::function<void(const RenderProgress&)>;

class Renderer {
 public:
  Renderer(VulkanContext& context, const ShaderCompiler& compiler);

  // Returns the per-pixel mean radiance (alpha = 1).
  ImageF render(const Scene& scene, const RenderOptions& options,
                const ProgressCallback& onProgress = {}, RenderStats* stats = nullptr);

 private:
  VulkanContext& context_;
  const ShaderCompiler& compiler_;
};

}  // namespace rt
