#include "io/Plot.hpp"

#include <fmt/format.h>
#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>

#include "util/Error.hpp"

namespace rt {
namespace {

constexpr Rgb8 kBlack{0, 0, 0};
constexpr Rgb8 kWhite{255, 255, 255};
constexpr Rgb8 kGrid{222, 222, 222};
constexpr Rgb8 kGuide{120, 120, 120};
constexpr float kTextScale = 2.0f;  // stb_easy_font glyphs are ~7 units tall
constexpr int kMarginLeft = 86;
constexpr int kMarginRight = 40;
constexpr int kMarginTop = 40;
constexpr int kMarginBottom = 62;

// An RGB image with clipped drawing primitives.
class Canvas {
 public:
  Canvas(uint32_t width, uint32_t height)
      : image_{width, height, std::vector<uint8_t>(size_t(width) * height * 3, 255)} {}

  void fillRect(double x0, double y0, double x1, double y1, Rgb8 color) {
    int ax = std::max(0, int(std::floor(std::min(x0, x1))));
    int ay = std::max(0, int(std::floor(std::min(y0, y1))));
    int bx = std::min(int(image_.width), int(std::ceil(std::max(x0, x1))));
    int by = std::min(int(image_.height), int(std::ceil(std::max(y0, y1))));
    for (int y = ay; y < by; ++y) {
      for (int x = ax; x < bx; ++x) {
        std::copy(color.begin(), color.end(), &image_.rgb[(size_t(y) * image_.width + x) * 3]);
      }
    }
  }

  // A line `thickness` pixels wide; dashLength > 0 draws dashes of that length.
  void line(double x0, double y0, double x1, double y1, Rgb8 color, double thickness,
            double dashLength = 0) {
    double length = std::hypot(x1 - x0, y1 - y0);
    int steps = std::max(1, int(std::ceil(length * 2)));
    double half = thickness / 2;
    for (int i = 0; i <= steps; ++i) {
      double t = double(i) / steps;
      if (dashLength > 0 && int(t * length / dashLength) % 2 == 1) continue;
      double x = x0 + (x1 - x0) * t;
      double y = y0 + (y1 - y0) * t;
      fillRect(x - half, y - half, x + half, y + half, color);
    }
  }

  // Text with its top-left corner at (x, y); `vertical` runs it bottom to
  // top, starting at (x, y) as its bottom-left corner.
  void text(double x, double y, const std::string& text, Rgb8 color, bool vertical = false) {
    std::vector<char> chars(text.begin(), text.end());
    chars.push_back('\0');
    std::vector<char> quads(chars.size() * 1024);
    unsigned char rgba[4] = {color[0], color[1], color[2], 255};
    int count = stb_easy_font_print(0, 0, chars.data(), rgba, quads.data(), int(quads.size()));
    for (int q = 0; q < count; ++q) {
      const float* corner0 = reinterpret_cast<const float*>(&quads[size_t(q) * 64]);
      const float* corner2 = reinterpret_cast<const float*>(&quads[size_t(q) * 64 + 32]);
      double u0 = corner0[0] * kTextScale, v0 = corner0[1] * kTextScale;
      double u1 = corner2[0] * kTextScale, v1 = corner2[1] * kTextScale;
      if (vertical) {
        fillRect(x + v0, y - u0, x + v1, y - u1, color);
      } else {
        fillRect(x + u0, y + v0, x + u1, y + v1, color);
      }
    }
  }

  Image8 take() { return std::move(image_); }

 private:
  Image8 image_;
};

double textWidth(const std::string& text) {
  std::vector<char> chars(text.begin(), text.end());
  chars.push_back('\0');
  return double(stb_easy_font_width(chars.data())) * kTextScale;
}

constexpr double kTextHeight = 7 * kTextScale;

// Whole decades [lo, hi] (exponents) holding every positive value.
std::pair<int, int> decadeRange(double minValue, double maxValue) {
  int lo = int(std::floor(std::log10(minValue) + 1e-9));
  int hi = int(std::ceil(std::log10(maxValue) - 1e-9));
  if (hi <= lo) hi = lo + 1;
  return {lo, hi};
}

// Maps data to pixels inside one panel's plot area.
struct Axes {
  double left, top, right, bottom;  // plot area in pixels
  int xLo, xHi, yLo, yHi;           // decade exponents

  double px(double x) const { return left + (std::log10(x) - xLo) / (xHi - xLo) * (right - left); }
  double py(double y) const {
    return bottom - (std::log10(y) - yLo) / (yHi - yLo) * (bottom - top);
  }
};

Axes axesFor(const PlotPanel& panel, double originX, const PlotSize& size) {
  double minX = INFINITY, maxX = 0, minY = INFINITY, maxY = 0;
  for (const PlotSeries& series : panel.series) {
    for (auto [x, y] : series.points) {
      if (!(x > 0 && y > 0)) continue;
      minX = std::min(minX, x), maxX = std::max(maxX, x);
      minY = std::min(minY, y), maxY = std::max(maxY, y);
    }
  }
  if (panel.guideY && *panel.guideY > 0) {
    minY = std::min(minY, *panel.guideY), maxY = std::max(maxY, *panel.guideY);
  }
  if (!(maxX > 0 && maxY > 0)) throw Error(fmt::format("plot '{}': no positive data", panel.title));
  auto [xLo, xHi] = decadeRange(minX, maxX);
  auto [yLo, yHi] = decadeRange(minY, maxY);
  return {originX + kMarginLeft,
          double(kMarginTop),
          originX + size.panelWidth - kMarginRight,
          double(size.panelHeight - kMarginBottom),
          xLo,
          xHi,
          yLo,
          yHi};
}

void drawGridAndTicks(Canvas& canvas, const Axes& a) {
  for (int e = a.xLo; e <= a.xHi; ++e) {
    double x = a.px(std::pow(10.0, e));
    canvas.line(x, a.top, x, a.bottom, kGrid, 1);
    canvas.line(x, a.bottom, x, a.bottom + 7, kBlack, 1);
    std::string label = decadeLabel(e);
    canvas.text(x - textWidth(label) / 2, a.bottom + 12, label, kBlack);
    for (int m = 2; m <= 9 && e < a.xHi; ++m) {
      double minor = a.px(m * std::pow(10.0, e));
      canvas.line(minor, a.bottom, minor, a.bottom + 4, kBlack, 1);
    }
  }
  for (int e = a.yLo; e <= a.yHi; ++e) {
    double y = a.py(std::pow(10.0, e));
    canvas.line(a.left, y, a.right, y, kGrid, 1);
    canvas.line(a.left - 7, y, a.left, y, kBlack, 1);
    std::string label = decadeLabel(e);
    canvas.text(a.left - 12 - textWidth(label), y - kTextHeight / 2, label, kBlack);
    for (int m = 2; m <= 9 && e < a.yHi; ++m) {
      double minor = a.py(m * std::pow(10.0, e));
      canvas.line(a.left - 4, minor, a.left, minor, kBlack, 1);
    }
  }
}

void drawFrameAndLabels(Canvas& canvas, const Axes& a, const PlotPanel& panel) {
  canvas.line(a.left, a.top, a.right, a.top, kBlack, 1);
  canvas.line(a.left, a.bottom, a.right, a.bottom, kBlack, 1);
  canvas.line(a.left, a.top, a.left, a.bottom, kBlack, 1);
  canvas.line(a.right, a.top, a.right, a.bottom, kBlack, 1);
  double centerX = (a.left + a.right) / 2;
  canvas.text(centerX - textWidth(panel.title) / 2, a.top - kTextHeight - 12, panel.title, kBlack);
  canvas.text(centerX - textWidth(panel.xLabel) / 2, a.bottom + 36, panel.xLabel, kBlack);
  double centerY = (a.top + a.bottom) / 2;
  canvas.text(a.left - kMarginLeft + 8, centerY + textWidth(panel.yLabel) / 2, panel.yLabel, kBlack,
              true);
}

void drawSeries(Canvas& canvas, const Axes& a, const PlotSeries& series) {
  std::vector<std::pair<double, double>> pixels;
  for (auto [x, y] : series.points) {
    if (x > 0 && y > 0) pixels.push_back({a.px(x), a.py(y)});
  }
  for (size_t i = 1; i < pixels.size(); ++i) {
    canvas.line(pixels[i - 1].first, pixels[i - 1].second, pixels[i].first, pixels[i].second,
                series.color, 2);
  }
  for (auto [x, y] : pixels) canvas.fillRect(x - 3, y - 3, x + 3, y + 3, series.color);
}

void drawLegend(Canvas& canvas, const Axes& a, const PlotPanel& panel) {
  double width = 0;
  for (const PlotSeries& series : panel.series) width = std::max(width, textWidth(series.name));
  const double rowHeight = kTextHeight + 8;
  double boxWidth = width + 48;
  double boxHeight = rowHeight * double(panel.series.size()) + 8;
  double x0 = a.right - boxWidth - 10;
  double y0 = a.top + 10;
  canvas.fillRect(x0, y0, x0 + boxWidth, y0 + boxHeight, kWhite);
  canvas.line(x0, y0, x0 + boxWidth, y0, kBlack, 1);
  canvas.line(x0, y0 + boxHeight, x0 + boxWidth, y0 + boxHeight, kBlack, 1);
  canvas.line(x0, y0, x0, y0 + boxHeight, kBlack, 1);
  canvas.line(x0 + boxWidth, y0, x0 + boxWidth, y0 + boxHeight, kBlack, 1);
  for (size_t i = 0; i < panel.series.size(); ++i) {
    double y = y0 + 8 + rowHeight * double(i);
    canvas.line(x0 + 8, y + kTextHeight / 2, x0 + 32, y + kTextHeight / 2, panel.series[i].color,
                2);
    canvas.text(x0 + 40, y, panel.series[i].name, kBlack);
  }
}

}  // namespace

std::string decadeLabel(int exponent) {
  if (exponent >= -3 && exponent <= 4) return fmt::format("{:g}", std::pow(10.0, exponent));
  return fmt::format("1e{:+03d}", exponent);
}

Image8 drawLogLogPlot(const std::vector<PlotPanel>& panels, const PlotSize& size) {
  Canvas canvas(size.panelWidth * uint32_t(std::max<size_t>(panels.size(), 1)), size.panelHeight);
  for (size_t i = 0; i < panels.size(); ++i) {
    const PlotPanel& panel = panels[i];
    Axes axes = axesFor(panel, double(i * size.panelWidth), size);
    drawGridAndTicks(canvas, axes);
    if (panel.guideY) {
      double y = axes.py(*panel.guideY);
      canvas.line(axes.left, y, axes.right, y, kGuide, 1, 6);
    }
    for (const PlotSeries& series : panel.series) drawSeries(canvas, axes, series);
    drawFrameAndLabels(canvas, axes, panel);
    drawLegend(canvas, axes, panel);
  }
  return canvas.take();
}

}  // namespace rt
