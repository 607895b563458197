// Adaptive sampling's host work per round (render/AdaptiveSampling.hpp):
// what a GPU waits on between two rounds, apart from the noise kernel and
// the transfers. On lavapipe the render hides it; on a GPU a uniform render
// of a few samples takes milliseconds, and these figures decide whether
// adaptive sampling can keep up (README "Adaptive sampling", "On a GPU").
// Synthetic tile noise after the first pass, at three image sizes: the set-up
// (AdaptiveRounds: the plan's per-tile counts) and one round's decisions
// (finishRound: pooling, dilation, the allocation; kernelRanges), and the
// edge round's work after the first pass (neighbourContrast over a synthetic
// first-pass image and AdaptivePlan::edgeRound, its allocation over every
// pixel; the read-back of the sums is not included), best of N.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/AdaptiveSampling.hpp"
#include "util/Clock.hpp"

namespace {

// First-pass sums of a tile whose one-sample variance is v: 16 paired pixels
// measured, 48 with one sample (AdaptiveSampling.hpp's first pass).
rt::gpu::GpuTileNoise firstPassTile(double v) {
  rt::gpu::GpuTileNoise tile{};
  tile.varianceSum = float(16 * v * 2);
  tile.squaredSum = float(16 * v / 2);
  tile.inverseCountSum = 48;
  tile.measured = 16;
  tile.pooled = 16;
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

// A first-pass image of one sample a pixel: a smooth gradient crossed by
// the outlines of discs, so that about one pixel in twenty has a contrast.
rt::SampleSums firstPassImage(uint32_t width, uint32_t height) {
  rt::SampleSums sums;
  sums.width = width;
  sums.height = height;
  sums.all.resize(size_t(width) * height);
  sums.odd.assign(sums.all.size(), glm::vec4(0.0f));
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      const float u = float(x % 97) / 97.0f - 0.5f, v = float(y % 89) / 89.0f - 0.5f;
      const float inside = u * u + v * v < 0.1f ? 0.6f : 0.0f;
      sums.all[size_t(y) * width + x] =
          glm::vec4(0.2f + 0.3f * float(x) / float(width) + inside, 0.3f, 0.4f + inside, 1.0f);
    }
  }
  return sums;
}

struct Timing {
  uint32_t tiles = 0;
  double setupMs = 1e30, roundMs = 1e30, edgeMs = 1e30;
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
    auto start = rt::SteadyClock::now();
    rt::AdaptiveRounds rounds(width, height, {0, 0, width, height}, goal);
    timing.setupMs = std::min(timing.setupMs, rt::secondsSince(start) * 1e3);
    start = rt::SteadyClock::now();
    rounds.finishRound(noise, rays);
    std::vector<glm::uvec2> ranges = rounds.kernelRanges();
    timing.roundMs = std::min(timing.roundMs, rt::secondsSince(start) * 1e3);
    timing.added = 0;
    for (const glm::uvec2& range : ranges) timing.added += range.y;
  }
  const rt::PixelRegion region{0, 0, width, height};
  rt::AdaptivePlan plan(width, height, region);
  plan.addRound(plan.uniformRound(1), rays, true);
  const rt::NoiseMeasurement measured = plan.measureNoise(noise);
  const rt::SampleSums image = firstPassImage(width, height);
  rt::AllocationGoal next;
  next.sampleBudget = double(goal.meanSamples) * width * height - double(plan.pixelSamples());
  next.maxSamples = goal.maxSamples;
  for (int i = 0; i < repeats; ++i) {
    auto start = rt::SteadyClock::now();
    const rt::EdgeRound edges =
        plan.edgeRound(measured.tiles, rt::neighbourContrast(image, {}, region), next);
    timing.edgeMs = std::min(timing.edgeMs, rt::secondsSince(start) * 1e3);
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
      "| image | tiles | set-up ms | one round's decisions ms | samples added per tile | edge "
      "round ms |\n");
  std::printf("|---|---|---|---|---|---|\n");
  const std::pair<uint32_t, uint32_t> sizes[] = {{640, 480}, {1920, 1080}, {3840, 2160}};
  for (auto [width, height] : sizes) {
    Timing t = timeRounds(width, height, repeats);
    std::printf("| %ux%u | %u | %.3f | %.3f | %.2f | %.1f |\n", width, height, t.tiles, t.setupMs,
                t.roundMs, double(t.added) / t.tiles, t.edgeMs);
  }
  return 0;
}
