// The viewer's frame planner: the budget of pixel-samples a frame follows the
// frame time within its bounds, for adaptive accumulations too, which never
// ask it for uniform bands.
#include <doctest/doctest.h>

#include "viewer/FramePlanner.hpp"

using rt::viewer::FramePlanner;

namespace {

constexpr double kFrameSeconds = 1.0 / 30.0;

// `count` frames that each took `seconds`.
void frames(FramePlanner& planner, int count, double seconds) {
  for (int i = 0; i < count; ++i) planner.frameTook(seconds);
}

}  // namespace

TEST_SUITE("viewer frame planner") {
  TEST_CASE("fast frames raise an adaptive accumulation's budget as a uniform one's") {
    FramePlanner uniform(kFrameSeconds, 0), adaptive(kFrameSeconds, 0);
    uniform.restart(640, 480);
    adaptive.restart(640, 480);
    REQUIRE_FALSE(uniform.plan(640, 480, 0, 1000).empty());  // adaptive ones never plan
    frames(uniform, 3, 0.002);
    frames(adaptive, 3, 0.002);
    CHECK(adaptive.budget() > 16384.0);
    CHECK(adaptive.budget() == uniform.budget());
    // Up to 64 samples a pixel a frame.
    frames(adaptive, 40, 0.002);
    CHECK(adaptive.budget() == 640.0 * 480.0 * 64.0);
  }

  TEST_CASE("slow frames lower the budget to a row's worth, even on a tiny image") {
    FramePlanner planner(kFrameSeconds, 0);
    planner.restart(640, 480);
    frames(planner, 40, 1.0);
    CHECK(planner.budget() == 1024.0);
    // An image of one pixel: the ceiling (64 pixel-samples) is under the
    // floor, which wins, whatever the frames take.
    planner.restart(1, 1);
    frames(planner, 5, 0.001);
    CHECK(planner.budget() == 1024.0);
  }
}
