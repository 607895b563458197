#include "viewer/FramePlanner.hpp"

#include <algorithm>
#include <cmath>

namespace rt::viewer {
namespace {

// Before the first measurement: about 16k pixel-samples, a few ms anywhere.
constexpr double kInitialBudget = 16384.0;
// One frame's measurement may change the budget by at most this factor.
constexpr double kMaxStep = 2.0;
// The budget's floor: about a row of one sample per frame.
constexpr double kMinBudget = 1024.0;
// Its ceiling, in samples per pixel of the image.
constexpr double kMaxSamplesPerFrame = 64.0;

}  // namespace

FramePlanner::FramePlanner(double targetFrameSeconds, uint32_t fixedSamplesPerFrame)
    : targetSeconds_(targetFrameSeconds),
      fixedSamples_(fixedSamplesPerFrame),
      budget_(kInitialBudget) {}

void FramePlanner::restart(uint32_t width, uint32_t height) {
  nextRow_ = 0;
  pixels_ = double(width) * height;
}

std::vector<Band> FramePlanner::plan(uint32_t width, uint32_t height, uint32_t samplesDone,
                                     uint32_t samplesTarget) {
  std::vector<Band> bands;
  const double pixels = double(width) * height;
  if (nextRow_ >= height) nextRow_ = 0;
  double budget = budget_;
  while (samplesDone < samplesTarget) {
    uint32_t remaining = samplesTarget - samplesDone;
    if (nextRow_ == 0) {
      double affordable = std::floor(budget / pixels);
      passSamples_ = fixedSamples_ > 0 ? fixedSamples_
                                       : static_cast<uint32_t>(std::clamp(affordable, 1.0, 1e6));
      passSamples_ = std::min(passSamples_, remaining);
    }
    uint32_t rows = height - nextRow_;
    if (fixedSamples_ == 0) {
      double affordable = std::floor(budget / (double(width) * passSamples_));
      rows = static_cast<uint32_t>(std::clamp(affordable, 1.0, double(rows)));
    }
    Band band{nextRow_, rows, passSamples_, nextRow_ + rows == height};
    bands.push_back(band);
    budget -= double(width) * rows * passSamples_;
    nextRow_ = band.endsPass ? 0 : nextRow_ + rows;
    if (band.endsPass) samplesDone += passSamples_;
    if (fixedSamples_ > 0 || budget < double(width)) break;
  }
  return bands;
}

void FramePlanner::frameTook(double seconds) {
  if (fixedSamples_ > 0 || seconds <= 0.0) return;
  double step = std::clamp(targetSeconds_ / seconds, 1.0 / kMaxStep, kMaxStep);
  // Damped, so that noisy frame times do not make the budget oscillate.
  budget_ *= std::pow(step, 0.7);
  // The ceiling is never below the floor: std::clamp with the two the other
  // way round is undefined, and before restart() took the image's size it
  // set an adaptive window's budget to 64 pixel-samples, one tile row a frame.
  budget_ = std::clamp(budget_, kMinBudget, std::max(kMinBudget, pixels_ * kMaxSamplesPerFrame));
}

}  // namespace rt::viewer
