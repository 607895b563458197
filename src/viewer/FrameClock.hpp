// The viewer's frame timing: how long frames take, how many were presented,
// samples per second, and when the next progress line is due.
#pragma once

#include <chrono>
#include <cstdint>

namespace rt::viewer {

// Samples per second over the last second or so.
class RateMeter {
 public:
  using Clock = std::chrono::steady_clock;
  void add(double samples, Clock::time_point now);
  double perSecond() const { return rate_; }

 private:
  Clock::time_point start_ = Clock::now();
  double samples_ = 0.0;
  double rate_ = 0.0;
};

class FrameClock {
 public:
  using Clock = std::chrono::steady_clock;

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
