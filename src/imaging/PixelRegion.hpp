// A rectangle of image pixels: the part of the image a render covers (the
// rest keeps zero samples) and over which errors are measured.
#pragma once

#include <cstdint>
#include <string>

namespace rt {

struct PixelRegion {
  uint32_t x = 0;
  uint32_t y = 0;
  uint32_t width = 0;  // 0: the whole image
  uint32_t height = 0;

  bool wholeImage() const { return width == 0 || height == 0; }
  bool contains(uint32_t px, uint32_t py) const {
    return px >= x && py >= y && px - x < width && py - y < height;
  }
};

// The region on an image of the given size: the whole image for an empty
// one. Throws rt::Error if it does not lie inside the image.
PixelRegion resolveRegion(const PixelRegion& region, uint32_t imageWidth, uint32_t imageHeight);

// "X,Y,WIDTH,HEIGHT" (e.g. "120,80,64,48"); throws rt::Error naming `what`.
PixelRegion parseRegion(const std::string& text, const std::string& what);

}  // namespace rt
