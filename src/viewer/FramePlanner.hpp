// Decides how much rendering each frame records so the window stays
// responsive: a budget of pixel-samples per frame, adjusted after every frame
// towards the target frame time. A budget smaller than one pass over the image
// becomes a band of rows (the pass continues next frame); a larger one becomes
// several samples per pixel over the whole image. With a fixed number of
// samples per frame (scripted runs) each frame is exactly one full pass.
#pragma once

#include <cstdint>
#include <vector>

namespace rt::viewer {

struct Band {
  uint32_t row = 0;
  uint32_t rows = 0;
  uint32_t samples = 0;   // per pixel
  bool endsPass = false;  // the last band of a pass: call finishPass(samples) after it
};

class FramePlanner {
 public:
  // `fixedSamplesPerFrame` 0: adaptive.
  FramePlanner(double targetFrameSeconds, uint32_t fixedSamplesPerFrame);

  // Forget the pass under way (accumulation restarted or resized) and take
  // the image's size, which bounds the budget (adaptive rounds never ask for
  // uniform bands, so plan() may never see it).
  void restart(uint32_t width, uint32_t height);

  // Bands for the next frame, for an image of width x height that has
  // `samplesDone` of `samplesTarget` samples per pixel.
  std::vector<Band> plan(uint32_t width, uint32_t height, uint32_t samplesDone,
                         uint32_t samplesTarget);

  // Adapts the budget to a frame that took `seconds` and rendered the
  // planned bands (not called for frames that did other heavy work).
  void frameTook(double seconds);

  double budget() const { return budget_; }

 private:
  double targetSeconds_;
  uint32_t fixedSamples_;
  double budget_;  // pixel-samples per frame
  uint32_t nextRow_ = 0;
  uint32_t passSamples_ = 1;
  double pixels_ = 0;  // the image's, from restart(): the budget's ceiling
};

}  // namespace rt::viewer
