#include "imaging/PixelRegion.hpp"

#include <fmt/format.h>

#include <regex>

#include "util/Error.hpp"

namespace rt {

PixelRegion resolveRegion(const PixelRegion& region, uint32_t imageWidth, uint32_t imageHeight) {
  if (region.wholeImage()) return {0, 0, imageWidth, imageHeight};
  if (region.x >= imageWidth || region.y >= imageHeight || region.width > imageWidth - region.x ||
      region.height > imageHeight - region.y) {
    throw Error(fmt::format("region {},{},{},{} does not fit in the {}x{} image", region.x,
                            region.y, region.width, region.height, imageWidth, imageHeight));
  }
  return region;
}

PixelRegion parseRegion(const std::string& text, const std::string& what) {
  static const std::regex pattern(R"((\d{1,6}),(\d{1,6}),(\d{1,6}),(\d{1,6}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    throw Error(fmt::format("{} {}: expected X,Y,WIDTH,HEIGHT, e.g. 100,50,64,64", what, text));
  }
  auto field = [&](int i) { return static_cast<uint32_t>(std::stoul(match[i].str())); };
  PixelRegion region{field(1), field(2), field(3), field(4)};
  if (region.width == 0 || region.height == 0) {
    throw Error(fmt::format("{} {}: width and height must be positive", what, text));
  }
  return region;
}

}  // namespace rt
