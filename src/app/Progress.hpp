// Terminal progress bar with samples/s and ETA. Redraws in place on a
// terminal; when stderr is a file or pipe it prints a line every 25%.
#pragma once

#include <cstdint>
#include <optional>

#include "render/Renderer.hpp"

namespace rt {

class ProgressBar {
 public:
  // `timeBudget`: the render ends by then at the latest (--time), which the
  // bar counts as progress too. `sampleLimit` false: the sample count is no
  // limit the user gave (a time budget or a target decides), so it is shown
  // without a total.
  ProgressBar(uint64_t pixels, bool enabled, std::optional<double> timeBudget = std::nullopt,
              bool sampleLimit = true);
  void update(const RenderProgress& progress);
  void finish();

 private:
  uint64_t pixels_;
  bool enabled_;
  std::optional<double> timeBudget_;
  bool sampleLimit_;
  bool interactive_;
  int lastQuarter_ = 0;
  double lastDraw_ = -1.0;
};

}  // namespace rt
