// The viewer's samples-per-second meter: measured over rendering time only,
// so the overlay of a finished render shows the rate it ran at.
#include <doctest/doctest.h>

#include <chrono>

#include "viewer/FrameClock.hpp"

using rt::viewer::RateMeter;

namespace {

RateMeter::Clock::time_point at(double seconds) {
  return RateMeter::Clock::time_point(std::chrono::duration_cast<RateMeter::Clock::duration>(
      std::chrono::duration<double>(seconds)));
}

// Frames of `frameSeconds` from `from` to `to`, each adding `samplesPerFrame`.
double frames(RateMeter& meter, double from, double to, double frameSeconds,
              double samplesPerFrame) {
  double t = from;
  while (t + frameSeconds <= to + 1e-9) {
    t += frameSeconds;
    meter.add(samplesPerFrame, at(t));
  }
  return t;
}

}  // namespace

TEST_SUITE("viewer frame clock") {
  TEST_CASE("the rate is samples over the time spent rendering them") {
    RateMeter meter(at(0.0));
    frames(meter, 0.0, 2.0, 0.02, 2.0e4);  // 1e6 samples a second
    CHECK(meter.perSecond() == doctest::Approx(1.0e6).epsilon(0.01));
  }

  TEST_CASE("idle frames after the render keep its rate, not zero") {
    RateMeter meter(at(0.0));
    double end = frames(meter, 0.0, 1.5, 0.02, 2.0e4);  // a whole window, then half of one
    frames(meter, end, end + 3.0, 0.016, 0.0);          // done: frames with no samples
    CHECK(meter.perSecond() == doctest::Approx(1.0e6).epsilon(0.01));
  }

  TEST_CASE("a render shorter than a window still gets its rate once it is done") {
    RateMeter meter(at(0.0));
    double end = frames(meter, 0.0, 0.4, 0.02, 1.0e4);  // 5e5 samples a second
    CHECK(meter.perSecond() == 0.0);                    // no window closed yet
    frames(meter, end, end + 1.0, 0.016, 0.0);
    CHECK(meter.perSecond() == doctest::Approx(5.0e5).epsilon(0.01));
  }

  TEST_CASE("work after an idle spell is timed from its own start") {
    RateMeter meter(at(0.0));
    double end = frames(meter, 0.0, 1.0, 0.02, 2.0e4);
    end = frames(meter, end, end + 5.0, 0.016, 0.0);
    frames(meter, end, end + 1.2, 0.04, 1.0e4);  // 2.5e5 samples a second
    CHECK(meter.perSecond() == doctest::Approx(2.5e5).epsilon(0.01));
  }
}
