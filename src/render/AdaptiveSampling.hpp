// Adaptive sampling: where the next samples go. The image is cut into square
// tiles (RT_ADAPTIVE_TILE_SIZE pixels a side); after a uniform first pass,
// each round estimates every tile's noise from the even/odd replicates
// (ImageError.hpp) and gives more samples to the tiles where they lower the
// image's error most, until the estimated RMSE reaches the target or the
// sample budget is spent.
//
// Why these choices:
// - A first pass of one sample a pixel, and a second one on two of the
//   eight 4x2 blocks of every tile (adaptivePairedPixel in gpu_types.h):
//   1.25 samples a pixel instead of 2 measure each tile's noise from its 16
//   pairs, and the pixels with one sample take their tile's pooled noise.
//   The noise of a whole tile is what the allocation and the image's
//   estimate need; a first pass of two samples everywhere alone cost
//   0.45-0.66x of uniform jittered sampling's time to RMSE 0.01 on whole
//   images. At equal mean samples the true RMSE is lower at 2-4 samples on
//   all four scenes of README "Adaptive sampling".
// - Tiles, not pixels: one pixel's estimate has a few degrees of freedom and
//   is often near zero by chance; 64 pixels pooled are steady, so a tile does
//   not stop early because its few samples happened to agree. The noise of
//   each tile is also raised to a quarter of its noisiest neighbour's, so an
//   edge of a noisy area is never starved.
// - Samples in proportion to sqrt(v_i / c_i), v_i the noise variance of one
//   sample and c_i its cost (rays a sample, counted per tile by the kernel):
//   that allocation minimizes the render's time at a given mean squared
//   error of the image (Lagrange: minimize sum n_i c_i s.t. sum v_i / n_i =
//   const), the trade --target-rmse and `converge` measure. Without the cost
//   a glass tile, whose samples trace many rays, would get as many samples
//   as a matte one of the same noise at several times the price.
// - A tile at most quadruples its samples per round (the edge round excepted,
//   below), so that every decision is revisited with an estimate from more
//   samples.
// - One round per 4x2 block, the edge round, right after the first pass: a
//   tile's paired blocks see a quarter of its pixels and miss most edges
//   (silhouettes, reflected and refracted outlines, thin features), whose
//   pixels hold most of a sharp image's error at a few samples. Each pixel
//   of the region then counts with its tile's noise plus half the largest
//   squared difference between its first sample and a neighbour's (an edge
//   pixel's one-sample variance is at most a quarter of the contrast across
//   the edge), averaged over its 4x2 block, and the allocation runs over the
//   blocks, grouped per tile by their contrast's power of two. Simulated on
//   measured per-pixel errors (bench/adaptive_bound.py) the per-pixel
//   version took default.json's RMSE at a mean of 2 samples from 0.0109
//   (tiles alone) to 0.0039. Blocks, not pixels: a block is one run of
//   eight invocations, one SIMD vector on lavapipe, which runs as long as
//   its busiest pixel, so per pixel the edge round's samples cost 1.35x the
//   CPU time of the same count spread evenly (the area-light study); per
//   block the times to RMSE 0.01-0.003 fell by 5-19% on the four scenes of
//   README "Adaptive sampling". Later rounds are per tile again: contrast
//   does not fall with samples, noise does.
// - Decisions depend only on the accumulated samples at the end of each
//   round, never on timing: the image is a pure function of scene, options
//   and seed. They do depend on the whole image, so adaptive renders cannot
//   be split into sample ranges or regions and merged.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "gpu_types.h"
#include "imaging/ImageError.hpp"
#include "imaging/PixelRegion.hpp"
#include "io/Image.hpp"
#include "noise_types.h"

namespace rt {

// Samples per pixel of the uniform first round, besides the paired pixels'
// second one (needs a budget of at least 2: with 1 there is no estimate).
constexpr uint32_t kAdaptiveFirstPass = 1;

// One tile as the allocation sees it.
struct TileNoise {
  uint32_t pixels = 0;   // pixels of the rendered region in the tile (0: outside it)
  uint32_t samples = 0;  // samples per pixel so far (the paired pixels have one more)
  double variance = 0;   // display-space variance of one sample, mean over its pixels
  double cost = 1;       // what one sample costs: rays it traces, on average over the tile
  // When above 0, what the samples are spread by in place of `variance`,
  // which still predicts the error (the edge round's contrast steers samples
  // but is no measured noise).
  double weight = 0;
};

struct AllocationGoal {
  double targetMse = 0;     // plan to reach this image mean squared error (0: no target)
  double sampleBudget = 0;  // pixel-samples this and later rounds may add at most
  uint32_t maxSamples = 0;  // per pixel
  // A unit ends the round with at most this many times its samples, so that
  // the next round decides again from more samples. Doubling needed a round
  // per doubling (2, 4, 8, 16, 27 samples: 5 rounds); the pooled estimate of
  // a 64-pixel tile is steady enough to allow four times.
  double growth = 4;
  // With a target: spend at least this many pixel-samples (within the
  // budget) even when the prediction says fewer reach it.
  double minimumSpend = 0;
};

// Samples per pixel to add to each tile this round (0: none). All zero when
// the goal is met, the budget spent, or no tile has noise left to remove.
std::vector<uint32_t> allocateSamples(const std::vector<TileNoise>& tiles,
                                      const AllocationGoal& goal);

// Image mean squared error predicted for the tiles (1/n noise).
double predictedMse(const std::vector<TileNoise>& tiles);

// Per pixel (row-major over the image; 0 outside the region) the largest
// squared display difference, mean over the channels, between the mean of
// the pixel's even samples and that of one of its four neighbours in the
// region. After the first pass every pixel's even half is its first sample,
// so a paired pixel is judged as the others are: from its two-sample mean,
// its edges looked smoother, it stayed among the pooled pixels that lend
// their noise to the tile's one-sample ones while its one-sample
// neighbours went to the edge pixels, and the estimate of those one-sample
// pixels read 1.7-2x their true error (default.json, 128x96, a mean of 2).
std::vector<float> neighbourContrast(const SampleSums& sums, const ToneMapping& mapping,
                                     const PixelRegion& region);

// The edge round's samples: per tile the count all its pixels get (the
// fewest any of them gets), and per pixel (row-major over the image) the
// samples beyond it, with their sums per tile. Later rounds plan the tile's
// common count as its count and the pixels' extras as extras.
struct EdgeRound {
  std::vector<uint32_t> common;     // per tile
  std::vector<uint32_t> pixels;     // per pixel: beyond the common count
  std::vector<uint64_t> extraSums;  // per tile: the sum of `pixels` over it
};

// One measurement of the accumulated sums (TileNoiseKernel's tiles): every
// tile's noise and the image's estimated RMSE (estimateDisplayRmse over the
// region), which come from the same per-pixel estimates.
struct NoiseMeasurement {
  std::vector<TileNoise> tiles;  // dilated: what the allocation plans with
  // Per tile the variance of one sample, pooled over its pixels with both
  // halves (or a neighbour's): the noise of its pixels with one sample.
  // Empty when some tile has neither.
  std::vector<double> sampleVariance;
  std::optional<double> rmse;  // nullopt when a pixel lacks one of its halves
};

class AdaptivePlan {
 public:
  static constexpr uint32_t kTileSize = RT_ADAPTIVE_TILE_SIZE;

  // Tiles over a width x height image; only pixels of `region` (resolved:
  // not empty) get samples.
  AdaptivePlan(uint32_t width, uint32_t height, const PixelRegion& region);

  uint32_t tileCount() const { return static_cast<uint32_t>(pixels_.size()); }
  uint32_t tilePixels(size_t tile) const { return pixels_[tile]; }  // in the region
  bool edgesRendered() const { return edgesRendered_; }
  uint32_t tilesPerRow() const { return tilesPerRow_; }
  // Samples per pixel so far, per tile (row-major over the whole image).
  const std::vector<uint32_t>& samples() const { return samples_; }

  // `count` samples per pixel everywhere in the region.
  std::vector<uint32_t> uniformRound(uint32_t count) const;
  // Each tile's noise (after dilation) and the region's estimated RMSE from
  // the device's per-tile sums (TileNoiseKernel::measure over the region).
  NoiseMeasurement measureNoise(const std::vector<gpu::GpuTileNoise>& measured) const;
  // Each pixel's estimated RMS error (-1 outside the region or without an
  // estimate): from its own halves, or else `sampleVariance` of its tile
  // (NoiseMeasurement's) over its sample count.
  std::vector<float> errorImage(const SampleSums& sums, const ToneMapping& mapping,
                                const std::vector<double>& sampleVariance) const;
  // The edge round (above): `tiles` as measureNoise gives them, `contrast`
  // from neighbourContrast.
  EdgeRound edgeRound(const std::vector<TileNoise>& tiles, const std::vector<float>& contrast,
                      const AllocationGoal& goal) const;
  // Records that the edge round was rendered, tracing `rays` per tile.
  void addEdgeRound(const EdgeRound& round, const std::vector<uint32_t>& rays);
  // Per tile: samples per pixel beyond its count, summed over its pixels.
  uint64_t extraSamples(size_t tile) const { return edgeSamples_[tile]; }
  // Records that `added` samples per pixel were rendered into each tile,
  // tracing `rays` rays there; `paired`: and the paired pixels' extra one
  // (the first round only).
  void addRound(const std::vector<uint32_t>& added, const std::vector<uint32_t>& rays,
                bool paired = false);
  // Per tile: (first sample index, count) for the render kernel, flagged
  // with RT_ADAPTIVE_PAIRED_FLAG for the paired pixels (`paired`: this is
  // the round that gives them their extra sample) and RT_ADAPTIVE_EXTRAS_FLAG
  // for the pixels' edge samples (`edge`: this is the edge round).
  std::vector<glm::uvec2> kernelRanges(const std::vector<uint32_t>& added, bool paired = false,
                                       bool edge = false) const;

  uint64_t pixelSamples() const;  // samples rendered over the region so far
  uint64_t regionPixels() const { return regionPixels_; }
  const PixelRegion& region() const { return region_; }

 private:
  size_t tileOf(uint32_t x, uint32_t y) const;
  // Turns per-tile sums of one sample's variance over `measured` pixels
  // into means; a tile with no measured pixel takes its noisiest measured
  // neighbour's. False if some tile of the region has neither.
  bool poolTiles(std::vector<double>& variance, const std::vector<uint32_t>& measured) const;
  // Calls visit(j) for the tiles j of the 3x3 block around `tile` (itself
  // included) that lie in the image.
  template <typename F>
  void forEachNeighbour(size_t tile, F visit) const;
  // Tiles with noise v_i (one sample's, per tile) raised to a share of their
  // noisiest neighbour's, and the cost of a sample from the rays counted.
  std::vector<TileNoise> dilatedTiles(const std::vector<double>& variance) const;
  double tileSamples(size_t tile) const;  // pixel-samples rendered in it
  // Calls visit(pixel index) for the pixels of the rectangle at (x, y) that
  // lie in the region.
  template <typename F>
  void forEachPixelIn(uint32_t x, uint32_t y, uint32_t width, uint32_t height, F visit) const;
  // Per pixel the mean of `values` over its 4x2 block (RT_ADAPTIVE_PAIR_BLOCK_*)
  // in the region: one run of eight invocations, one SIMD vector on lavapipe.
  std::vector<float> blockMeans(const std::vector<float>& values) const;

  uint32_t tilesPerRow_ = 0;
  uint32_t width_ = 0;
  PixelRegion region_;
  std::vector<uint32_t> pixels_;       // region pixels per tile
  std::vector<uint32_t> paired_;       // region pixels per tile that adaptivePairedPixel picks
  std::vector<uint32_t> samples_;      // per tile
  bool pairsRendered_ = false;         // the paired pixels have their extra sample
  std::vector<uint64_t> edgeSamples_;  // per tile: its pixels' samples beyond samples_
  bool edgesRendered_ = false;
  std::vector<uint64_t> rays_;  // per tile: rays its samples traced
  uint64_t regionPixels_ = 0;
};

// One adaptive render's rounds, shared by the offline renderer and the
// viewer: the samples the current round adds per tile, bands of whole tile
// rows to render them in, and after each round the estimate, the stopping
// test and the next round's plan. The caller renders each round (upload
// kernelRanges(), dispatch the bands) and then calls finishRound.
class AdaptiveRounds {
 public:
  struct Goal {
    uint32_t meanSamples = 0;  // budget: samples per pixel on average
    double targetRmse = 0;     // stop once the estimate reaches it (0: no target)
    uint32_t maxSamples = 0;   // per pixel
    // No budget of its own (a time budget without a sample budget): each
    // time meanSamples are spent it doubles, up to maxSamples, so the rounds
    // go on until the caller stops them.
    bool openEnded = false;
  };

  AdaptiveRounds(uint32_t width, uint32_t height, const PixelRegion& region, const Goal& goal);

  // No samples left to add: the target is reached, the budget spent (an
  // open-ended one up to maxSamples), or the next round would add too little
  // to be worth a round (kMinRoundShare).
  bool finished() const { return finished_; }
  // The current round's (first sample, count) per tile, for the kernel.
  std::vector<glm::uvec2> kernelRanges() const {
    return plan_.kernelRanges(edgeRound_ ? edgeRound_->common : round_, pairRound_,
                              edgeRound_.has_value());
  }
  // The tiles (row-major indices) the current round adds samples to: the
  // only ones whose sums it changes.
  std::vector<uint32_t> roundTiles() const;
  // In the edge round its samples per pixel (for the kernel's pixel
  // extras), else empty.
  const std::vector<uint32_t>& pixelExtras() const;
  // The end of a band of whole tile rows from image row `y` (in the region)
  // holding about `work` pixel-samples of this round (at least one tile row).
  uint32_t bandEnd(uint32_t y, double work) const;
  // Pixel-samples this round adds to image rows [y, end).
  double rowWork(uint32_t y, uint32_t end) const;

  // Reads the accumulated sums back (ProgressiveRenderer::sampleSums), for
  // the edge round's contrast, and how they are displayed.
  struct ImageReader {
    std::function<SampleSums()> read;
    ToneMapping mapping;
  };

  // The round was rendered: `noise` is every tile's noise over all samples
  // so far (ProgressiveRenderer::tileNoise), `tileRays` the rays the round
  // traced per tile (ProgressiveRenderer::takeTileRays). After the first
  // round, `image` (read once) plans the edge round; without it the rounds
  // are all per tile.
  void finishRound(const std::vector<gpu::GpuTileNoise>& noise,
                   const std::vector<uint32_t>& tileRays, const ImageReader* image = nullptr);
  // The render stopped part way through the round: the estimate and the
  // tiles' noise from `noise` (over the samples it has), and no more rounds.
  void measureStop(const std::vector<gpu::GpuTileNoise>& noise);

  std::optional<double> rmseEstimate() const { return estimate_; }
  // Each pixel's estimated RMS error (AdaptivePlan::errorImage, with the
  // tiles' noise as the last round measured it).
  std::vector<float> errorImage(const SampleSums& sums, const ToneMapping& mapping) const {
    return plan_.errorImage(sums, mapping, sampleVariance_);
  }
  bool reachedTarget() const;
  double meanSamples() const;  // per pixel of the region, rendered so far

 private:
  // Plans the round after one measured as `noise`: the edge round when
  // `image` is given (after the first pass), else one per tile.
  void planRound(const NoiseMeasurement& noise, const ImageReader* image);

  AdaptivePlan plan_;
  Goal goal_;
  std::vector<uint32_t> round_;         // samples per pixel this round adds, per tile
  bool pairRound_ = false;              // and the paired pixels one more (the first round)
  std::optional<EdgeRound> edgeRound_;  // this round is the edge round
  std::optional<double> estimate_;
  std::vector<double> sampleVariance_;  // NoiseMeasurement's, of the last round
  bool finished_ = false;
};

}  // namespace rt
