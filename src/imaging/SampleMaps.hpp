// Where a render's samples went and how much error is left, as images people
// can look at: per-pixel channels for EXR layers, false-colour maps for PNG.
#pragma once

#include <vector>

#include "io/Image.hpp"

namespace rt {

// Each pixel's sample count (the alpha of a rendered image), row-major.
std::vector<float> sampleCountChannel(const ImageF& image);

// Sample counts in false colour on a log scale from the fewest (dark blue)
// to the most (yellow); pixels without samples black. A key along the
// bottom rows would hide pixels, so the range is left to the summary line.
Image8 sampleCountMap(const ImageF& image);

// Estimated per-pixel errors (estimatedErrorImage; -1: none, drawn black)
// in the same colours, linear from 0 to the 99th percentile (brighter
// outliers saturate).
Image8 errorMap(uint32_t width, uint32_t height, const std::vector<float>& errors);

}  // namespace rt
