// Adaptive sampling: the allocation on synthetic tiles, and adaptive renders
// of the study scenes: deterministic, within the budget, samples where the
// noise is, more accurate than uniform sampling at the same mean count, and
// an error estimate that stays honest although tiles stopped at different
// counts.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <numeric>
#include <random>
#include <set>

#include "formats/json/JsonSceneLoader.hpp"
#include "imaging/ImageError.hpp"
#include "render/AdaptiveSampling.hpp"
#include "render/ProgressiveRenderer.hpp"
#include "render/Renderer.hpp"
#include "render/TileNoise.hpp"
#include "support/TestSupport.hpp"
#include "util/Error.hpp"

using namespace rt;

namespace {

// 96x72: large enough that the noise sits in some tiles more than in
// others (12 x 9 tiles).
RenderOptions smallRender(SamplerKind sampler, uint32_t samples, uint32_t seed = 1,
                          uint32_t width = 96) {
  return test::studyRender(sampler, samples, seed, width);
}

RenderOptions adaptiveRender(uint32_t samples, uint32_t seed = 1, uint32_t width = 96) {
  RenderOptions options = smallRender(SamplerKind::Sobol, samples, seed, width);
  options.adaptive = true;
  options.keepErrorImage = true;
  return options;
}

// A 96x72 accumulation of an adaptive render with a budget of `samples`
// (Sobol), for tests that run the rounds themselves.
ProgressiveOptions adaptiveAccumulation(uint32_t samples) {
  ProgressiveOptions options;
  options.width = 96;
  options.height = 72;
  options.samplesTotal = samples;
  options.sampler = SamplerKind::Sobol;
  options.independentHalves = true;
  options.adaptive = true;
  return options;
}

const ImageF& studyTruth(const std::string& name, uint32_t width = 96) {
  return test::studyTruth(name, width, 2048);
}

// Mean over channels of the squared display error of pixel i.
double squaredError(const ImageF& image, const ImageF& truth, size_t i, const ToneMapping& m) {
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    double d =
        double(displayValue(image.rgba[i * 4 + c], m)) - displayValue(truth.rgba[i * 4 + c], m);
    sum += d * d;
  }
  return sum / 3.0;
}

std::vector<TileNoise> syntheticTiles(const std::vector<double>& variances, uint32_t samples) {
  std::vector<TileNoise> tiles;
  for (double v : variances) tiles.push_back({64, samples, v});
  return tiles;
}

// The tiles' noise sums of hand-made replicate sums, measured by the
// device's kernel (TileNoiseKernel) as the renderer measures them.
std::vector<gpu::GpuTileNoise> measureOnDevice(const SampleSums& sums,
                                               const ToneMapping& mapping = {}) {
  const VkDeviceSize bytes = sums.all.size() * sizeof(glm::vec4);
  Buffer all(test::gpu(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  Buffer odd(test::gpu(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  all.upload(sums.all.data(), bytes);
  odd.upload(sums.odd.data(), bytes);
  TileNoiseKernel kernel(test::gpu(), test::shaderCompiler(), sums.width, sums.height);
  std::vector<gpu::GpuTileNoise> tiles =
      kernel.measure(all, odd, nullptr, {0, 0, sums.width, sums.height}, mapping);
  test::checkNoValidationMessages();
  return tiles;
}

// Runs allocation rounds on tiles whose noise stays as given, as a render
// would, until no tile gets more samples.
uint32_t allocateUntilDone(std::vector<TileNoise>& tiles, const AllocationGoal& goal) {
  double budget = goal.sampleBudget;
  uint32_t rounds = 0;
  for (;; ++rounds) {
    AllocationGoal left = goal;
    left.sampleBudget = budget;
    std::vector<uint32_t> added = allocateSamples(tiles, left);
    if (std::all_of(added.begin(), added.end(), [](uint32_t n) { return n == 0; })) break;
    for (size_t i = 0; i < tiles.size(); ++i) {
      CHECK(added[i] <= 3 * tiles[i].samples);  // at most quadrupling per round
      budget -= double(added[i]) * tiles[i].pixels;
      tiles[i].samples += added[i];
    }
    REQUIRE(rounds < 64);
  }
  return rounds;
}

// The allocation's rule by brute force, for random tiles: each tile ends
// with n_i(c) = clamp(c * sqrt(v / cost), samples, max(cap, samples)); c is
// the largest multiplier within the budget and, with a target, at most the
// smallest whose predicted MSE is 0.9x the target; then rounded down and at
// most quadrupled. Bisection over 400 steps, independent of the renderer's
// exact solve.
std::vector<uint32_t> allocateByBisection(const std::vector<TileNoise>& tiles,
                                          const AllocationGoal& goal) {
  auto planned = [&](const TileNoise& t, double c) {
    const double rate = std::sqrt(t.variance / t.cost);
    return std::clamp(c * rate, double(t.samples), double(std::max(goal.maxSamples, t.samples)));
  };
  auto spend = [&](double c) {
    double sum = 0;
    for (const TileNoise& t : tiles) sum += t.pixels * (planned(t, c) - t.samples);
    return sum;
  };
  auto mse = [&](double c) {
    double sum = 0, pixels = 0;
    for (const TileNoise& t : tiles) {
      pixels += t.pixels;
      if (t.variance > 0) sum += t.pixels * t.variance / planned(t, c);
    }
    return sum / pixels;
  };
  auto bisect = [](auto below, bool largest) {  // below(c) holds on one side of the answer
    double lo = std::log(1e-12), hi = std::log(1e18);
    for (int i = 0; i < 400; ++i) {
      const double mid = 0.5 * (lo + hi);
      (below(std::exp(mid)) == largest ? lo : hi) = mid;
    }
    return std::exp(largest ? lo : hi);
  };
  std::vector<uint32_t> added(tiles.size(), 0);
  if (goal.targetMse > 0 && mse(0) <= goal.targetMse) return added;
  double c = bisect([&](double m) { return spend(m) <= goal.sampleBudget; }, true);
  if (goal.targetMse > 0) {
    c = std::min(c, bisect([&](double m) { return mse(m) <= goal.targetMse * 0.9; }, false));
  }
  for (size_t i = 0; i < tiles.size(); ++i) {
    const double wanted = std::floor(planned(tiles[i], c)) - tiles[i].samples;
    added[i] = static_cast<uint32_t>(std::clamp(wanted, 0.0, 3.0 * tiles[i].samples));
  }
  return added;
}

}  // namespace

TEST_SUITE("adaptive sampling") {
  TEST_CASE(
      "noiseless tiles get nothing; the others samples in proportion to the noise's deviation") {
    std::vector<TileNoise> tiles = syntheticTiles({0.0, 0.01, 0.04, 0.16}, 8);
    AllocationGoal goal;
    goal.targetMse = 1e-4;  // RMSE 0.01
    goal.sampleBudget = 1e12;
    goal.maxSamples = 1u << 20;
    uint32_t rounds = allocateUntilDone(tiles, goal);
    CHECK(rounds >= 2);
    CHECK(tiles[0].samples == 8);
    CHECK(double(tiles[2].samples) / tiles[1].samples ==
          doctest::Approx(2.0).epsilon(0.05).scale(0));
    CHECK(double(tiles[3].samples) / tiles[1].samples ==
          doctest::Approx(4.0).epsilon(0.05).scale(0));
    CHECK(predictedMse(tiles) <= 1e-4);
    // Uniform sampling would need every tile at the noisiest's count...
    const double uniform = (0.0 + 0.01 + 0.04 + 0.16) / 4 / 1e-4;
    const double adaptive =
        double(tiles[0].samples + tiles[1].samples + tiles[2].samples + tiles[3].samples) / 4;
    CHECK(adaptive < 0.75 * uniform);  // ...(mean sigma)^2 / mean(sigma^2) = 0.6 of it here
  }

  TEST_CASE("at equal noise a tile whose samples cost four times as much gets half the samples") {
    // n ~ sqrt(v / cost) minimizes the time at a given error: the costly
    // tile's error stays higher, which the cheap tile's extra samples offset.
    std::vector<TileNoise> tiles = syntheticTiles({0.04, 0.04, 0.0}, 8);
    tiles[1].cost = 4.0;
    AllocationGoal goal;
    goal.targetMse = 1e-4;
    goal.sampleBudget = 1e12;
    goal.maxSamples = 1u << 20;
    allocateUntilDone(tiles, goal);
    CHECK(double(tiles[0].samples) / tiles[1].samples ==
          doctest::Approx(2.0).epsilon(0.05).scale(0));
    CHECK(tiles[2].samples == 8);
    CHECK(predictedMse(tiles) <= 1e-4);
  }

  TEST_CASE("the budget caps what the rounds add, and a met target adds nothing") {
    std::vector<TileNoise> tiles = syntheticTiles({0.01, 0.02, 0.5, 0.0}, 8);
    AllocationGoal goal;
    goal.sampleBudget = 64.0 * 4 * 24;  // 24 more samples per pixel on average
    goal.maxSamples = 1u << 20;
    allocateUntilDone(tiles, goal);
    double spent = 0;
    for (const TileNoise& t : tiles) spent += double(t.samples - 8) * t.pixels;
    CHECK(spent <= goal.sampleBudget);
    CHECK(spent > 0.9 * goal.sampleBudget);
    CHECK(tiles[3].samples == 8);
    goal.targetMse = 1.0;  // far above the predicted error
    std::vector<uint32_t> added = allocateSamples(tiles, goal);
    CHECK(std::all_of(added.begin(), added.end(), [](uint32_t n) { return n == 0; }));
  }

  TEST_CASE("one round spends the budget on n = c * sqrt(v), clamped to the tiles' bounds") {
    // Rates sqrt(v) 0.1, 0.2 and 0.3 from 4 samples, at most 12: a budget of
    // 15.3 samples per tile solves to c = 51, where the tiles plan 5.1, 10.2
    // and 15.3 (clamped to 12) samples: the rounded-down counts add 1, 6, 8.
    std::vector<TileNoise> tiles = syntheticTiles({0.01, 0.04, 0.09, 0.0}, 4);
    AllocationGoal goal;
    goal.sampleBudget = 64.0 * 15.3;
    goal.maxSamples = 12;
    std::vector<uint32_t> added = allocateSamples(tiles, goal);
    CHECK(added == std::vector<uint32_t>{1, 6, 8, 0});
    // A target between: the smallest c whose plan predicts it. At c = 51
    // the prediction is (0.01 / 5.1 + 0.04 / 10.2 + 0.09 / 12) / 4.
    const double atC51 = (0.01 / 5.1 + 0.04 / 10.2 + 0.09 / 12) / 4;
    goal.sampleBudget = 1e12;
    goal.targetMse = atC51 / 0.9;  // the allocation aims at 0.9x its target MSE
    added = allocateSamples(tiles, goal);
    CHECK(added == std::vector<uint32_t>{1, 6, 8, 0});
  }

  TEST_CASE("the exact multiplier solve allocates as a brute-force bisection does") {
    // Random tiles: noiseless ones, capped ones, costly ones; bound by the
    // budget or by the target.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    uint32_t cases = 0, mismatches = 0, targetBound = 0;
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<TileNoise> tiles(1 + trial % 40);
      for (TileNoise& t : tiles) {
        t.pixels = unit(random) < 0.1 ? 17 : 64;
        t.samples = 1 + static_cast<uint32_t>(unit(random) * 12);
        t.variance = unit(random) < 0.2 ? 0.0 : std::exp(-12 + 8 * unit(random));
        t.cost = 1 + 7 * unit(random);
      }
      AllocationGoal goal;
      goal.maxSamples = 4 + static_cast<uint32_t>(unit(random) * 60);
      goal.sampleBudget = 64.0 * double(tiles.size()) * 30 * unit(random);
      goal.targetMse = trial % 2 ? std::exp(-14 + 6 * unit(random)) : 0.0;
      const std::vector<uint32_t> exact = allocateSamples(tiles, goal);
      const std::vector<uint32_t> bisected = allocateByBisection(tiles, goal);
      for (size_t i = 0; i < tiles.size(); ++i) mismatches += exact[i] != bisected[i];
      cases += static_cast<uint32_t>(tiles.size());
      AllocationGoal budgetOnly = goal;
      budgetOnly.targetMse = 0;
      if (goal.targetMse > 0 && allocateSamples(tiles, budgetOnly) != exact) ++targetBound;
    }
    CAPTURE(cases);
    CHECK(mismatches == 0);
    CHECK(targetBound > 20);  // the target, not only the budget, decided some trials
  }

  TEST_CASE("the plan counts a region's pixels and paired pixels per tile as a pixel walk does") {
    // A region that starts and ends inside tiles and inside 4x2 blocks.
    const PixelRegion region{3, 5, 30, 21};
    AdaptivePlan plan(37, 29, region);
    uint64_t paired = 0;
    for (uint32_t y = region.y; y < region.y + region.height; ++y) {
      for (uint32_t x = region.x; x < region.x + region.width; ++x) {
        paired += gpu::adaptivePairedPixel(x, y);
      }
    }
    REQUIRE(paired > 0);
    CHECK(plan.regionPixels() == 30 * 21);
    plan.addRound(plan.uniformRound(1), std::vector<uint32_t>(plan.tileCount(), 0), true);
    CHECK(plan.pixelSamples() == 30 * 21 + paired);
  }

  TEST_CASE("a tile beside a noisy one keeps a share of its noise") {
    AdaptivePlan plan(24, 8, {0, 0, 24, 8});  // three tiles in a row
    // Rays: 3 a sample in tile 0, none counted in tile 1, 1 a sample in tile 2.
    plan.addRound(plan.uniformRound(4), {64 * 4 * 3, 0, 64 * 4});
    SampleSums sums{24, 8, std::vector<glm::vec4>(24 * 8), std::vector<glm::vec4>(24 * 8)};
    for (uint32_t y = 0; y < 8; ++y) {
      for (uint32_t x = 0; x < 24; ++x) {
        const size_t i = y * 24 + x;
        // Halves of two samples each: equal in tiles 1 and 2, 0.2 apart in tile 0.
        const float odd = x < 8 ? 0.6f : 0.5f;
        sums.odd[i] = glm::vec4(glm::vec3(2 * odd), 2);
        sums.all[i] = sums.odd[i] + glm::vec4(glm::vec3(2 * 0.4f), 2);
        if (x >= 8) sums.all[i] = sums.odd[i] + glm::vec4(glm::vec3(2 * 0.5f), 2);
      }
    }
    std::vector<gpu::GpuTileNoise> sumsOnDevice = measureOnDevice(sums);
    REQUIRE(sumsOnDevice.size() == 3);
    // The kernel's sums over tile 0: 64 pixels of squared error 0.01 each.
    CHECK(sumsOnDevice[0].squaredSum == doctest::Approx(64 * 0.01).epsilon(1e-4));
    CHECK(sumsOnDevice[0].varianceSum == doctest::Approx(64 * 0.01 * 4).epsilon(1e-4));
    CHECK(sumsOnDevice[0].measured == 64);
    CHECK(sumsOnDevice[1].squaredSum == 0.0f);
    CHECK(sumsOnDevice[2].inverseCountSum == 0.0f);
    CHECK(sumsOnDevice[2].unsampled == 0);
    NoiseMeasurement measured = plan.measureNoise(sumsOnDevice);
    // Squared error of the mean 0.04 * 4 / 16 in tile 0, none in the others
    // (before dilation, which only steers samples).
    REQUIRE(measured.rmse);
    CHECK(*measured.rmse == doctest::Approx(std::sqrt(0.01 / 3)).epsilon(1e-4).scale(0));
    std::vector<TileNoise>& noise = measured.tiles;
    REQUIRE(noise.size() == 3);
    // (A - B)^2 nA nB / n^2 * n = 0.04 * 4 / 16 * 4.
    CHECK(noise[0].variance == doctest::Approx(0.04).epsilon(1e-4).scale(0));
    CHECK(noise[1].variance == doctest::Approx(0.25 * 0.04).epsilon(1e-4).scale(0));
    CHECK(noise[2].variance == 0.0);
    CHECK(noise[0].samples == 4);
    CHECK(plan.pixelSamples() == 24 * 8 * 4);
    // A sample's cost is its rays, at least the camera ray.
    CHECK(noise[0].cost == 3.0);
    CHECK(noise[1].cost == 1.0);
    CHECK(noise[2].cost == 1.0);
  }

  TEST_CASE("the first pass pairs two 4x2 blocks of every tile, and the kernel pairs the same") {
    // Each 4x2 block (one run of eight lanes, pixelInGroup in trace.comp) is
    // paired as a whole, and two of a tile's eight are.
    uint32_t splitBlocks = 0, wrongTiles = 0;
    for (uint32_t tile = 0; tile < 256; ++tile) {
      uint32_t paired = 0;
      for (uint32_t block = 0; block < 8; ++block) {
        uint32_t x0 = (tile % 16) * 8 + (block & 1) * 4, y0 = (tile / 16) * 8 + (block >> 1) * 2;
        uint32_t first = gpu::adaptivePairedPixel(x0, y0);
        for (uint32_t i = 0; i < 8; ++i) {
          if (gpu::adaptivePairedPixel(x0 + i % 4, y0 + i / 4) != first) ++splitBlocks;
        }
        paired += first;
      }
      if (paired != 2) ++wrongTiles;
    }
    CHECK(splitBlocks == 0);
    CHECK(wrongTiles == 0);
    // End to end: a target the first pass meets ends the render after it.
    Scene scene = test::projectScene("study-arealight.json");
    RenderOptions options = adaptiveRender(16);
    options.targetRmse = 1.0;
    RenderStats stats;
    ImageF image = test::render(scene, options, &stats);
    uint32_t wrongCounts = 0;
    for (uint32_t y = 0; y < image.height; ++y) {
      for (uint32_t x = 0; x < image.width; ++x) {
        float count = image.rgba[(size_t(y) * image.width + x) * 4 + 3];
        if (count != 1.0f + float(gpu::adaptivePairedPixel(x, y))) ++wrongCounts;
      }
    }
    CHECK(wrongCounts == 0);
    CHECK(stats.meanSamples == 1.25);  // 12 x 9 whole tiles
    REQUIRE(stats.rmseEstimate);
    CHECK(stats.reachedTarget);
  }

  TEST_CASE(
      "pixels of one sample take their tile's noise, an edge tile without pairs its neighbour's") {
    // An image one column wider than k tiles, where the last column's tile
    // has no paired pixel.
    auto pairedInColumn = [](uint32_t x) {
      uint32_t n = 0;
      for (uint32_t y = 0; y < 8; ++y) n += gpu::adaptivePairedPixel(x, y);
      return n;
    };
    uint32_t k = 1;
    while (pairedInColumn(8 * k) > 0 && k < 1000) ++k;
    REQUIRE(k < 1000);
    const uint32_t width = 8 * k + 1, height = 8;
    AdaptivePlan plan(width, height, {0, 0, width, height});
    SampleSums sums{width, height, std::vector<glm::vec4>(width * height),
                    std::vector<glm::vec4>(width * height)};
    uint32_t paired = 0;
    for (uint32_t y = 0; y < height; ++y) {
      for (uint32_t x = 0; x < width; ++x) {
        const size_t i = size_t(y) * width + x;
        if (gpu::adaptivePairedPixel(x, y)) {
          // Halves of one sample, 0.4 and 0.6: a squared error of the mean
          // of 0.04 / 4, one sample's variance 0.02.
          sums.odd[i] = glm::vec4(glm::vec3(0.6f), 1);
          sums.all[i] = glm::vec4(glm::vec3(1.0f), 2);
          ++paired;
        } else {
          sums.all[i] = glm::vec4(glm::vec3(0.5f), 1);
        }
      }
    }
    std::vector<gpu::GpuTileNoise> sumsOnDevice = measureOnDevice(sums);
    // Per tile: its paired pixels are measured, the others have one sample.
    for (size_t tile = 0; tile < sumsOnDevice.size(); ++tile) {
      CAPTURE(tile);
      const double columns = tile + 1 < sumsOnDevice.size() ? 8 : 1;
      CHECK(double(sumsOnDevice[tile].measured) + sumsOnDevice[tile].inverseCountSum ==
            doctest::Approx(columns * 8));
      CHECK(sumsOnDevice[tile].unsampled == 0);
    }
    CHECK(sumsOnDevice.back().measured == 0);
    NoiseMeasurement measured = plan.measureNoise(sumsOnDevice);
    REQUIRE(measured.rmse);
    const double pixels = double(width) * height;
    const double expected = std::sqrt((paired * 0.01 + (pixels - paired) * 0.02) / pixels);
    CHECK(*measured.rmse == doctest::Approx(expected).epsilon(1e-4).scale(0));
    std::vector<float> errors = plan.errorImage(sums, ToneMapping{}, measured.sampleVariance);
    for (uint32_t y = 0; y < height; ++y) {
      CAPTURE(y);
      CHECK(errors[size_t(y) * width + width - 1] ==
            doctest::Approx(std::sqrt(0.02)).epsilon(1e-4).scale(0));
    }
  }

  TEST_CASE("adaptive renders are deterministic, within the budget, and sample the penumbrae") {
    Scene scene = test::projectScene("study-arealight.json");
    RenderStats first, second;
    ImageF a = test::render(scene, adaptiveRender(32), &first);
    ImageF b = test::render(scene, adaptiveRender(32), &second);
    CHECK(a.rgba == b.rgba);
    CHECK(first.meanSamples <= 32.0);
    CHECK(first.meanSamples > 16.0);
    CHECK(first.samplesDone >= kAdaptiveFirstPass);
    // Every pixel has an estimate, those of one sample from their tile.
    CHECK(std::all_of(first.estimatedError.begin(), first.estimatedError.end(),
                      [](float e) { return e >= 0; }));
    CHECK(first.maxSamples >= 4 * first.samplesDone);  // the counts spread
    CHECK(first.estimatedError.size() == a.rgba.size() / 4);
    // Another seed decides differently.
    ImageF c = test::render(scene, adaptiveRender(32, 2));
    CHECK(c.rgba != a.rgba);
  }

  TEST_CASE("each pixel of an adaptive render holds the samples of a uniform render of its count") {
    // Sample s of a pixel depends only on (pixel, s, dimension, seed) and
    // the sums add in index order, so a pixel given n samples by the first
    // pass, its paired block, the edge round and the tile rounds (each
    // starting after the pixel's samples so far) equals, bit for bit, the
    // pixel of a uniform render of n samples: no index is skipped or taken
    // twice. The area-light study's adaptive render splits its one-sample
    // light four ways by itself (light splitting), as the uniform render
    // does when asked.
    for (const char* name : {"default.json", "study-arealight.json"}) {
      CAPTURE(std::string(name));
      Scene scene = test::projectScene(name);
      const ImageF image = test::render(scene, adaptiveRender(3));
      std::set<uint32_t> counts;
      for (size_t i = 0; i < image.rgba.size() / 4; ++i)
        counts.insert(uint32_t(image.rgba[4 * i + 3]));
      REQUIRE(counts.size() >= 3);  // the first pass, the pairs and the edges at least
      if (!scene.areaLights.empty()) scene.settings.lightSplit = 4;
      uint32_t compared = 0;
      for (uint32_t count : counts) {
        if (count > 8) break;
        RenderOptions uniform = smallRender(SamplerKind::Sobol, count);
        uniform.estimateError = true;  // independent halves, as adaptive renders draw them
        const ImageF expected = test::render(scene, uniform);
        for (size_t i = 0; i < image.rgba.size() / 4; ++i) {
          if (uint32_t(image.rgba[4 * i + 3]) != count) continue;
          CAPTURE(i);
          CAPTURE(count);
          for (int c = 0; c < 4; ++c) CHECK(image.rgba[4 * i + c] == expected.rgba[4 * i + c]);
          ++compared;
        }
      }
      CHECK(compared > image.rgba.size() / 4 * 9 / 10);
    }
  }

  TEST_CASE("at the same mean sample count adaptive sampling beats uniform sampling") {
    // At half the study's size (20 x 15 tiles): the gain grows with the
    // number of tiles that can stop early. The RMSE over three seeds: one
    // render's varies by about 5% with the seed, as much as the margin.
    constexpr uint32_t kWidth = 160;
    constexpr uint32_t kSeeds = 3;
    for (const char* name : {"study-arealight.json", "study-thinlens.json"}) {
      CAPTURE(std::string(name));
      Scene scene = test::projectScene(name);
      ToneMapping mapping = toneMappingFor(scene);
      const ImageF& truth = studyTruth(name, kWidth);
      RenderStats stats;
      auto error = [&](auto options, RenderStats* s = nullptr) {
        double squared = 0;
        for (uint32_t seed = 1; seed <= kSeeds; ++seed) {
          const double rmse = displayRmse(test::render(scene, options(seed), s), truth, mapping);
          squared += rmse * rmse;
        }
        return std::sqrt(squared / kSeeds);
      };
      double adaptive =
          error([&](uint32_t seed) { return adaptiveRender(32, seed, kWidth); }, &stats);
      double jittered = error(
          [&](uint32_t seed) { return smallRender(SamplerKind::Jittered, 32, seed, kWidth); });
      double sobol =
          error([&](uint32_t seed) { return smallRender(SamplerKind::Sobol, 32, seed, kWidth); });
      CAPTURE(adaptive);
      CAPTURE(jittered);
      CAPTURE(sobol);
      CHECK(stats.meanSamples <= 32.0);
      CHECK(adaptive < 0.9 * jittered);
      CHECK(adaptive < 0.9 * sobol);
    }
  }

  TEST_CASE("the estimate stays within 25% of the true error for the image and per sample count") {
    // The mean squared errors over three seeds: an estimate is right on
    // average, not in every render. At 96x72 one pixel of the area-light
    // study, which sees the light in the mirror sphere now and then, holds
    // most of the estimate when one of its halves has such a sample (0.25
    // in one render at 64 samples: the estimate of the image read 2.1x its
    // true error, 0.0034 against 0.0016, though that pixel's mean was within
    // 0.01 of the truth); three renders' sums tell what the estimate says.
    for (const char* name : {"study-arealight.json", "study-thinlens.json"}) {
      for (uint32_t samples : {24u, 64u}) {
        CAPTURE(std::string(name));
        CAPTURE(samples);
        Scene scene = test::projectScene(name);
        ToneMapping mapping = toneMappingFor(scene);
        const ImageF& truth = studyTruth(name);
        double estimated[2] = {0, 0}, actual[2] = {0, 0};
        size_t pixels[2] = {0, 0};
        double estimateSquared = 0, truthSquared = 0;
        for (uint32_t seed = 1; seed <= 3; ++seed) {
          RenderStats stats;
          ImageF image = test::render(scene, adaptiveRender(samples, seed), &stats);
          const double trueRmse = displayRmse(image, truth, mapping);
          REQUIRE(stats.rmseEstimate);
          estimateSquared += *stats.rmseEstimate * *stats.rmseEstimate;
          truthSquared += trueRmse * trueRmse;
          // Pixels that stopped early against those that went on: split at
          // the median count.
          std::vector<float> counts;
          for (size_t i = 3; i < image.rgba.size(); i += 4) counts.push_back(image.rgba[i]);
          std::vector<float> sorted = counts;
          std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
          const float median = sorted[sorted.size() / 2];
          for (size_t i = 0; i < counts.size(); ++i) {
            const int went = counts[i] > median ? 1 : 0;
            const double e = stats.estimatedError[i];
            estimated[went] += e * e;
            actual[went] += squaredError(image, truth, i, mapping);
            ++pixels[went];
          }
        }
        CHECK(std::sqrt(estimateSquared / 3) ==
              doctest::Approx(std::sqrt(truthSquared / 3)).epsilon(0.25).scale(0));
        // Compare estimated and true RMSE within each group.
        for (int went : {0, 1}) {
          if (pixels[went] < 3 * 64) continue;  // too few pixels for a steady comparison
          CAPTURE(went);
          CAPTURE(pixels[went]);
          CHECK(std::sqrt(estimated[went] / double(pixels[went])) ==
                doctest::Approx(std::sqrt(actual[went] / double(pixels[went])))
                    .epsilon(0.25)
                    .scale(0));
        }
      }
    }
  }

  TEST_CASE("--target-rmse with adaptive sampling stops once the estimate reaches it") {
    // And not far below it: the plans aim at the target through their
    // prediction calibrated to the estimate (predictionBias). Aimed at 0.81x
    // the MSE by the uncalibrated prediction, these renders ended at 0.72x
    // and 0.68x the target RMSE; now 0.80x and 0.82x.
    Scene scene = test::projectScene("study-thinlens.json");
    for (double target : {0.012, 0.006}) {
      CAPTURE(target);
      RenderOptions options = adaptiveRender(4096);
      options.targetRmse = target;
      RenderStats stats;
      test::render(scene, options, &stats);
      REQUIRE(stats.rmseEstimate);
      CHECK(stats.reachedTarget);
      CHECK(*stats.rmseEstimate <= target);
      CHECK(*stats.rmseEstimate > 0.76 * target);
      CHECK(stats.meanSamples < 512);
    }
  }

  TEST_CASE("a render to a target does not stall short of it (the common scene)" *
            test::needsShared()) {
    // Plans aimed at the target by their calibrated prediction shrank round
    // after round here and the render ended at an estimate of 0.0103.
    const std::filesystem::path shared = test::requireShared();
    Scene scene = loadJsonScene(shared / "bench" / "common-scene" / "common_dof.json");
    RenderOptions options;
    options.sampler = SamplerKind::Sobol;
    options.width = 160;
    options.height = 120;
    options.samplesPerPixel = 4096;
    options.adaptive = true;
    options.targetRmse = 0.01;
    RenderStats stats;
    test::render(scene, options, &stats);
    REQUIRE(stats.rmseEstimate);
    CAPTURE(*stats.rmseEstimate);
    CHECK(stats.reachedTarget);
    CHECK(stats.meanSamples < 4);
  }

  TEST_CASE("neighbour contrast: the largest squared display step between first samples") {
    // Two samples a pixel, each 0.1, but (1, 1)'s first is 0.5: the step is
    // 0.4 between first samples (0.2 between the pixels' means).
    SampleSums sums;
    sums.width = 4;
    sums.height = 3;
    sums.all.assign(12, glm::vec4(0.2f, 0.2f, 0.2f, 2.0f));
    sums.all[5] = glm::vec4(0.6f, 0.6f, 0.6f, 2.0f);
    sums.odd.assign(12, glm::vec4(0.1f, 0.1f, 0.1f, 1.0f));
    const std::vector<float> contrast = neighbourContrast(sums, ToneMapping{}, {0, 0, 4, 3});
    for (size_t i = 0; i < contrast.size(); ++i) {
      CAPTURE(i);
      const bool besideStep = i == 5 || i == 1 || i == 4 || i == 6 || i == 9;
      CHECK(contrast[i] == doctest::Approx(besideStep ? 0.16 : 0.0));
    }
    // Outside the region nothing is compared.
    const std::vector<float> inRegion = neighbourContrast(sums, ToneMapping{}, {2, 0, 2, 3});
    CHECK(inRegion[5] == 0.0f);
    CHECK(inRegion[6] == doctest::Approx(0.0));
  }

  TEST_CASE("the edge round gives a noiseless tile's contrasting blocks samples, and no others") {
    AdaptivePlan plan(16, 8, {0, 0, 16, 8});  // two tiles
    plan.addRound(plan.uniformRound(1), std::vector<uint32_t>(2, 64), true);
    std::vector<TileNoise> tiles = syntheticTiles({0.0, 0.0}, 1);
    std::vector<float> contrast(16 * 8, 0.0f);
    for (uint32_t y = 0; y < 8; ++y) contrast[y * 16 + 11] = 0.09f;  // a column in tile 1
    AllocationGoal goal;
    goal.sampleBudget = 2.0 * 128 - double(plan.pixelSamples());
    goal.maxSamples = 64;
    const EdgeRound round = plan.edgeRound(tiles, contrast, goal);
    // The column's 4x2 blocks (x 8 to 11: one SIMD vector each, which runs
    // as long as its busiest pixel) share its samples; the budget of 96
    // allows 3 more a pixel there (2 after rounding down), and no growth cap.
    const uint32_t extra = round.pixels[11];
    CHECK(extra >= 2);
    for (uint32_t y = 0; y < 8; ++y) {
      for (uint32_t x = 0; x < 16; ++x) {
        CAPTURE(x);
        CHECK(round.pixels[y * 16 + x] == (x >= 8 && x < 12 ? extra : 0u));
      }
    }
    CHECK(round.common == std::vector<uint32_t>{0, 0});
    CHECK(round.extraSums == std::vector<uint64_t>{0, 32 * extra});
    plan.addEdgeRound(round, {64, 160});
    CHECK(plan.pixelSamples() == 128 + 32 + 32 * extra);  // the paired pixels' 32 included
    CHECK(plan.extraSamples(1) == 32 * extra);
    // The later rounds start each pixel after its edge samples.
    const std::vector<glm::uvec2> ranges = plan.kernelRanges({1, 1});
    CHECK(ranges[1].x == (1u | RT_ADAPTIVE_PAIRED_FLAG | RT_ADAPTIVE_EXTRAS_FLAG));
    CHECK(ranges[1].y == 1u);
  }

  TEST_CASE("aimed at a target, the edge round quadruples a pixel's samples at most") {
    // The contrast steers the samples but predicts no error: uncapped, a plan
    // aimed at RMSE 0.01 took default.json to 7.1 samples a pixel and 0.0022.
    AdaptivePlan plan(16, 8, {0, 0, 16, 8});
    plan.addRound(plan.uniformRound(1), std::vector<uint32_t>(2, 64), true);
    std::vector<TileNoise> tiles = syntheticTiles({1e-3, 1e-3}, 1);
    std::vector<float> contrast(16 * 8, 0.0f);
    for (uint32_t y = 0; y < 8; ++y) contrast[y * 16 + 11] = 0.09f;
    AllocationGoal goal;
    goal.sampleBudget = 1e9;
    goal.maxSamples = 64;
    goal.targetMse = 1e-6;
    const EdgeRound round = plan.edgeRound(tiles, contrast, goal);
    CHECK(round.common == std::vector<uint32_t>{3, 3});
    for (uint32_t y = 0; y < 8; ++y) {
      for (uint32_t x = 0; x < 16; ++x) {
        CAPTURE(x);
        CHECK(round.pixels[y * 16 + x] == 0u);  // the column too: capped like the rest
      }
    }
    goal.targetMse = 0;  // a budget alone: the column gets more than four times
    goal.sampleBudget = 4.0 * 128;
    const EdgeRound budgeted = plan.edgeRound(tiles, contrast, goal);
    CHECK(budgeted.common[1] + budgeted.pixels[11] > 3u);
  }

  TEST_CASE("silhouettes that the paired blocks miss get their samples at a mean of 2") {
    // Three diffuse spheres against the background under a point light: the
    // only error is at their outlines, where a tile's paired blocks see few
    // of the pixels. Without the edge round adaptive sampling had a higher
    // RMSE here than uniform Sobol sampling.
    Scene scene = test::frontStage(96, 72, {0, 0, 50}, 0.8f);
    const glm::vec3 centres[] = {{-1.1f, 0.3f, 0}, {0.2f, -0.4f, 0}, {1.2f, 0.5f, 0.3f}};
    const glm::vec3 colours[] = {{0.9f, 0.3f, 0.2f}, {0.3f, 0.8f, 0.4f}, {0.9f, 0.9f, 0.9f}};
    for (int i = 0; i < 3; ++i)
      test::addSphere(scene, test::diffuse(colours[i]), centres[i], 0.55f);
    const ToneMapping mapping = toneMappingFor(scene);
    RenderOptions reference;
    reference.sampler = SamplerKind::Sobol;
    reference.samplesPerPixel = 1024;
    const ImageF truth = test::render(scene, reference);
    RenderOptions uniform;
    uniform.sampler = SamplerKind::Sobol;
    uniform.samplesPerPixel = 2;
    RenderOptions adaptive = uniform;
    adaptive.adaptive = true;
    RenderStats stats;
    const ImageF image = test::render(scene, adaptive, &stats);
    const double adaptiveError = displayRmse(image, truth, mapping);
    // The outline pixels are measured apart from their tiles' pools, so the
    // flat pixels of one sample do not take the outlines' noise.
    REQUIRE(stats.rmseEstimate.has_value());
    CAPTURE(*stats.rmseEstimate);
    CHECK(*stats.rmseEstimate == doctest::Approx(adaptiveError).epsilon(0.25));
    const double uniformError = displayRmse(test::render(scene, uniform), truth, mapping);
    CAPTURE(adaptiveError);
    CAPTURE(uniformError);
    // 0.64x (0.52x with samples per pixel rather than per 4x2 block, whose
    // vectors run as long as their busiest pixel; 0.66x per pixel capped at
    // 4x); 1.01x without the edge round.
    CHECK(adaptiveError < 0.72 * uniformError);
    // The samples went to the outlines: pixels whose converged value differs
    // from a neighbour's.
    double outline = 0, flat = 0, outlinePixels = 0, flatPixels = 0;
    for (uint32_t y = 1; y + 1 < 72; ++y) {
      for (uint32_t x = 1; x + 1 < 96; ++x) {
        float step = 0;
        for (glm::ivec2 d :
             {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
          for (int c = 0; c < 3; ++c) {
            step =
                std::max(step, std::abs(truth.pixel(x, y)[c] - truth.pixel(x + d.x, y + d.y)[c]));
          }
        }
        const float count = image.pixel(x, y)[3];
        (step > 0.05f ? outline : flat) += count;
        (step > 0.05f ? outlinePixels : flatPixels) += 1;
      }
    }
    CAPTURE(outline / outlinePixels);
    CAPTURE(flat / flatPixels);
    // 2.9x (3.6x per pixel, 2.8x capped at 4x); 1.5x without.
    CHECK(outline / outlinePixels > 2.4 * flat / flatPixels);
  }

  TEST_CASE("with edge samples the estimate stays honest on a glass scene at a mean of 2") {
    // default.json's error at a few samples sits at the outlines of its glass
    // and mirror spheres, where the edge round adds samples. Pooled with the
    // flat pixels' noise, those pixels made the estimate 1.49x the truth here
    // (three seeds); measured apart, 1.18x; with the edges found from every
    // pixel's first sample (neighbourContrast), 1.00x.
    Scene scene = test::projectScene("default.json");
    const ToneMapping mapping = toneMappingFor(scene);
    RenderOptions reference;
    reference.sampler = SamplerKind::Sobol;
    reference.samplesPerPixel = 512;
    reference.width = 128;
    reference.height = 96;
    reference.seed = 999;
    const ImageF truth = test::render(scene, reference);
    RenderOptions options = reference;
    options.samplesPerPixel = 2;
    options.adaptive = true;
    double truthSquared = 0, estimateSquared = 0;
    for (uint32_t seed = 1; seed <= 3; ++seed) {
      options.seed = seed;
      RenderStats stats;
      const double error = displayRmse(test::render(scene, options, &stats), truth, mapping);
      REQUIRE(stats.rmseEstimate.has_value());
      truthSquared += error * error;
      estimateSquared += *stats.rmseEstimate * *stats.rmseEstimate;
    }
    CAPTURE(std::sqrt(truthSquared / 3));
    CAPTURE(std::sqrt(estimateSquared / 3));
    CHECK(std::sqrt(estimateSquared / truthSquared) < 1.12);
    CHECK(std::sqrt(estimateSquared / truthSquared) > 0.88);
  }

  TEST_CASE("a measurement of the changed tiles alone equals a measurement of every tile") {
    // 24x16 pixels, 3x2 tiles, every pixel with both halves; tiles 1 and 4
    // change between the measurements.
    const uint32_t width = 24, height = 16;
    SampleSums sums{width, height, std::vector<glm::vec4>(width * height),
                    std::vector<glm::vec4>(width * height)};
    auto fill = [&](uint32_t x0, uint32_t y0, float spread) {
      for (uint32_t y = y0; y < y0 + 8; ++y) {
        for (uint32_t x = x0; x < x0 + 8; ++x) {
          const size_t i = y * width + x;
          const float odd = 0.3f + spread * float((x * 7 + y * 3) % 5);
          sums.odd[i] = glm::vec4(glm::vec3(2 * odd), 2);
          sums.all[i] = sums.odd[i] + glm::vec4(glm::vec3(0.8f), 2);
        }
      }
    };
    for (uint32_t tile = 0; tile < 6; ++tile) fill(tile % 3 * 8, tile / 3 * 8, 0.01f * float(tile));
    const VkDeviceSize bytes = sums.all.size() * sizeof(glm::vec4);
    Buffer all(test::gpu(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Buffer odd(test::gpu(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    auto upload = [&] {
      all.upload(sums.all.data(), bytes);
      odd.upload(sums.odd.data(), bytes);
    };
    auto sameTiles = [](const std::vector<gpu::GpuTileNoise>& a,
                        const std::vector<gpu::GpuTileNoise>& b) {
      return a.size() == b.size() &&
             std::memcmp(a.data(), b.data(), a.size() * sizeof(gpu::GpuTileNoise)) == 0;
    };
    const PixelRegion whole{0, 0, width, height};
    upload();
    TileNoiseKernel listed(test::gpu(), test::shaderCompiler(), width, height);
    const std::vector<gpu::GpuTileNoise> before = listed.measure(all, odd, nullptr, whole, {});
    fill(8, 0, 0.2f);
    fill(8, 8, 0.3f);
    upload();
    const std::vector<uint32_t> changed{1, 4};
    const std::vector<gpu::GpuTileNoise> after =
        listed.measure(all, odd, nullptr, whole, {}, &changed);
    const std::vector<gpu::GpuTileNoise> expected = measureOnDevice(sums);
    CHECK(sameTiles(after, expected));
    CHECK_FALSE(sameTiles(before, expected));  // the test measures a change
    // Another display mapping measures every tile whatever the list says.
    ToneMapping brighter;
    brighter.exposure = 2.0f;
    brighter.srgbEncode = true;
    const std::vector<uint32_t> none;
    CHECK(sameTiles(listed.measure(all, odd, nullptr, whole, brighter, &none),
                    measureOnDevice(sums, brighter)));
    // So do other buffers: here the first sums again, in buffers of their own.
    for (uint32_t tile = 0; tile < 6; ++tile) fill(tile % 3 * 8, tile / 3 * 8, 0.01f * float(tile));
    Buffer otherAll(test::gpu(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    Buffer otherOdd(test::gpu(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    otherAll.upload(sums.all.data(), bytes);
    otherOdd.upload(sums.odd.data(), bytes);
    CHECK(sameTiles(listed.measure(otherAll, otherOdd, nullptr, whole, brighter, &none),
                    measureOnDevice(sums, brighter)));
    test::checkNoValidationMessages();
  }

  TEST_CASE("each round's measurement of the tiles it sampled equals a full measurement") {
    // The rounds measure only the tiles they sampled (the edge round's, and
    // the few that later rounds give samples); a stale tile would show in
    // the estimate, which sums every tile's figures.
    Scene scene = test::projectScene("default.json");
    const ToneMapping mapping = toneMappingFor(scene);
    const ProgressiveOptions options = adaptiveAccumulation(3);
    ProgressiveRenderer job(test::gpu(), test::shaderCompiler(), scene, options);
    const PixelRegion whole{0, 0, options.width, options.height};
    const AdaptivePlan geometry(options.width, options.height, whole);
    // Renders the rounds and returns their estimates.
    auto renderRounds = [&] {
      AdaptiveRounds rounds(options.width, options.height, whole, {3, 0.0, 1024});
      std::vector<double> estimates;
      std::set<size_t> sampledTiles;
      while (!rounds.finished()) {
        sampledTiles.insert(rounds.roundTiles().size());
        job.setSamplePlan(rounds.kernelRanges(), rounds.pixelExtras());
        test::gpu().submitAndWait([&](VkCommandBuffer commands) {
          job.recordPlannedSamples(commands, 0, options.height);
        });
        job.finishAdaptiveRound(rounds, mapping);
        REQUIRE(rounds.rmseEstimate());
        CHECK(geometry.measureNoise(job.tileNoise(mapping)).rmse == rounds.rmseEstimate());
        estimates.push_back(*rounds.rmseEstimate());
      }
      CHECK(*sampledTiles.begin() < geometry.tileCount());  // some round skipped tiles
      return estimates;
    };
    const std::vector<double> first = renderRounds();
    CHECK(first.size() >= 3);  // the first pass, the edge round and one more
    // After a reset (the viewer's, when the camera moves) no tile keeps the
    // last render's figures, nor a pixel its edge samples.
    job.reset();
    CHECK(renderRounds() == first);
    test::checkNoValidationMessages();
  }

  TEST_CASE("an open-ended adaptive render (a time budget alone) goes on past its budget") {
    const Scene scene = test::projectScene("study-arealight.json");
    RenderOptions options = adaptiveRender(2);
    RenderStats closed;
    test::render(scene, options, &closed);
    CHECK_FALSE(closed.stoppedEarly);
    CHECK(closed.meanSamples <= 2.0);

    // Stopped, as --time stops it, once past a mean of 8: the first budget
    // doubled twice. Without the doubling the render ends at 2 by itself.
    options.openEndedBudget = true;
    double reached = 0;
    int polls = 0;
    options.shouldStop = [&] { return reached > 8.0 || ++polls > 100000; };
    Renderer renderer(test::gpu(), test::shaderCompiler());
    RenderStats open;
    renderer.render(
        scene, options, [&](const RenderProgress& p) { reached = p.samplesDone; }, &open);
    test::checkNoValidationMessages();
    CHECK(open.stoppedEarly);
    CHECK(open.meanSamples > 8.0);
    CHECK(open.meanSamples <= 16.0);  // within the stage that passed 8
  }

  TEST_CASE("no pixel of an adaptive render passes the rounds' cap, its paired sample included") {
    const Scene scene = test::projectScene("study-arealight.json");
    const ToneMapping mapping = toneMappingFor(scene);
    const ProgressiveOptions options = adaptiveAccumulation(64);
    ProgressiveRenderer job(test::gpu(), test::shaderCompiler(), scene, options);
    const PixelRegion whole{0, 0, options.width, options.height};
    // A budget far above the cap: the noisy tiles all want more than it.
    AdaptiveRounds rounds(options.width, options.height, whole, {64, 0.0, 4});
    while (!rounds.finished()) {
      job.setSamplePlan(rounds.kernelRanges(), rounds.pixelExtras());
      test::gpu().submitAndWait(
          [&](VkCommandBuffer commands) { job.recordPlannedSamples(commands, 0, options.height); });
      job.finishAdaptiveRound(rounds, mapping);
    }
    const SampleSums sums = job.sampleSums();
    float most = 0;
    for (const glm::vec4& sum : sums.all) most = std::max(most, sum.w);
    CHECK(most == 4.0f);
    test::checkNoValidationMessages();
  }

  TEST_CASE("an adaptive render cannot be split into sample ranges") {
    Scene scene = test::projectScene("study-thinlens.json");
    RenderOptions options = adaptiveRender(16);
    options.firstSample = 8;
    CHECK_THROWS_AS(test::render(scene, options), Error);
  }
}
