// The size the render should have and since when: a window being dragged
// resizes often, so the render follows once a size held for a moment.
#pragma once

#include <chrono>
#include <glm/glm.hpp>

namespace rt::viewer {

class PendingResize {
 public:
  using Clock = std::chrono::steady_clock;

  void start(glm::uvec2 size) { wanted_ = size; }
  // The window (swapchain) now has `size`.
  void windowSized(glm::uvec2 size) {
    if (size == wanted_) return;
    wanted_ = size;
    seenAt_ = Clock::now();
  }
  glm::uvec2 wanted() const { return wanted_; }
  // Whether the wanted size held long enough to render at it.
  bool settled() const { return Clock::now() - seenAt_ >= kSettle; }

 private:
  static constexpr std::chrono::milliseconds kSettle{250};
  glm::uvec2 wanted_{0};
  Clock::time_point seenAt_{};
};

}  // namespace rt::viewer
