// Combines renders of disjoint sample ranges of one scene (each an image
// whose alpha holds the pixel's sample count) into the image that rendering
// all their samples at once gives, up to float rounding.
#pragma once

#include <vector>

#include "io/Image.hpp"

namespace rt {

// Throws rt::Error if the images differ in size or carry no samples.
ImageF mergeRenders(const std::vector<ImageF>& parts);

}  // namespace rt
