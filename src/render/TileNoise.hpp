// The noise of the replicate sums measured on the device: for every tile of
// RT_ADAPTIVE_TILE_SIZE^2 pixels, the sums of its pixels' estimated squared
// errors (shaders/tile_noise.comp, noise_types.h). Adaptive sampling plans
// its rounds from them and the --target-rmse checkpoints read the image's
// estimate from them, so neither reads the accumulation buffers back (at
// 1920x1080 that was 66 MB and 2 million pixels measured on the CPU a round:
// about 0.25 s on the H200's host, where a round renders in milliseconds).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "gpu/Buffer.hpp"
#include "gpu/ComputeKernel.hpp"
#include "imaging/PixelRegion.hpp"
#include "io/Image.hpp"
#include "noise_types.h"

namespace rt {

class ShaderCompiler;
class VulkanContext;

class TileNoiseKernel {
 public:
  // For accumulation buffers of width x height pixels.
  TileNoiseKernel(VulkanContext& context, const ShaderCompiler& compiler, uint32_t width,
                  uint32_t height);

  // Per tile, row-major over the whole image, the sums over its pixels in
  // `region` (resolved) of the sums in `all` and `odd` (one vec4 per
  // pixel); `pixelExtras` (one uint per pixel, or null): the edge round's
  // samples, whose pixels are measured apart. `changedTiles` (or null: all
  // of them): the only tiles whose sums changed since the previous call,
  // which the caller vouches for; the others keep that call's figures where
  // it measured the same buffers with the same region and mapping, and are
  // measured again where it did not. Submits and waits: no dispatch may be in flight
  // on the buffers.
  std::vector<gpu::GpuTileNoise> measure(const Buffer& all, const Buffer& odd,
                                         const Buffer* pixelExtras, const PixelRegion& region,
                                         const ToneMapping& mapping,
                                         const std::vector<uint32_t>* changedTiles = nullptr);

 private:
  VulkanContext& context_;
  uint32_t width_;
  uint32_t height_;
  uint32_t tileCount_;  // gpu::adaptiveTileGrid's, row-major
  ComputeKernel kernel_;
  Buffer tiles_;
  Buffer noExtras_;  // bound when there are no pixel extras (never read then)
  Buffer tileList_;  // the changed tiles of a listed measurement
  // What tiles_ holds every tile's figures for: the parameters (listedTiles
  // 0) and the buffers measured.
  struct Measured {
    gpu::GpuTileNoiseParams params;
    std::array<VkBuffer, 3> buffers;  // all, odd, pixel extras (or none)
  };
  std::optional<Measured> measuredWith_;

  // Uploads `changedTiles` and sets params.listedTiles where they may stand
  // for every tile (the last measurement was `measuring`'s), else 0; records
  // `measuring` as the last. Returns the invocations to dispatch.
  uint32_t listTiles(const Measured& measuring, const std::vector<uint32_t>* changedTiles,
                     gpu::GpuTileNoiseParams& params);
};

// The image's estimated RMSE (estimateDisplayRmse's figure) from its tiles,
// `pixels` the measured region's: nullopt unless every pixel has both halves.
std::optional<double> estimatedRmse(const std::vector<gpu::GpuTileNoise>& tiles, uint64_t pixels);

}  // namespace rt
