#include "imaging/Merge.hpp"

#include <fmt/format.h>

#include "util/Error.hpp"

namespace rt {

ImageF mergeRenders(const std::vector<ImageF>& parts) {
  if (parts.empty()) throw Error("merge: no images given");
  const uint32_t width = parts[0].width;
  const uint32_t height = parts[0].height;
  for (size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].width != width || parts[i].height != height) {
      throw Error(fmt::format("merge: image {} is {}x{}, the first is {}x{}", i + 1, parts[i].width,
                              parts[i].height, width, height));
    }
  }
  ImageF merged{width, height, std::vector<float>(size_t(width) * height * 4, 0.0f)};
  // Means are weighted by their sample counts; sums are kept in double so
  // that the merge adds no rounding of its own beyond the final division.
  for (size_t pixel = 0; pixel < size_t(width) * height; ++pixel) {
    double sum[3] = {0, 0, 0};
    double count = 0;
    for (const ImageF& part : parts) {
      const float* p = &part.rgba[pixel * 4];
      if (!(p[3] >= 0.0f)) throw Error("merge: an image has a negative or NaN sample count");
      for (int c = 0; c < 3; ++c) sum[c] += double(p[c]) * p[3];
      count += p[3];
    }
    if (count <= 0) throw Error(fmt::format("merge: pixel {} has no samples in any image", pixel));
    for (int c = 0; c < 3; ++c) merged.rgba[pixel * 4 + c] = float(sum[c] / count);
    merged.rgba[pixel * 4 + 3] = float(count);
  }
  return merged;
}

}  // namespace rt
