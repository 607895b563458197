// Progressive accumulation of one scene: the render kernel, the scene
// buffers and a float32 accumulation buffer, advanced a few samples at a time.
// The offline Renderer drives it in a loop; the interactive viewer records
// its dispatches into frame command buffers, moves the camera and reloads
// shaders between frames.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "encode/Features.hpp"
#include "encode/FlatScene.hpp"
#include "encode/SceneBuffers.hpp"
#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "gpu_types.h"
#include "imaging/ImageError.hpp"
#include "imaging/PixelRegion.hpp"
#include "io/Image.hpp"
#include "render/ImageSampling.hpp"
#include "render/TileNoise.hpp"
#include "scene/Scene.hpp"

namespace rt {

class AdaptiveRounds;
class ShaderCompiler;
class VulkanContext;

struct ProgressiveOptions : ImageSampling {
  uint32_t samplesTotal = 0;  // samples the render aims for: strata of the jittered sampler
  uint32_t firstSample = 0;   // index of the first sample added (split renders)
  // Even and odd samples as two independent replicates (RT_SAMPLER_REPLICATES),
  // which the error estimate needs; it costs stratified samplers accuracy.
  bool independentHalves = false;
  // Keep the sums of the odd samples, which every error estimate reads
  // (estimateRmse, tileNoise, the error image of sampleSums). Without them
  // the kernel neither loads nor stores them and halvesIndependent() is false.
  bool oddSums = true;
  // Per-tile sample ranges (setSamplePlan, recordPlannedSamples) instead of
  // one range for every pixel: adaptive sampling (render/AdaptiveSampling.hpp).
  bool adaptive = false;
};

// Whether render kernels on this device take their pixels from a work queue
// (ShaderFeatures::workQueue, WorkQueue::OnCpu): CPU devices with subgroup
// ballots, lavapipe from Mesa 25 on.
bool workQueueAvailable(const VulkanContext& context);

// Whether the BVH walk votes before writing its stack's array
// (ShaderFeatures::laneVotes): devices with subgroup votes, lavapipe from
// Mesa 25 on.
bool laneVotesPay(const VulkanContext& context);

class ProgressiveRenderer {
 public:
  ProgressiveRenderer(VulkanContext& context, const ShaderCompiler& compiler, const Scene& scene,
                      const ProgressiveOptions& options);

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t samplesDone() const { return samplesDone_; }
  const FlatScene& flatScene() const { return flat_; }
  const ShaderFeatures& features() const { return features_; }
  // What the render leaves out or reads differently: the flat scene's
  // warnings, then the device's (scene arrays it misreads).
  const std::vector<std::string>& warnings() const { return warnings_; }

  // The rendered pixels (the whole image unless ProgressiveOptions::region).
  const PixelRegion& region() const { return region_; }

  // Records a dispatch adding `count` samples per pixel to rows [row, row + rows)
  // of the region (row 0: its top row), starting at sample index samplesDone().
  // Call finishPass(count) once every row got them.
  void recordSamples(VkCommandBuffer commands, uint32_t row, uint32_t rows, uint32_t count) const;
  void finishPass(uint32_t count) { samplesDone_ += count; }
  // recordSamples over the whole image, submitted and waited for.
  void addSamples(uint32_t count);

  // Adaptive kernels only: per tile of RT_ADAPTIVE_TILE_SIZE^2 pixels (row-
  // major over the image), the first sample index and the count the next
  // planned dispatches add, and (when not empty) every pixel's edge samples
  // (AdaptiveRounds::pixelExtras). recordPlannedSamples records them for rows
  // [row, row + rows) of the region.
  void setSamplePlan(const std::vector<glm::uvec2>& ranges,
                     const std::vector<uint32_t>& pixelExtras = {});
  void recordPlannedSamples(VkCommandBuffer commands, uint32_t row, uint32_t rows) const;

  // Back to zero samples (e.g. after a camera move).
  void recordReset(VkCommandBuffer commands);
  void reset();

  // New camera: uploads the scene constants and resets. No dispatch may be in flight.
  void setCamera(const Camera& camera);

  // Recompiles the render kernel (and the noise kernel, when the render has
  // one) from the shader files. On a compile or pipeline error it throws and
  // the current kernels stay; on success the old render kernel is kept until
  // releaseRetiredKernels(), to be called once no frame uses it.
  void reloadShaders();
  void releaseRetiredKernels() { retired_.clear(); }

  const Buffer& accumulation() const { return accumulation_; }
  // Descriptor bindings of the render kernel (trace.comp).
  static std::vector<KernelBinding> kernelBindings(const ShaderFeatures& features,
                                                   AccelKind accel = AccelKind::Bvh);
  // Mean radiance per pixel; alpha = the pixel's sample count.
  ImageF resolve();
  // The accumulation sums of all and of the odd-indexed samples.
  SampleSums sampleSums();
  // estimateDisplayRmse over the region, from the samples so far (measured
  // on the device); nullopt unless the halves are independent
  // (independentHalves, or the random sampler, whose samples always are).
  std::optional<double> estimateRmse(const ToneMapping& mapping);
  // Per tile (row-major over the image) the noise of the region's pixels so
  // far, measured on the device (TileNoiseKernel); needs halvesIndependent().
  // In an adaptive render the pixels with edge-round samples (pixel extras)
  // are measured apart. No dispatch may be in flight.
  std::vector<gpu::GpuTileNoise> tileNoise(const ToneMapping& mapping);
  bool halvesIndependent() const;
  // Adaptive kernels only: per tile, the rays traced since the last call (or
  // reset). No dispatch may be in flight.
  std::vector<uint32_t> takeTileRays();
  // Adaptive renders (AdaptiveSampling.hpp): measures the round just
  // rendered (the tiles' noise, the edge round's pixels apart once it has
  // run; the rays it traced; after the first round the image, for the edge
  // round) and has `rounds` plan the next. No dispatch may be in flight.
  void finishAdaptiveRound(AdaptiveRounds& rounds, const ToneMapping& mapping);
  // The render stopped inside a round: `rounds` measures the samples it has.
  void stopAdaptiveRound(AdaptiveRounds& rounds, const ToneMapping& mapping);
  // Rays traced so far (only with ProgressiveOptions::countRays).
  uint64_t raysTraced();

 private:
  std::unique_ptr<ComputeKernel> buildKernel() const;
  // tileNoise, where `roundTiles` (or null) are the tiles an adaptive round
  // just sampled: the only ones measured again when nothing else changed.
  std::vector<gpu::GpuTileNoise> measureTiles(const ToneMapping& mapping,
                                              const std::vector<uint32_t>* roundTiles);
  void recordRange(VkCommandBuffer commands, uint32_t row, uint32_t rows, uint32_t first,
                   uint32_t count) const;

  VulkanContext& context_;
  const ShaderCompiler& compiler_;
  ProgressiveOptions options_;
  FlatScene flat_;
  ShaderFeatures features_;
  std::vector<std::string> warnings_;
  uint32_t width_;
  uint32_t height_;
  SceneBuffers sceneBuffers_;
  PixelRegion region_;
  Buffer accumulation_;
  // Sums of odd sample indices, for the error estimate (ProgressiveOptions::oddSums).
  std::optional<Buffer> oddAccumulation_;
  std::optional<Buffer> rayCounter_;
  std::optional<Buffer> workQueue_;     // runs of pixels taken (ShaderFeatures::workQueue)
  std::optional<Buffer> samplePlan_;    // adaptive only
  std::optional<Buffer> tileRays_;      // adaptive only: running counters
  std::vector<uint32_t> tileRaysRead_;  // the counters at the last takeTileRays()
  std::optional<Buffer> pixelExtras_;   // adaptive only: the edge round's counts
  std::unique_ptr<ComputeKernel> kernel_;
  std::vector<std::unique_ptr<ComputeKernel>> retired_;
  std::unique_ptr<TileNoiseKernel> tileNoise_;  // for halvesIndependent() renders
  // The accumulation was reset since the tiles' noise was last measured: the
  // next measurement covers every tile, not only a round's. Nothing else
  // changes the sums between an adaptive render's measurements (its kernel
  // renders no uniform passes: recordSamples refuses them).
  bool resetSinceMeasured_ = true;
  uint32_t samplesDone_ = 0;
  uint64_t raysTraced_ = 0;
};

}  // namespace rt
