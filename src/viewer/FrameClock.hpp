// The viewer's frame timing: how long frames take, how many were presented,
// samples per second, and when the next progress line is due.
#pragma once

#include <cstdint>

#include "util/Clock.hpp"

namespace rt::viewer {

// Samples per second over the last second or so of rendering. Frames that
// add no samples (the render is done, or paused) are not time spent
// rendering: a finished render keeps showing the rate it ran at, not zero.
class RateMeter {
 public:
  using Clock = SteadyClock;
  explicit RateMeter(Clock::time_point start = Clock::now()) : start_(start), lastWork_(start) {}
  // A frame that finished at `now` and added `samples`.
  void add(double samples, Clock::time_point now);
  double perSecond() const { return rate_; }

 private:
  Clock::time_point start_;     // of the window being counted
  Clock::time_point lastWork_;  // the last frame in it that added samples
  double samples_ = 0.0;
  double rate_ = 0.0;
};

class FrameClock {
 public:
  using Clock = SteadyClock;

  // A frame finished on the GPU with `pixelSamples` of work; returns the
  // seconds since the previous one finished.
  double frameDone(uint64_t pixelSamples, Clock::time_point now);
  void presented() {
    ++framesPresented_;
    lastPresentAt_ = Clock::now();
  }
  // Whether a progress line is due (always with `verbose`); marks it written.
  bool takeLogDue(bool verbose);

  uint64_t framesPresented() const { return framesPresented_; }
  Clock::time_point lastPresentAt() const { return lastPresentAt_; }
  double frameMilliseconds() const { return frameMilliseconds_; }
  double samplesPerSecond() const { return rate_.perSecond(); }

 private:
  uint64_t framesPresented_ = 0;
  Clock::time_point lastFrameDone_ = Clock::now();
  Clock::time_point lastLogAt_{};
  Clock::time_point lastPresentAt_{};
  double frameMilliseconds_ = 0.0;
  RateMeter rate_;
};

}  // namespace rt::viewer
