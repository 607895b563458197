// Adaptive sampling's host work per round (render/AdaptiveSampling.hpp):
// what a GPU waits on between two rounds, apart from the noise kernel and
// the transfers. On lavapipe the render hides it; on a GPU a uniform render
// of a few samples takes milliseconds, and these figures decide whether
// adaptive sampling can keep up (README "Adaptive sampling", "On a GPU").
// Synthetic tile noise after the first pass, at three image sizes: the set-up
// (AdaptiveRounds: the plan's per-tile counts) and one round's decisions
// (finishRound: pooling, dilation, the allocation; kernelRanges), best of N.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

#include "BenchClock.hpp"
#include "render/AdaptiveSampling.hpp"

namespace {

// First-pass sums of a tile whose one-sample variance is v: 16 paired pixels
// measured, 48 with one sample (AdaptiveSampling.hpp's first pass).
rt::gpu::GpuTileNoise firstPassTile(double v) {
  rt::gpu::GpuTileNoise tile{};
  tile.varianceSum = float(16 * v * 2);
  tile.squaredSum = float(16 * v / 2);
  tile.inverseCountSum = 48;
  tile.measured = 16;
  return tile;
}

// Noise that varies smoothly over the image by a factor of e^8, with a few
// noisy areas, as penumbrae and defocused edges make it.
std::vector<rt::gpu::GpuTileNoise> syntheticNoise(uint32_t tilesPerRow, uint32_t rows) {
  std::vector<rt::gpu::GpuTileNoise> tiles;
  for (uint32_t ty = 0; ty < rows; ++ty) {
    for (uint32_t tx = 0; tx < tilesPerRow; ++tx) {
      double v = 1e-4 * std::exp(4 * std::sin(tx * 0.07) * std::cos(ty * 0.11));
      tiles.push_back(firstPassTile(v));
    }
  }
  return tiles;
}

struct Timing {
  uint32_t tiles = 0;
  double setupMs = 1e30, roundMs = 1e30;
  uint64_t added = 0;
};

Timing timeRounds(uint32_t width, uint32_t height, int repeats) {
  const uint32_t tile = rt::AdaptivePlan::kTileSize;
  const uint32_t tilesPerRow = (width + tile - 1) / tile, rows = (height + tile - 1) / tile;
  const std::vector<rt::gpu::GpuTileNoise> noise = syntheticNoise(tilesPerRow, rows);
  const std::vector<uint32_t> rays(noise.size(), 2 * tile * tile);  // 2 rays a sample
  const rt::AdaptiveRounds::Goal goal{4, 0.003, 4096};              // the budget binds
  Timing timing;
  timing.tiles = static_cast<uint32_t>(noise.size());
  for (int i = 0; i < repeats; ++i) {
    auto start = bench::Clock::now();
    rt::AdaptiveRounds rounds(width, height, {0, 0, width, height}, goal);
    timing.setupMs = std::min(timing.setupMs, bench::secondsSince(start) * 1e3);
    start = bench::Clock::now();
    rounds.finishRound(noise, rays);
    std::vector<glm::uvec2> ranges = rounds.kernelRanges();
    timing.roundMs = std::min(timing.roundMs, bench::secondsSince(start) * 1e3);
    timing.added = 0;
    for (const glm::uvec2& range : ranges) timing.added += range.y;
  }
  return timing;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Adaptive sampling's host work per round, synthetic tile noise");
  int repeats = 9;
  app.add_option("--repeat", repeats, "Best of this many")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  std::printf(
      "| image | tiles | set-up ms | one round's decisions ms | samples added per tile |\n");
  std::printf("|---|---|---|---|---|\n");
  const std::pair<uint32_t, uint32_t> sizes[] = {{640, 480}, {1920, 1080}, {3840, 2160}};
  for (auto [width, height] : sizes) {
    Timing t = timeRounds(width, height, repeats);
    std::printf("| %ux%u | %u | %.3f | %.3f | %.2f |\n", width, height, t.tiles, t.setupMs,
                t.roundMs, double(t.added) / t.tiles);
  }
  return 0;
}
