#include "render/TileNoise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Arithmetic.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

constexpr std::array<uint32_t, 5> kBindings{
    RT_NOISE_BINDING_ACCUMULATION, RT_NOISE_BINDING_ACCUMULATION_ODD, RT_NOISE_BINDING_TILES,
    RT_NOISE_BINDING_PIXEL_EXTRAS, RT_NOISE_BINDING_TILE_LIST};

uint32_t tileCount(uint32_t width, uint32_t height) {
  const glm::uvec2 grid = gpu::adaptiveTileGrid({width, height});
  return grid.x * grid.y;
}

bool sameParams(const gpu::GpuTileNoiseParams& a, const gpu::GpuTileNoiseParams& b) {
  // Every field is set (the padding to zero), so the bytes compare the values.
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}

}  // namespace

TileNoiseKernel::TileNoiseKernel(VulkanContext& context, const ShaderCompiler& compiler,
                                 uint32_t width, uint32_t height)
    : context_(context),
      width_(width),
      height_(height),
      tileCount_(tileCount(width, height)),
      kernel_(context, compiler.compile("tile_noise.comp", {}),
              std::vector<uint32_t>(kBindings.begin(), kBindings.end()),
              sizeof(gpu::GpuTileNoiseParams)),
      tiles_(context, VkDeviceSize(tileCount_) * sizeof(gpu::GpuTileNoise),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
      noExtras_(context, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
      tileList_(context, VkDeviceSize(std::max(tileCount_, 1u)) * sizeof(uint32_t),
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
  // Compiled now rather than at the first measurement: over an image of no
  // tiles the kernel reads and writes nothing, so its bindings only need to
  // be valid.
  for (uint32_t binding : kBindings) kernel_.bind(binding, tiles_);
  const gpu::GpuTileNoiseParams noTiles{};
  kernel_.compileNow(&noTiles);
}

std::vector<gpu::GpuTileNoise> TileNoiseKernel::measure(const Buffer& all, const Buffer& odd,
                                                        const Buffer* pixelExtras,
                                                        const PixelRegion& region,
                                                        const ToneMapping& mapping,
                                                        const std::vector<uint32_t>* changedTiles) {
  const PixelRegion r = resolveRegion(region, width_, height_);
  gpu::GpuTileNoiseParams params{};
  params.size = {width_, height_};
  params.regionStart = {r.x, r.y};
  params.regionEnd = {r.x + r.width, r.y + r.height};
  params.exposure = mapping.exposure;
  params.toneCurve = static_cast<uint32_t>(mapping.curve);
  params.srgbEncode = mapping.srgbEncode ? 1u : 0u;
  params.hasPixelExtras = pixelExtras ? 1u : 0u;
  const Measured measuring{
      params, {all.handle(), odd.handle(), pixelExtras ? pixelExtras->handle() : VK_NULL_HANDLE}};
  const uint32_t invocations = listTiles(measuring, changedTiles, params);
  kernel_.bind(RT_NOISE_BINDING_ACCUMULATION, all);
  kernel_.bind(RT_NOISE_BINDING_ACCUMULATION_ODD, odd);
  kernel_.bind(RT_NOISE_BINDING_TILES, tiles_);
  kernel_.bind(RT_NOISE_BINDING_PIXEL_EXTRAS, pixelExtras ? *pixelExtras : noExtras_);
  kernel_.bind(RT_NOISE_BINDING_TILE_LIST, tileList_);
  if (invocations > 0) {
    context_.submitAndWait([&](VkCommandBuffer commands) {
      kernel_.recordDispatch(commands, &params,
                             divideRoundUp(invocations, RT_NOISE_WORKGROUP_SIZE));
    });
  }
  std::vector<gpu::GpuTileNoise> tiles(tileCount_);
  tiles_.download(tiles.data(), tiles.size() * sizeof(gpu::GpuTileNoise));
  return tiles;
}

uint32_t TileNoiseKernel::listTiles(const Measured& measuring,
                                    const std::vector<uint32_t>* changedTiles,
                                    gpu::GpuTileNoiseParams& params) {
  // Only the changed tiles where the others' figures are those of the same
  // parameters and buffers: an adaptive round after the first samples few
  // tiles (the thin-lens study's third round at 320x240 about 10%), and
  // measuring them all cost about 30 ns of CPU time a pixel on lavapipe, a
  // sixth of one of its samples, every round (bench/README.md).
  const bool listed = changedTiles && measuredWith_ &&
                      sameParams(measuring.params, measuredWith_->params) &&
                      measuring.buffers == measuredWith_->buffers;
  measuredWith_ = measuring;
  params.listedTiles = 0;
  if (!listed) return tileCount_;
  const auto count = static_cast<uint32_t>(changedTiles->size());
  if (count > tileCount_) throw Error("tile noise: more changed tiles than tiles");
  if (count > 0) tileList_.upload(changedTiles->data(), count * sizeof(uint32_t));
  params.listedTiles = count;
  return count;
}

std::optional<double> estimatedRmse(const std::vector<gpu::GpuTileNoise>& tiles, uint64_t pixels) {
  double squared = 0;
  uint64_t measured = 0;
  for (const gpu::GpuTileNoise& tile : tiles) {
    squared += tile.squaredSum;
    measured += tile.measured;
  }
  if (pixels == 0 || measured != pixels) return std::nullopt;
  return std::sqrt(squared / double(pixels));
}

}  // namespace rt
