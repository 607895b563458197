#include "imaging/SampleMaps.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace rt {
namespace {

// A perceptually ordered ramp (dark blue, purple, orange, yellow), sampled
// at five points and interpolated linearly.
std::array<uint8_t, 3> rampColour(double t) {
  static constexpr std::array<std::array<double, 3>, 5> kStops{
      {{13, 8, 135}, {126, 3, 168}, {204, 71, 120}, {248, 149, 64}, {240, 249, 33}}};
  t = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  const size_t low = std::min(static_cast<size_t>(t), kStops.size() - 2);
  const double f = t - double(low);
  std::array<uint8_t, 3> rgb{};
  for (size_t c = 0; c < 3; ++c) {
    rgb[c] = static_cast<uint8_t>(
        std::lround(kStops[low][c] + f * (kStops[low + 1][c] - kStops[low][c])));
  }
  return rgb;
}

// Values mapped to [0, 1] by `unit`; negative values (no data) black.
template <typename Unit>
Image8 falseColour(uint32_t width, uint32_t height, const std::vector<float>& values, Unit unit) {
  Image8 image{width, height, std::vector<uint8_t>(size_t(width) * height * 3, 0)};
  for (size_t i = 0; i < values.size(); ++i) {
    if (!(values[i] >= 0.0f)) continue;
    std::array<uint8_t, 3> rgb = rampColour(unit(values[i]));
    std::copy(rgb.begin(), rgb.end(), image.rgb.begin() + i * 3);
  }
  return image;
}

}  // namespace

std::vector<float> sampleCountChannel(const ImageF& image) {
  std::vector<float> counts(size_t(image.width) * image.height);
  for (size_t i = 0; i < counts.size(); ++i) counts[i] = image.rgba[i * 4 + 3];
  return counts;
}

Image8 sampleCountMap(const ImageF& image) {
  std::vector<float> counts = sampleCountChannel(image);
  float fewest = 0, most = 0;
  for (float count : counts) {
    if (count <= 0) continue;
    fewest = fewest > 0 ? std::min(fewest, count) : count;
    most = std::max(most, count);
  }
  for (float& count : counts) count = count > 0 ? count : -1.0f;  // no samples: black
  const double span = most > fewest ? std::log(double(most) / fewest) : 1.0;
  return falseColour(image.width, image.height, counts, [&](float count) {
    return std::log(double(count) / std::max(fewest, 1e-30f)) / span;
  });
}

Image8 errorMap(uint32_t width, uint32_t height, const std::vector<float>& errors) {
  std::vector<float> known;
  for (float e : errors) {
    if (e >= 0.0f) known.push_back(e);
  }
  float scale = 0;
  if (!known.empty()) {
    auto percentile = known.begin() + std::ptrdiff_t(0.99 * double(known.size() - 1));
    std::nth_element(known.begin(), percentile, known.end());
    scale = *percentile;
  }
  return falseColour(width, height, errors,
                     [&](float e) { return scale > 0 ? double(e) / scale : 0.0; });
}

}  // namespace rt
