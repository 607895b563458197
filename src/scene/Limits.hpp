// What a scene may ask for, in one place for every loader and the command
// line: larger values are typos or hostile files, not render requests.
#pragma once

#include <cstdint>

namespace rt {

constexpr uint32_t kMaxImageSide = 16384;  // pixels per side of an image
constexpr uint32_t kMaxBounces = 64;       // nbounces, distributed bounces
constexpr uint32_t kMaxSamplesPerPixel = 1u << 20;
constexpr uint32_t kMaxLightSamples = 4096;  // shadow rays per area light and hit
constexpr uint32_t kMaxLightSplit = 64;      // replicas of a hit's area-light estimate

}  // namespace rt
