#include "app/Progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace rt {

ProgressBar::ProgressBar(uint64_t pixels, bool enabled, std::optional<double> timeBudget,
                         bool sampleLimit)
    : pixels_(pixels),
      enabled_(enabled),
      timeBudget_(timeBudget),
      sampleLimit_(sampleLimit),
      interactive_(::isatty(STDERR_FILENO) == 1) {}

void ProgressBar::update(const RenderProgress& p) {
  if (!enabled_ || p.samplesTotal == 0) return;
  double fraction = sampleLimit_ ? p.samplesDone / p.samplesTotal : 0.0;
  if (timeBudget_ && *timeBudget_ > 0) {
    fraction = std::max(fraction, std::min(1.0, p.elapsedSeconds / *timeBudget_));
  }
  if (p.targetRmse > 0 && p.rmseEstimate && *p.rmseEstimate > 0) {
    // Noise falls as 1/sqrt(samples): the share of the samples the target needs.
    double ratio = p.targetRmse / *p.rmseEstimate;
    fraction = std::max(fraction, std::min(1.0, ratio * ratio));
  }
  double rate = p.elapsedSeconds > 0 ? p.samplesDone * double(pixels_) / p.elapsedSeconds : 0;
  double eta = fraction > 0 ? p.elapsedSeconds * (1.0 - fraction) / fraction : 0;
  std::string stats = sampleLimit_ ? fmt::format("{:5.1f}/{} spp", p.samplesDone, p.samplesTotal)
                                   : fmt::format("{:5.1f} spp", p.samplesDone);
  stats += fmt::format("  {:7.2f} Msamples/s  ETA {:5.1f} s", rate * 1e-6, eta);
  if (p.rmseEstimate) stats += fmt::format("  RMSE ~{:.4f}", *p.rmseEstimate);
  if (interactive_) {
    if (p.elapsedSeconds - lastDraw_ < 0.1 && fraction < 1.0) return;
    lastDraw_ = p.elapsedSeconds;
    constexpr int kWidth = 30;
    int filled = static_cast<int>(fraction * kWidth);
    std::fprintf(stderr, "\r[%s%s] %s", std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, '.').c_str(), stats.c_str());
    std::fflush(stderr);
    return;
  }
  int quarter = static_cast<int>(fraction * 4.0);
  if (quarter > lastQuarter_) {
    lastQuarter_ = quarter;
    std::fprintf(stderr, "progress %3d%%  %s\n", quarter * 25, stats.c_str());
  }
}

void ProgressBar::finish() {
  if (enabled_ && interactive_) std::fprintf(stderr, "\n");
}

}  // namespace rt
