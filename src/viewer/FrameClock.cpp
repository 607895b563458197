#include "viewer/FrameClock.hpp"

namespace rt::viewer {
namespace {
// Without --verbose, a progress line at most this often.
constexpr std::chrono::seconds kLogInterval(1);
// The rate is measured over windows of this much rendering...
constexpr double kRateWindowSeconds = 1.0;
// ...or over a shorter one that idle frames end, if it lasted this long.
constexpr double kShortestRateWindowSeconds = 0.05;
}  // namespace

void RateMeter::add(double samples, Clock::time_point now) {
  if (samples <= 0.0) {
    double busy = secondsBetween(start_, lastWork_);
    if (samples_ > 0.0 && busy >= kShortestRateWindowSeconds) rate_ = samples_ / busy;
    samples_ = 0.0;
    start_ = now;
    lastWork_ = now;
    return;
  }
  samples_ += samples;
  lastWork_ = now;
  double seconds = secondsBetween(start_, now);
  if (seconds < kRateWindowSeconds) return;
  rate_ = samples_ / seconds;
  samples_ = 0.0;
  start_ = now;
}

double FrameClock::frameDone(uint64_t pixelSamples, Clock::time_point now) {
  double seconds = secondsBetween(lastFrameDone_, now);
  lastFrameDone_ = now;
  frameMilliseconds_ = seconds * 1e3;
  rate_.add(double(pixelSamples), now);
  return seconds;
}

bool FrameClock::takeLogDue(bool verbose) {
  Clock::time_point now = Clock::now();
  if (!verbose && now - lastLogAt_ < kLogInterval) return false;
  lastLogAt_ = now;
  return true;
}

}  // namespace rt::viewer
