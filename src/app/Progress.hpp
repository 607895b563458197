// Terminal progress bar with samples/s and ETA. Redraws in place on a
// terminal; when stderr is a file or pipe it prints a line every 25%.
#pragma once

#include <cstdint>

#include "render/Renderer.hpp"

namespace rt {

class ProgressBar {
 public:
  ProgressBar(uint64_t pixels, bool enabled);
  void update(const RenderProgress& progress);
  void finish();

 private:
  uint64_t pixels_;
  bool enabled_;
  bool interactive_;
  int lastQuarter_ = 0;
  double lastDraw_ = -1.0;
};

}  // namespace rt
