#include "viewer/Accumulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "scene/Limits.hpp"

namespace rt::viewer {

Accumulation::Accumulation(double frameSeconds, uint32_t fixedSamplesPerFrame)
    : planner_(frameSeconds, fixedSamplesPerFrame), fixedPerFrame_(fixedSamplesPerFrame > 0) {}

void Accumulation::restart(ProgressiveRenderer& renderer, uint32_t target, bool adaptive) {
  renderer_ = &renderer;
  target_ = target;
  planner_.restart(renderer.width(), renderer.height());
  adaptive_.reset();
  adaptiveRow_ = 0;
  if (adaptive) {
    const uint32_t width = renderer.width(), height = renderer.height();
    adaptive_.emplace(width, height, PixelRegion{0, 0, width, height},
                      AdaptiveRounds::Goal{target, 0.0, kMaxSamplesPerPixel});
  }
  start_ = Clock::now();
  doneReported_ = false;
}

void Accumulation::setTarget(uint32_t target) {
  target_ = target;
  doneReported_ = false;
}

bool Accumulation::accumulating() const {
  if (adaptive_) return !adaptive_->finished();
  return renderer_ && renderer_->samplesDone() < target_;
}

double Accumulation::samplesPerPixel() const {
  if (!renderer_) return 0.0;
  if (!adaptive_) return double(renderer_->samplesDone());
  // Finished rounds, and the bands of the current one recorded so far.
  double pixels = double(renderer_->width()) * renderer_->height();
  double underway = adaptive_->finished() ? 0.0 : adaptive_->rowWork(0, adaptiveRow_);
  return adaptive_->meanSamples() + underway / std::max(pixels, 1.0);
}

std::string Accumulation::samplesText() const {
  if (adaptive_) return fmt::format("{:.2f} mean", samplesPerPixel());
  return std::to_string(static_cast<uint32_t>(samplesPerPixel()));
}

std::optional<double> Accumulation::rmseEstimate() const {
  return adaptive_ ? adaptive_->rmseEstimate() : std::nullopt;
}

std::optional<double> Accumulation::takeDoneSeconds() {
  if (accumulating() || doneReported_) return std::nullopt;
  doneReported_ = true;
  return secondsSince(start_);
}

std::vector<Band> Accumulation::planAdaptiveBands(const ToneMapping& mapping, bool& readBack) {
  const uint32_t height = renderer_->height();
  if (adaptiveRow_ >= height) {
    // The round's last band was in the frame just finished: with nothing
    // in flight, measure the tiles' noise and plan the next round.
    renderer_->finishAdaptiveRound(*adaptive_, mapping);
    adaptiveRow_ = 0;
    readBack = true;
  }
  if (adaptive_->finished()) return {};
  if (adaptiveRow_ == 0) {
    renderer_->setSamplePlan(adaptive_->kernelRanges(), adaptive_->pixelExtras());
  }
  // Scripted runs with fixed samples per frame render a whole round a frame.
  double budget = fixedPerFrame_ ? std::numeric_limits<double>::infinity() : planner_.budget();
  uint32_t end = adaptive_->bandEnd(adaptiveRow_, budget);
  Band band{adaptiveRow_, end - adaptiveRow_, 0, end == height};
  adaptiveRow_ = end;
  return {band};
}

Accumulation::FrameSamples Accumulation::record(VkCommandBuffer commands,
                                                const ToneMapping& mapping) {
  FrameSamples frame;
  if (!renderer_) return frame;
  std::vector<Band> bands = adaptive_ ? planAdaptiveBands(mapping, frame.readBack)
                                      : planner_.plan(renderer_->width(), renderer_->height(),
                                                      renderer_->samplesDone(), target_);
  uint32_t first = renderer_->height();
  uint32_t end = 0;
  for (const Band& band : bands) {
    first = std::min(first, band.row);
    end = std::max(end, band.row + band.rows);
    if (adaptive_) {
      renderer_->recordPlannedSamples(commands, band.row, band.rows);
      frame.pixelSamples +=
          static_cast<uint64_t>(adaptive_->rowWork(band.row, band.row + band.rows));
      continue;
    }
    renderer_->recordSamples(commands, band.row, band.rows, band.samples);
    // Sample indices of the next band start after this pass.
    if (band.endsPass) renderer_->finishPass(band.samples);
    frame.pixelSamples += uint64_t(renderer_->width()) * band.rows * band.samples;
  }
  if (!bands.empty()) {
    frame.firstRow = first;
    frame.rows = end - first;
  }
  return frame;
}

}  // namespace rt::viewer
