#include "render/AdaptiveSampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/Error.hpp"

namespace rt {
namespace {

// Tiles aim a little below the target, so that the round after a plan
// usually reaches it instead of falling just short.
constexpr double kTargetMargin = 0.9 * 0.9;
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
// A tile ends a round with at most this many times its samples: the next
// round decides again from more samples. Doubling needed a round per
// doubling (2, 4, 8, 16, 27 samples: 5 rounds); the pooled estimate of a
// 64-pixel tile is steady enough to allow four times.
constexpr double kGrowth = 4;

uint32_t divideRoundUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

// The samples per pixel tile `t` would end with for the multiplier c of the
// allocation n = c * sqrt(v / cost), never fewer than it has nor more than allowed.
double plannedSamples(const TileNoise& t, double c, uint32_t maxSamples) {
  double wanted = c * std::sqrt(t.variance / t.cost);
  return std::clamp(wanted, double(t.samples), double(std::max(maxSamples, t.samples)));
}

// A tile of the region as the search for the multiplier sees it: it ends
// with clamp(c * rate, low, high) samples per pixel (plannedSamples). The
// rates are worked out once: the search evaluates every tile about a hundred
// times a round, and at 1920x1080 (32 400 tiles) the square roots alone cost
// milliseconds a round.
struct TilePlan {
  double pixels, variance, rate, low, high;
  double samplesAt(double c) const { return std::clamp(c * rate, low, high); }
};

std::vector<TilePlan> tilePlans(const std::vector<TileNoise>& tiles, uint32_t maxSamples) {
  std::vector<TilePlan> plans;
  plans.reserve(tiles.size());
  for (const TileNoise& t : tiles) {
    if (t.pixels == 0) continue;
    plans.push_back({double(t.pixels), t.variance, std::sqrt(t.variance / t.cost),
                     double(t.samples), double(std::max(maxSamples, t.samples))});
  }
  return plans;
}

double mseAt(const std::vector<TilePlan>& plans, double c) {
  double sum = 0;
  double pixels = 0;
  for (const TilePlan& t : plans) {
    pixels += t.pixels;
    if (t.variance > 0) sum += t.pixels * t.variance / t.samplesAt(c);
  }
  return pixels > 0 ? sum / pixels : 0;
}

double spendAt(const std::vector<TilePlan>& plans, double c) {
  double spend = 0;
  for (const TilePlan& t : plans) spend += t.pixels * (t.samplesAt(c) - t.low);
  return spend;
}

// The multiplier where a monotone function of it crosses `level`, by
// bisection in log space: the largest c with f(c) <= level if f increases,
// the smallest c with f(c) <= level if it decreases.
template <typename F>
double solveMultiplier(F f, double level, bool increasing) {
  double lo = std::log(1e-9), hi = std::log(1e15);
  for (int i = 0; i < 80; ++i) {
    double mid = 0.5 * (lo + hi);
    bool below = f(std::exp(mid)) <= level;
    if (below == increasing) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return std::exp(increasing ? lo : hi);
}

}  // namespace

double predictedMse(const std::vector<TileNoise>& tiles) { return mseAt(tilePlans(tiles, 0), 0); }

std::vector<uint32_t> allocateSamples(const std::vector<TileNoise>& tiles,
                                      const AllocationGoal& goal) {
  std::vector<uint32_t> added(tiles.size(), 0);
  if (goal.sampleBudget < 1) return added;
  const uint32_t cap = goal.maxSamples;
  const std::vector<TilePlan> plans = tilePlans(tiles, cap);
  double c = solveMultiplier([&](double m) { return spendAt(plans, m); }, goal.sampleBudget, true);
  if (goal.targetMse > 0) {
    if (predictedMse(tiles) <= goal.targetMse) return added;
    double toTarget = solveMultiplier([&](double m) { return mseAt(plans, m); },
                                      goal.targetMse * kTargetMargin, false);
    c = std::min(c, toTarget);
  }
  for (size_t i = 0; i < tiles.size(); ++i) {
    const TileNoise& t = tiles[i];
    if (t.pixels == 0 || t.samples == 0) continue;
    // Rounded down: the rounds never spend more than the budget.
    double wanted = std::floor(plannedSamples(t, c, cap)) - t.samples;
    added[i] = static_cast<uint32_t>(std::clamp(wanted, 0.0, double(t.samples) * (kGrowth - 1)));
  }
  return added;
}

AdaptivePlan::AdaptivePlan(uint32_t width, uint32_t height, const PixelRegion& region)
    : tilesPerRow_(divideRoundUp(width, kTileSize)), width_(width), region_(region) {
  const uint32_t rows = divideRoundUp(height, kTileSize);
  pixels_.assign(size_t(tilesPerRow_) * rows, 0);
  paired_.assign(pixels_.size(), 0);
  samples_.assign(pixels_.size(), 0);
  rays_.assign(pixels_.size(), 0);
  for (uint32_t y = region.y; y < region.y + region.height; ++y) {
    for (uint32_t x = region.x; x < region.x + region.width; ++x) {
      ++pixels_[tileOf(x, y)];
      paired_[tileOf(x, y)] += gpu::adaptivePairedPixel(x, y);
    }
  }
  regionPixels_ = uint64_t(region.width) * region.height;
}

size_t AdaptivePlan::tileOf(uint32_t x, uint32_t y) const {
  return size_t(y / kTileSize) * tilesPerRow_ + x / kTileSize;
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
    counts[i] = measured[i].measured;
    complete = complete && measured[i].unsampled == 0;
  }
  complete = poolTiles(variance, counts) && complete;
  NoiseMeasurement noise;
  noise.tiles = dilatedTiles(variance);
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

std::vector<glm::uvec2> AdaptivePlan::kernelRanges(const std::vector<uint32_t>& added,
                                                   bool paired) const {
  std::vector<glm::uvec2> ranges(samples_.size(), glm::uvec2(0));
  for (size_t i = 0; i < ranges.size(); ++i) {
    if (pixels_[i] == 0) continue;
    ranges[i] = {samples_[i], added[i]};
    if (pairsRendered_) ranges[i].x |= RT_ADAPTIVE_PAIRED_FLAG;
    if (paired) ranges[i].y |= RT_ADAPTIVE_PAIRED_FLAG;
  }
  return ranges;
}

double AdaptivePlan::tileSamples(size_t tile) const {
  return double(pixels_[tile]) * samples_[tile] + (pairsRendered_ ? paired_[tile] : 0);
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
      // The paired pixels' extra sample: one pixel in four.
      const uint32_t samples = round_[size_t(row / tile) * plan_.tilesPerRow() + tx];
      const double extra = pairRound_ && samples > 0 ? 0.25 : 0.0;
      work += (samples + extra) * (x1 - x0) * (next - row);
    }
    row = next;
  }
  return work;
}

void AdaptiveRounds::finishRound(const std::vector<gpu::GpuTileNoise>& measured,
                                 const std::vector<uint32_t>& tileRays) {
  plan_.addRound(round_, tileRays, pairRound_);
  pairRound_ = false;
  NoiseMeasurement noise = plan_.measureNoise(measured);
  estimate_ = noise.rmse;
  sampleVariance_ = std::move(noise.sampleVariance);
  AllocationGoal next;
  next.targetMse = goal_.targetRmse * goal_.targetRmse;
  next.sampleBudget =
      double(goal_.meanSamples) * double(plan_.regionPixels()) - double(plan_.pixelSamples());
  next.maxSamples = goal_.maxSamples;
  round_ = reachedTarget() ? std::vector<uint32_t>(round_.size(), 0)
                           : allocateSamples(noise.tiles, next);
  const PixelRegion& region = plan_.region();
  const double work = rowWork(region.y, region.y + region.height);
  finished_ = work < kMinRoundShare * double(plan_.pixelSamples());
}

bool AdaptiveRounds::reachedTarget() const {
  return goal_.targetRmse > 0 && estimate_ && *estimate_ <= goal_.targetRmse;
}

double AdaptiveRounds::meanSamples() const {
  return double(plan_.pixelSamples()) / double(std::max<uint64_t>(plan_.regionPixels(), 1));
}

}  // namespace rt
