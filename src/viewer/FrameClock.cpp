#include "viewer/FrameClock.hpp"

namespace rt::viewer {
namespace {
// Without --verbose, a progress line at most this often.
constexpr std::chrono::seconds kLogInterval(1);
}  // namespace

void RateMeter::add(double samples, Clock::time_point now) {
  samples_ += samples;
  double seconds = std::chrono::duration<double>(now - start_).count();
  if (seconds < 1.0) return;
  rate_ = samples_ / seconds;
  samples_ = 0.0;
  start_ = now;
}

double FrameClock::frameDone(uint64_t pixelSamples, Clock::time_point now) {
  double seconds = std::chrono::duration<double>(now - lastFrameDone_).count();
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
