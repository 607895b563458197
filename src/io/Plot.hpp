// Log-log line plots drawn straight into an 8-bit image (no plotting
// library): panels side by side, each with decade grid lines and labels,
// minor ticks, one line with markers per series, an optional dashed
// horizontal guide and a legend. Text comes from stb_easy_font's quads.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/Image.hpp"

namespace rt {

using Rgb8 = std::array<uint8_t, 3>;

struct PlotSeries {
  std::string name;
  Rgb8 color{0, 0, 0};
  std::vector<std::pair<double, double>> points;  // (x, y); values <= 0 are skipped
};

struct PlotPanel {
  std::string title;
  std::string xLabel;
  std::string yLabel;
  std::vector<PlotSeries> series;
  std::optional<double> guideY;  // dashed horizontal line (e.g. a target error)
};

struct PlotSize {
  uint32_t panelWidth = 560;
  uint32_t panelHeight = 420;
};

// The panels left to right in one image. Axes span whole decades around the
// data. Throws rt::Error if a panel has no positive point.
Image8 drawLogLogPlot(const std::vector<PlotPanel>& panels, const PlotSize& size = {});

// "0.001", "0.01", ..., "10000" for 10^-3..10^4, "1e-05" beyond.
std::string decadeLabel(int exponent);

}  // namespace rt
