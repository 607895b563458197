#include "render/AdaptiveSampling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "util/Error.hpp"

namespace rt {
namespace {

// Tiles aim a little below the target (MSE 0.9x, RMSE 0.95x), so that the
// round after a plan usually reaches it instead of falling just short. The
// plans aimed at 0.81x the MSE before their prediction was calibrated
// (predictionBias), and ended at 0.75-0.8x the target RMSE.
constexpr double kTargetMargin = 0.9;
// A tile's noise is raised to this fraction of its noisiest neighbour's.
constexpr double kNeighbourShare = 0.25;
// A round costs a dispatch, the tiles' noise measurement and the allocation
// whatever its size (about 3.5 ms on lavapipe at 320x240, measured when the
// sums were still read back and measured on the host; the device's
// measurement costs about the same there): the last rounds of a render, which add a few
// samples to a few tiles, cost more time than their samples. A round adding
// under this share of the samples so far ends the render instead (with
// 0.5%, a render to a mean of 4 took 5 rounds and 1.2x the time of a
// uniform one; with 1%, 4 rounds and the same time, best of 5: 0.052 s
// against 0.051 s; 2% left 2% of the budget unspent).
constexpr double kMinRoundShare = 0.01;
// A round aimed at a target adds at least this share of the samples so far
// (within the budget): the calibrated prediction can stall short of the
// target, each plan smaller than the last (the common scene at 160x120 and
// RMSE 0.01: rounds of +0.09 and +0.03 samples a pixel, then one under
// kMinRoundShare ended the render at an estimate of 0.0103; with 15% it
// reached 0.0096 in the next round).
constexpr double kMinTargetStep = 0.15;
// The edge round counts this share of a pixel's neighbour contrast as noise:
// a pixel that an edge crosses at coverage p has a one-sample variance of
// p (1 - p) times the squared contrast, at most a quarter of it; the pixel's
// mean after one sample differs from one neighbour by the whole contrast.
// A half simulated better than a quarter (bench/adaptive_bound.py).
constexpr double kContrastShare = 0.5;

// How much the allocation's prediction (its tiles' noise over their counts)
// exceeds the image's estimate, as a ratio of MSEs: the tiles' noise is
// raised towards their neighbours' (dilatedTiles), so a plan aimed at the
// target by its prediction ended below it (the thin-lens study at RMSE 0.01:
// prediction 0.0228 against an estimate of 0.0209 in its second round). The
// target is scaled by it. Targets 0.01, 0.005, 0.003 on the two studies,
// the common scene and default.json (320x240) took 2.0-6.2, 4.9-14.3 and
// 8.7-26.9 samples a pixel instead of 2.6-7.2, 6.3-17.2 and 9.8-30.6, every
// estimate at or below its target (with kMinTargetStep).
double predictionBias(const NoiseMeasurement& noise) {
  const double predicted = predictedMse(noise.tiles);
  if (!noise.rmse || *noise.rmse <= 0 || predicted <= 0) return 1;
  return predicted / (*noise.rmse * *noise.rmse);
}

constexpr uint32_t kPairBlockWidth = RT_ADAPTIVE_PAIR_BLOCK_WIDTH;
constexpr uint32_t kPairBlockHeight = RT_ADAPTIVE_PAIR_BLOCK_HEIGHT;

// Pixels of the region inside the rectangle at (x, y).
uint32_t overlap(const PixelRegion& region, uint32_t x, uint32_t y, uint32_t width,
                 uint32_t height) {
  const uint32_t x0 = std::max(x, region.x), x1 = std::min(x + width, region.x + region.width);
  const uint32_t y0 = std::max(y, region.y), y1 = std::min(y + height, region.y + region.height);
  return x0 < x1 && y0 < y1 ? (x1 - x0) * (y1 - y0) : 0;
}

// A tile as the allocation sees it: for the multiplier c of the allocation
// n = c * sqrt(v / cost) it ends with clamp(c * rate, low, high) samples per
// pixel, never fewer than it has nor more than allowed. Tiles outside the
// region have no pixels and count for nothing.
struct TilePlan {
  double pixels, variance, rate, low, high;
  double samplesAt(double c) const { return rate > 0 ? std::clamp(c * rate, low, high) : low; }
  // The tile's samples move with c, from c = low / rate to high / rate (a
  // tile without samples has no estimate and gets none).
  bool moves() const { return pixels > 0 && rate > 0 && low > 0 && low < high; }
};

std::vector<TilePlan> tilePlans(const std::vector<TileNoise>& tiles, uint32_t maxSamples) {
  std::vector<TilePlan> plans;
  plans.reserve(tiles.size());
  for (const TileNoise& t : tiles) {
    const double weight = t.weight > 0 ? t.weight : t.variance;
    plans.push_back({double(t.pixels), t.variance, std::sqrt(weight / t.cost), double(t.samples),
                     double(std::max(maxSamples, t.samples))});
  }
  return plans;
}

double mseAt(const std::vector<TilePlan>& plans, double c) {
  double sum = 0;
  double pixels = 0;
  for (const TilePlan& t : plans) {
    pixels += t.pixels;
    if (t.variance > 0 && t.pixels > 0) sum += t.pixels * t.variance / t.samplesAt(c);
  }
  return pixels > 0 ? sum / pixels : 0;
}

// Where the slope of a piecewise linear function changes.
struct Kink {
  double at;
  double slopeChange;
};

// The largest x >= 0 with f(x) <= level, for the continuous, nondecreasing,
// piecewise linear f(x) = start + sum over kinks of slopeChange * max(0, x - at)
// (infinity if f never exceeds level, 0 if f(0) does). A selection, not a
// sort nor a bisection: each step evaluates f at the median of the kinks
// left and keeps the half on the crossing's side, O(n) in all. The bisection
// it replaced evaluated all 32 400 tiles of a 1920x1080 image 80 times, a
// sort of the kinks took longer still.
double largestAtOrBelow(std::vector<Kink> kinks, double start, double level) {
  if (start > level) return 0;
  // Below `lower` f is known to stay at or below the level; the kinks there
  // add slopeBelow * x - offsetBelow to f(x) for every x above them.
  double lower = 0, slopeBelow = 0, offsetBelow = 0;
  bool crossed = false;  // some kink above `lower` has f above the level
  auto first = kinks.begin(), last = kinks.end();
  while (first != last) {
    auto pivot = first + (last - first) / 2;
    std::nth_element(first, pivot, last, [](const Kink& a, const Kink& b) { return a.at < b.at; });
    double slope = slopeBelow, offset = offsetBelow;
    for (auto k = first; k != pivot; ++k) {
      slope += k->slopeChange;
      offset += k->slopeChange * k->at;
    }
    if (start + slope * pivot->at - offset <= level) {
      lower = pivot->at;
      slopeBelow = slope + pivot->slopeChange;
      offsetBelow = offset + pivot->slopeChange * pivot->at;
      first = pivot + 1;
    } else {
      crossed = true;
      last = pivot;
    }
  }
  // f is linear from `lower` to the next kink; every tile's kinks come in
  // pairs that cancel, so it is flat after the last.
  if (!crossed) return std::numeric_limits<double>::infinity();
  const double atLower = start + slopeBelow * lower - offsetBelow;
  return lower + (level - atLower) / slopeBelow;
}

// The largest multiplier whose plan adds at most `budget` pixel-samples: the
// spend sum p * (clamp(c * rate, low, high) - low) rises linearly in c while
// a tile's samples move, from c = low / rate to c = high / rate.
double multiplierForBudget(const std::vector<TilePlan>& plans, double budget) {
  std::vector<Kink> kinks;
  kinks.reserve(2 * plans.size());
  for (const TilePlan& t : plans) {
    if (!t.moves()) continue;
    kinks.push_back({t.low / t.rate, t.pixels * t.rate});
    kinks.push_back({t.high / t.rate, -t.pixels * t.rate});
  }
  return largestAtOrBelow(std::move(kinks), 0, budget);
}

// The smallest multiplier whose plan predicts a mean squared error of at most
// `mse`. In u = 1 / c the prediction sum p * v / clamp(c * rate, low, high) / P
// rises: from every tile at its highest count at u = 0, linearly in u while a
// tile's samples move (p * v * u / rate), from u = rate / high to rate / low.
double multiplierForMse(const std::vector<TilePlan>& plans, double mse) {
  double pixels = 0, atHighest = 0;
  std::vector<Kink> kinks;
  kinks.reserve(2 * plans.size());
  for (const TilePlan& t : plans) {
    pixels += t.pixels;
    if (t.pixels == 0 || t.variance <= 0) continue;
    atHighest += t.pixels * t.variance / t.high;
    if (!t.moves()) continue;
    const double slope = t.pixels * t.variance / t.rate;
    kinks.push_back({t.rate / t.high, slope});
    kinks.push_back({t.rate / t.low, -slope});
  }
  if (pixels == 0) return 0;
  // Scale the slopes instead of the level, so that the sums stay as above.
  for (Kink& kink : kinks) kink.slopeChange /= pixels;
  return 1 / largestAtOrBelow(std::move(kinks), atHighest / pixels, mse);
}

}  // namespace

double predictedMse(const std::vector<TileNoise>& tiles) { return mseAt(tilePlans(tiles, 0), 0); }

std::vector<float> neighbourContrast(const SampleSums& sums, const ToneMapping& mapping,
                                     const PixelRegion& region) {
  std::vector<glm::vec3> shown(sums.all.size());
  for (uint32_t y = region.y; y < region.y + region.height; ++y) {
    for (uint32_t x = region.x; x < region.x + region.width; ++x) {
      const size_t pixel = size_t(y) * sums.width + x;
      const glm::vec4 sum = sums.all[pixel] - sums.odd[pixel];
      for (int c = 0; c < 3; ++c) {
        shown[pixel][c] = sum.w > 0 ? displayValue(sum[c] / sum.w, mapping) : 0.0f;
      }
    }
  }
  std::vector<float> contrast(sums.all.size(), 0.0f);
  auto compare = [&](size_t a, size_t b) {
    const glm::vec3 d = shown[a] - shown[b];
    const float squared = glm::dot(d, d) / 3.0f;
    contrast[a] = std::max(contrast[a], squared);
    contrast[b] = std::max(contrast[b], squared);
  };
  for (uint32_t y = region.y; y < region.y + region.height; ++y) {
    for (uint32_t x = region.x; x < region.x + region.width; ++x) {
      const size_t pixel = size_t(y) * sums.width + x;
      if (x + 1 < region.x + region.width) compare(pixel, pixel + 1);
      if (y + 1 < region.y + region.height) compare(pixel, pixel + sums.width);
    }
  }
  return contrast;
}

std::vector<uint32_t> allocateSamples(const std::vector<TileNoise>& tiles,
                                      const AllocationGoal& goal) {
  std::vector<uint32_t> added(tiles.size(), 0);
  if (goal.sampleBudget < 1) return added;
  const std::vector<TilePlan> plans = tilePlans(tiles, goal.maxSamples);
  double c = multiplierForBudget(plans, goal.sampleBudget);
  if (goal.targetMse > 0) {
    if (mseAt(plans, 0) <= goal.targetMse) return added;
    const double step = multiplierForBudget(plans, std::min(goal.sampleBudget, goal.minimumSpend));
    c = std::min(c, std::max(step, multiplierForMse(plans, goal.targetMse * kTargetMargin)));
  }
  for (size_t i = 0; i < tiles.size(); ++i) {
    const TileNoise& t = tiles[i];
    if (t.pixels == 0 || t.samples == 0) continue;
    // Rounded down: the rounds never spend more than the budget.
    double wanted = std::floor(plans[i].samplesAt(c)) - t.samples;
    added[i] =
        static_cast<uint32_t>(std::clamp(wanted, 0.0, double(t.samples) * (goal.growth - 1)));
  }
  return added;
}

AdaptivePlan::AdaptivePlan(uint32_t width, uint32_t height, const PixelRegion& region)
    : tilesPerRow_(gpu::adaptiveTileGrid({width, height}).x), width_(width), region_(region) {
  const uint32_t rows = gpu::adaptiveTileGrid({width, height}).y;
  pixels_.assign(size_t(tilesPerRow_) * rows, 0);
  paired_.assign(pixels_.size(), 0);
  samples_.assign(pixels_.size(), 0);
  edgeSamples_.assign(pixels_.size(), 0);
  rays_.assign(pixels_.size(), 0);
  // Per tile and paired block, not per pixel (a walk over 2 million pixels
  // cost 5 ms at 1920x1080).
  const uint32_t blocksPerRow = kTileSize / kPairBlockWidth;
  for (uint32_t ty = 0; ty < rows; ++ty) {
    for (uint32_t tx = 0; tx < tilesPerRow_; ++tx) {
      const size_t tile = size_t(ty) * tilesPerRow_ + tx;
      pixels_[tile] = overlap(region, tx * kTileSize, ty * kTileSize, kTileSize, kTileSize);
      if (pixels_[tile] == 0) continue;
      const glm::uvec2 blocks = gpu::adaptivePairedBlocks(tx, ty);
      for (uint32_t block : {blocks.x, blocks.y}) {
        paired_[tile] += overlap(region, tx * kTileSize + block % blocksPerRow * kPairBlockWidth,
                                 ty * kTileSize + block / blocksPerRow * kPairBlockHeight,
                                 kPairBlockWidth, kPairBlockHeight);
      }
    }
  }
  regionPixels_ = uint64_t(region.width) * region.height;
}

size_t AdaptivePlan::tileOf(uint32_t x, uint32_t y) const {
  return size_t(y / kTileSize) * tilesPerRow_ + x / kTileSize;
}

// The edge round's pixels are grouped by their tile and their contrast's
// power of two: one unit of the allocation per group (pixels of a group get
// the same count), not one per pixel. At 1920x1080 the allocation over every
// pixel took 190 ms of host time (rt-bench-adaptive).
constexpr int kContrastLevels = 22;  // 0: below 2^-20; then one per power of two to 1

int contrastLevel(float contrast) {
  if (!(contrast >= 0x1p-20f)) return 0;
  int exponent = 0;
  std::frexp(contrast, &exponent);
  return std::clamp(exponent + 20, 1, kContrastLevels - 1);
}

template <typename F>
void AdaptivePlan::forEachPixelIn(uint32_t x, uint32_t y, uint32_t width, uint32_t height,
                                  F visit) const {
  const uint32_t x0 = std::max(x, region_.x), x1 = std::min(x + width, region_.x + region_.width);
  const uint32_t y0 = std::max(y, region_.y), y1 = std::min(y + height, region_.y + region_.height);
  for (uint32_t py = y0; py < y1; ++py) {
    for (uint32_t px = x0; px < x1; ++px) visit(size_t(py) * width_ + px);
  }
}

std::vector<float> AdaptivePlan::blockMeans(const std::vector<float>& values) const {
  std::vector<float> means(values.size(), 0.0f);
  for (uint32_t by = region_.y / kPairBlockHeight * kPairBlockHeight;
       by < region_.y + region_.height; by += kPairBlockHeight) {
    for (uint32_t bx = region_.x / kPairBlockWidth * kPairBlockWidth;
         bx < region_.x + region_.width; bx += kPairBlockWidth) {
      const uint32_t pixels = overlap(region_, bx, by, kPairBlockWidth, kPairBlockHeight);
      double sum = 0;
      forEachPixelIn(bx, by, kPairBlockWidth, kPairBlockHeight,
                     [&](size_t pixel) { sum += values[pixel]; });
      const float mean = static_cast<float>(sum / double(pixels));
      forEachPixelIn(bx, by, kPairBlockWidth, kPairBlockHeight,
                     [&](size_t pixel) { means[pixel] = mean; });
    }
  }
  return means;
}

EdgeRound AdaptivePlan::edgeRound(const std::vector<TileNoise>& tiles,
                                  const std::vector<float>& pixelContrast,
                                  const AllocationGoal& goal) const {
  const std::vector<float> contrast = blockMeans(pixelContrast);
  // Per tile, its pixels' levels and each level's unit.
  struct Group {
    uint32_t pixels = 0;
    double contrastSum = 0;
    size_t unit = 0;
  };
  std::vector<TileNoise> units;
  std::vector<std::array<Group, kContrastLevels>> groups(pixels_.size());
  auto forEachPixel = [&](size_t tile, auto visit) {
    forEachPixelIn(uint32_t(tile % tilesPerRow_) * kTileSize,
                   uint32_t(tile / tilesPerRow_) * kTileSize, kTileSize, kTileSize, visit);
  };
  for (size_t tile = 0; tile < pixels_.size(); ++tile) {
    if (pixels_[tile] == 0) continue;
    forEachPixel(tile, [&](size_t pixel) {
      Group& group = groups[tile][contrastLevel(contrast[pixel])];
      group.pixels += 1;
      group.contrastSum += contrast[pixel];
    });
    // A paired pixel's extra first-round sample stays on top of its count,
    // as in the rounds per tile.
    for (Group& group : groups[tile]) {
      if (group.pixels == 0) continue;
      group.unit = units.size();
      const double meanContrast = group.contrastSum / group.pixels;
      const TileNoise& noise = tiles[tile];
      units.push_back({group.pixels, noise.samples, noise.variance, noise.cost,
                       noise.variance + kContrastShare * meanContrast});
    }
  }
  // No growth cap for a budget: a pixel's contrast does not fall with its
  // samples as a tile's noise estimate steadies, so a later round would
  // decide the same. Capped at 4x (and the rest left to the rounds per tile,
  // which spread it over whole tiles) default.json at a mean of 3 had an RMSE
  // of 0.0065, uncapped 0.0047 (three seeds, 320x240). A target keeps the
  // cap: the contrast steers the samples but predicts no error, and an
  // uncapped plan aimed at RMSE 0.01 took default.json to 7.1 samples a
  // pixel and 0.0022 where 2.6 reach 0.0082 with the cap.
  AllocationGoal edgeGoal = goal;
  if (goal.targetMse == 0) edgeGoal.growth = std::numeric_limits<double>::infinity();
  const std::vector<uint32_t> added = allocateSamples(units, edgeGoal);
  EdgeRound round;
  round.common.assign(pixels_.size(), 0);
  round.pixels.assign(contrast.size(), 0);
  round.extraSums.assign(pixels_.size(), 0);
  for (size_t tile = 0; tile < pixels_.size(); ++tile) {
    if (pixels_[tile] == 0) continue;
    uint32_t common = std::numeric_limits<uint32_t>::max();
    for (const Group& group : groups[tile]) {
      if (group.pixels > 0) common = std::min(common, added[group.unit]);
    }
    round.common[tile] = common;
    forEachPixel(tile, [&](size_t pixel) {
      const uint32_t extra = added[groups[tile][contrastLevel(contrast[pixel])].unit] - common;
      round.pixels[pixel] = extra;
      round.extraSums[tile] += extra;
    });
  }
  return round;
}

void AdaptivePlan::addEdgeRound(const EdgeRound& round, const std::vector<uint32_t>& rays) {
  if (edgesRendered_) throw Error("adaptive round: the edges have their samples");
  addRound(round.common, rays);
  for (size_t i = 0; i < samples_.size(); ++i) edgeSamples_[i] += round.extraSums[i];
  edgesRendered_ = true;
}

std::vector<uint32_t> AdaptivePlan::uniformRound(uint32_t count) const {
  std::vector<uint32_t> added(pixels_.size(), 0);
  for (size_t i = 0; i < added.size(); ++i) added[i] = pixels_[i] > 0 ? count : 0;
  return added;
}

template <typename F>
void AdaptivePlan::forEachNeighbour(size_t tile, F visit) const {
  const size_t rows = pixels_.size() / tilesPerRow_;
  const size_t ty = tile / tilesPerRow_, tx = tile % tilesPerRow_;
  for (size_t ny = ty > 0 ? ty - 1 : 0; ny <= std::min(ty + 1, rows - 1); ++ny) {
    for (size_t nx = tx > 0 ? tx - 1 : 0; nx <= std::min<size_t>(tx + 1, tilesPerRow_ - 1); ++nx) {
      visit(ny * tilesPerRow_ + nx);
    }
  }
}

bool AdaptivePlan::poolTiles(std::vector<double>& variance,
                             const std::vector<uint32_t>& measured) const {
  std::vector<double> own = variance;
  for (size_t i = 0; i < own.size(); ++i) {
    if (measured[i] > 0) own[i] /= measured[i];
  }
  bool complete = true;
  for (size_t i = 0; i < own.size(); ++i) {
    variance[i] = own[i];
    if (measured[i] > 0 || pixels_[i] == 0) continue;
    // A tile at the image's edge whose paired blocks fall outside it: its
    // noisiest measured neighbour's noise.
    bool found = false;
    forEachNeighbour(i, [&](size_t j) {
      if (measured[j] == 0) return;
      variance[i] = found ? std::max(variance[i], own[j]) : own[j];
      found = true;
    });
    complete = complete && found;
  }
  return complete;
}

NoiseMeasurement AdaptivePlan::measureNoise(const std::vector<gpu::GpuTileNoise>& measured) const {
  if (measured.size() != pixels_.size()) throw Error("adaptive round: not one noise sum per tile");
  std::vector<double> variance(measured.size());
  std::vector<uint32_t> counts(measured.size());
  bool complete = true;
  for (size_t i = 0; i < measured.size(); ++i) {
    variance[i] = measured[i].varianceSum;
    counts[i] = measured[i].pooled;
    if (counts[i] == 0) {
      // Every measured pixel has edge samples: their noise, which is the
      // larger, for the others too.
      variance[i] = measured[i].edgeVarianceSum;
      counts[i] = measured[i].measured;
    }
    complete = complete && measured[i].unsampled == 0;
  }
  complete = poolTiles(variance, counts) && complete;
  // The allocation plans with the mean over all of a tile's pixels: the
  // pooled noise for the pixels without edge samples, their own for those with.
  std::vector<double> tileVariance = variance;
  for (size_t i = 0; i < measured.size(); ++i) {
    if (pixels_[i] == 0) continue;
    const uint32_t edges = measured[i].measured - measured[i].pooled;
    tileVariance[i] =
        (variance[i] * (pixels_[i] - edges) + measured[i].edgeVarianceSum) / double(pixels_[i]);
  }
  NoiseMeasurement noise;
  noise.tiles = dilatedTiles(tileVariance);
  if (!complete || regionPixels_ == 0) return noise;
  // Pixels with both halves count their own error; the others their tile's
  // noise over their sample count.
  double squaredSum = 0;
  for (size_t i = 0; i < measured.size(); ++i) {
    squaredSum += double(measured[i].squaredSum) + variance[i] * measured[i].inverseCountSum;
  }
  noise.rmse = std::sqrt(squaredSum / double(regionPixels_));
  noise.sampleVariance = std::move(variance);
  return noise;
}

std::vector<float> AdaptivePlan::errorImage(const SampleSums& sums, const ToneMapping& mapping,
                                            const std::vector<double>& sampleVariance) const {
  std::vector<float> image(sums.all.size(), -1.0f);
  for (uint32_t y = region_.y; y < region_.y + region_.height; ++y) {
    for (uint32_t x = region_.x; x < region_.x + region_.width; ++x) {
      const size_t pixel = size_t(y) * width_ + x;
      const float count = sums.all[pixel].w;
      double squared = -1;
      if (std::optional<double> own = estimatePixelSquaredError(sums, pixel, mapping)) {
        squared = *own;
      } else if (count > 0 && !sampleVariance.empty()) {
        squared = sampleVariance[tileOf(x, y)] / count;
      }
      if (squared >= 0) image[pixel] = static_cast<float>(std::sqrt(squared));
    }
  }
  return image;
}

std::vector<TileNoise> AdaptivePlan::dilatedTiles(const std::vector<double>& variance) const {
  std::vector<TileNoise> tiles(pixels_.size());
  for (size_t i = 0; i < tiles.size(); ++i) {
    TileNoise& tile = tiles[i];
    tile.pixels = pixels_[i];
    tile.samples = samples_[i];
    if (tile.pixels == 0) continue;
    // Every sample traces at least its camera ray.
    const double samples = tileSamples(i);
    tile.cost = samples > 0 ? std::max(double(rays_[i]) / samples, 1.0) : 1.0;
    double neighbour = 0;
    forEachNeighbour(i, [&](size_t j) {
      if (pixels_[j] > 0) neighbour = std::max(neighbour, variance[j]);
    });
    tile.variance = std::max(variance[i], kNeighbourShare * neighbour);
  }
  return tiles;
}

void AdaptivePlan::addRound(const std::vector<uint32_t>& added, const std::vector<uint32_t>& rays,
                            bool paired) {
  if (rays.size() != samples_.size()) throw Error("adaptive round: not one ray count per tile");
  if (paired && pairsRendered_) throw Error("adaptive round: the pairs have their sample");
  for (size_t i = 0; i < samples_.size(); ++i) {
    samples_[i] += added[i];
    rays_[i] += rays[i];
  }
  pairsRendered_ = pairsRendered_ || paired;
}

std::vector<glm::uvec2> AdaptivePlan::kernelRanges(const std::vector<uint32_t>& added, bool paired,
                                                   bool edge) const {
  std::vector<glm::uvec2> ranges(samples_.size(), glm::uvec2(0));
  for (size_t i = 0; i < ranges.size(); ++i) {
    if (pixels_[i] == 0) continue;
    ranges[i] = {samples_[i], added[i]};
    if (pairsRendered_) ranges[i].x |= RT_ADAPTIVE_PAIRED_FLAG;
    if (edgesRendered_) ranges[i].x |= RT_ADAPTIVE_EXTRAS_FLAG;
    if (paired) ranges[i].y |= RT_ADAPTIVE_PAIRED_FLAG;
    if (edge) ranges[i].y |= RT_ADAPTIVE_EXTRAS_FLAG;
  }
  return ranges;
}

double AdaptivePlan::tileSamples(size_t tile) const {
  return double(pixels_[tile]) * samples_[tile] + (pairsRendered_ ? paired_[tile] : 0) +
         double(edgeSamples_[tile]);
}

uint64_t AdaptivePlan::pixelSamples() const {
  uint64_t total = 0;
  for (size_t i = 0; i < samples_.size(); ++i) total += static_cast<uint64_t>(tileSamples(i));
  return total;
}

AdaptiveRounds::AdaptiveRounds(uint32_t width, uint32_t height, const PixelRegion& region,
                               const Goal& goal)
    : plan_(width, height, region),
      goal_(goal),
      round_(plan_.uniformRound(std::min(goal.meanSamples, kAdaptiveFirstPass))),
      pairRound_(goal.meanSamples >= 2) {
  finished_ = goal.meanSamples == 0 || plan_.regionPixels() == 0;
}

uint32_t AdaptiveRounds::bandEnd(uint32_t y, double work) const {
  const uint32_t tile = AdaptivePlan::kTileSize;
  const PixelRegion& region = plan_.region();
  const uint32_t bottom = region.y + region.height;
  double sum = 0;
  uint32_t end = y;
  while (end < bottom && (end == y || sum < work)) {
    uint32_t next = std::min((end / tile + 1) * tile, bottom);
    sum += rowWork(end, next);
    end = next;
  }
  return end;
}

double AdaptiveRounds::rowWork(uint32_t y, uint32_t end) const {
  const uint32_t tile = AdaptivePlan::kTileSize;
  const PixelRegion& region = plan_.region();
  double work = 0;
  for (uint32_t row = y; row < end;) {
    uint32_t next = std::min((row / tile + 1) * tile, end);
    for (uint32_t tx = region.x / tile; tx * tile < region.x + region.width; ++tx) {
      uint32_t x0 = std::max(tx * tile, region.x);
      uint32_t x1 = std::min((tx + 1) * tile, region.x + region.width);
      const size_t index = size_t(row / tile) * plan_.tilesPerRow() + tx;
      // The paired pixels' extra sample: one pixel in four.
      const uint32_t samples = round_[index];
      double perPixel = samples + (pairRound_ && samples > 0 ? 0.25 : 0.0);
      if (edgeRound_ && plan_.tilePixels(index) > 0) {
        perPixel = edgeRound_->common[index] +
                   double(edgeRound_->extraSums[index]) / plan_.tilePixels(index);
      }
      work += perPixel * (x1 - x0) * (next - row);
    }
    row = next;
  }
  return work;
}

std::vector<uint32_t> AdaptiveRounds::roundTiles() const {
  std::vector<uint32_t> tiles;
  for (uint32_t i = 0; i < plan_.tileCount(); ++i) {
    if (plan_.tilePixels(i) == 0) continue;
    const bool sampled = edgeRound_ ? edgeRound_->common[i] > 0 || edgeRound_->extraSums[i] > 0
                                    : round_[i] > 0 || pairRound_;
    if (sampled) tiles.push_back(i);
  }
  return tiles;
}

const std::vector<uint32_t>& AdaptiveRounds::pixelExtras() const {
  static const std::vector<uint32_t> none;
  return edgeRound_ ? edgeRound_->pixels : none;
}

void AdaptiveRounds::finishRound(const std::vector<gpu::GpuTileNoise>& measured,
                                 const std::vector<uint32_t>& tileRays, const ImageReader* image) {
  if (edgeRound_) {
    plan_.addEdgeRound(*edgeRound_, tileRays);
  } else {
    plan_.addRound(round_, tileRays, pairRound_);
  }
  const bool firstRound = pairRound_;
  pairRound_ = false;
  NoiseMeasurement noise = plan_.measureNoise(measured);
  estimate_ = noise.rmse;
  planRound(noise, firstRound ? image : nullptr);
  while (finished_ && goal_.openEnded && !reachedTarget() && goal_.meanSamples < goal_.maxSamples) {
    goal_.meanSamples = std::min(2 * goal_.meanSamples, goal_.maxSamples);
    planRound(noise, nullptr);
  }
  sampleVariance_ = std::move(noise.sampleVariance);
}

void AdaptiveRounds::planRound(const NoiseMeasurement& noise, const ImageReader* image) {
  AllocationGoal next;
  next.targetMse = goal_.targetRmse * goal_.targetRmse * predictionBias(noise);
  next.sampleBudget =
      double(goal_.meanSamples) * double(plan_.regionPixels()) - double(plan_.pixelSamples());
  // A paired pixel's extra first-pass sample stays on top of its tile's count.
  next.maxSamples = std::max(goal_.maxSamples, 2u) - 1;
  next.minimumSpend = kMinTargetStep * double(plan_.pixelSamples());
  // The round just rendered (an edge round too) is in the plan: a new one.
  round_.assign(round_.size(), 0);
  edgeRound_.reset();
  if (!reachedTarget() && image) {
    edgeRound_ = plan_.edgeRound(
        noise.tiles, neighbourContrast(image->read(), image->mapping, plan_.region()), next);
  } else if (!reachedTarget()) {
    round_ = allocateSamples(noise.tiles, next);
  }
  const PixelRegion& region = plan_.region();
  const double work = rowWork(region.y, region.y + region.height);
  finished_ = work < kMinRoundShare * double(plan_.pixelSamples());
}

void AdaptiveRounds::measureStop(const std::vector<gpu::GpuTileNoise>& measured) {
  // The pooled noise and the estimate come from the device's sums alone, so
  // they hold for a round rendered in part; the plan's counts do not.
  NoiseMeasurement noise = plan_.measureNoise(measured);
  estimate_ = noise.rmse;
  sampleVariance_ = std::move(noise.sampleVariance);
  round_.assign(round_.size(), 0);
  edgeRound_.reset();
  finished_ = true;
}

bool AdaptiveRounds::reachedTarget() const {
  return goal_.targetRmse > 0 && estimate_ && *estimate_ <= goal_.targetRmse;
}

double AdaptiveRounds::meanSamples() const {
  return double(plan_.pixelSamples()) / double(std::max<uint64_t>(plan_.regionPixels(), 1));
}

}  // namespace rt
