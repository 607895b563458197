// How the window's image accumulates: the samples each frame adds (row bands
// of uniform passes that the FramePlanner sizes for the frame time, or the
// rounds of adaptive sampling), how far it got, and when it is done. The
// Viewer owns the renderer; this decides what goes into it.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "render/AdaptiveSampling.hpp"
#include "render/ProgressiveRenderer.hpp"
#include "util/Clock.hpp"
#include "viewer/FramePlanner.hpp"

namespace rt::viewer {

class Accumulation {
 public:
  // `fixedSamplesPerFrame` 0: bands sized for `frameSeconds`.
  Accumulation(double frameSeconds, uint32_t fixedSamplesPerFrame);

  // `renderer` holds zero samples (just made or reset): start towards
  // `target` samples per pixel, the mean budget when `adaptive`.
  void restart(ProgressiveRenderer& renderer, uint32_t target, bool adaptive);
  // A new target that keeps the samples so far (uniform sampling with a
  // sampler whose samples do not depend on the target).
  void setTarget(uint32_t target);

  bool accumulating() const;
  double samplesPerPixel() const;   // the mean under adaptive sampling
  std::string samplesText() const;  // "16", or "12.37 mean" when adaptive
  bool adaptive() const { return adaptive_.has_value(); }
  // Adaptive sampling's, after its first round.
  std::optional<double> rmseEstimate() const;
  // Once, when accumulating() has become false: seconds since restart.
  std::optional<double> takeDoneSeconds();

  struct FrameSamples {
    uint32_t firstRow = 0;  // rows that got samples
    uint32_t rows = 0;
    uint64_t pixelSamples = 0;
    bool readBack = false;  // a round was measured (a wait for the device, then host work)
  };
  // Between frames, nothing in flight: records this frame's dispatches.
  // `mapping` is the display's: adaptive rounds measure noise in it.
  FrameSamples record(VkCommandBuffer commands, const ToneMapping& mapping);
  // A frame of plain rendering took `seconds`: sizes the next ones.
  void frameTook(double seconds) { planner_.frameTook(seconds); }

 private:
  using Clock = SteadyClock;
  std::vector<Band> planAdaptiveBands(const ToneMapping& mapping, bool& readBack);

  FramePlanner planner_;
  const bool fixedPerFrame_;
  ProgressiveRenderer* renderer_ = nullptr;
  uint32_t target_ = 0;
  // Adaptive sampling: the rounds since restart, and the first row of the
  // current round not yet recorded.
  std::optional<AdaptiveRounds> adaptive_;
  uint32_t adaptiveRow_ = 0;
  Clock::time_point start_ = Clock::now();
  bool doneReported_ = false;
};

}  // namespace rt::viewer
