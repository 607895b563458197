#include "render/TileNoise.hpp"

#include <array>
#include <cmath>

#include "gpu/ShaderCompiler.hpp"
#include "gpu/VulkanContext.hpp"
#include "util/Arithmetic.hpp"

namespace rt {
namespace {

constexpr std::array<uint32_t, 4> kBindings{RT_NOISE_BINDING_ACCUMULATION,
                                            RT_NOISE_BINDING_ACCUMULATION_ODD,
                                            RT_NOISE_BINDING_TILES, RT_NOISE_BINDING_PIXEL_EXTRAS};

uint32_t tileCount(uint32_t width, uint32_t height) {
  const glm::uvec2 grid = gpu::adaptiveTileGrid({width, height});
  return grid.x * grid.y;
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
      noExtras_(context, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
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
                                                        const ToneMapping& mapping) {
  const PixelRegion r = resolveRegion(region, width_, height_);
  gpu::GpuTileNoiseParams params{};
  params.size = {width_, height_};
  params.regionStart = {r.x, r.y};
  params.regionEnd = {r.x + r.width, r.y + r.height};
  params.exposure = mapping.exposure;
  params.toneCurve = static_cast<uint32_t>(mapping.curve);
  params.srgbEncode = mapping.srgbEncode ? 1u : 0u;
  params.edges = pixelExtras ? 1u : 0u;
  kernel_.bind(RT_NOISE_BINDING_ACCUMULATION, all);
  kernel_.bind(RT_NOISE_BINDING_ACCUMULATION_ODD, odd);
  kernel_.bind(RT_NOISE_BINDING_TILES, tiles_);
  kernel_.bind(RT_NOISE_BINDING_PIXEL_EXTRAS, pixelExtras ? *pixelExtras : noExtras_);
  context_.submitAndWait([&](VkCommandBuffer commands) {
    kernel_.recordDispatch(commands, &params, divideRoundUp(tileCount_, RT_NOISE_WORKGROUP_SIZE));
  });
  std::vector<gpu::GpuTileNoise> tiles(tileCount_);
  tiles_.download(tiles.data(), tiles.size() * sizeof(gpu::GpuTileNoise));
  return tiles;
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
