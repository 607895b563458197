#include "imaging/ImageError.hpp"

#include <fmt/format.h>

#include <cmath>

#include "noise_types.h"
#include "util/Error.hpp"

namespace rt {

double displayRmse(const ImageF& image, const ImageF& reference, const ToneMapping& mapping,
                   const PixelRegion& region) {
  if (image.width != reference.width || image.height != reference.height) {
    throw Error(fmt::format("image is {}x{} but the reference is {}x{}", image.width, image.height,
                            reference.width, reference.height));
  }
  const PixelRegion r = resolveRegion(region, image.width, image.height);
  double sum = 0;
  for (uint32_t y = r.y; y < r.y + r.height; ++y) {
    for (uint32_t x = r.x; x < r.x + r.width; ++x) {
      const float* a = image.pixel(x, y);
      const float* b = reference.pixel(x, y);
      for (int c = 0; c < 3; ++c) {
        double d = double(displayValue(a[c], mapping)) - displayValue(b[c], mapping);
        sum += d * d;
      }
    }
  }
  return std::sqrt(sum / (3.0 * r.width * r.height));
}

std::optional<double> estimatePixelSquaredError(const SampleSums& sums, size_t pixel,
                                                const ToneMapping& mapping) {
  const float squared =
      gpu::pixelSquaredError(sums.all[pixel], sums.odd[pixel], mapping.exposure,
                             static_cast<uint32_t>(mapping.curve), mapping.srgbEncode ? 1u : 0u);
  if (squared < 0.0f) return std::nullopt;
  return squared;
}

std::optional<double> estimateDisplayRmse(const SampleSums& sums, const ToneMapping& mapping,
                                          const PixelRegion& region) {
  const PixelRegion r = resolveRegion(region, sums.width, sums.height);
  double sum = 0;
  for (uint32_t y = r.y; y < r.y + r.height; ++y) {
    for (uint32_t x = r.x; x < r.x + r.width; ++x) {
      std::optional<double> pixel =
          estimatePixelSquaredError(sums, size_t(y) * sums.width + x, mapping);
      if (!pixel) return std::nullopt;
      sum += *pixel;
    }
  }
  return std::sqrt(sum / (double(r.width) * r.height));
}

std::vector<float> estimatedErrorImage(const SampleSums& sums, const ToneMapping& mapping) {
  std::vector<float> errors(sums.all.size(), -1.0f);
  for (size_t i = 0; i < errors.size(); ++i) {
    if (std::optional<double> squared = estimatePixelSquaredError(sums, i, mapping)) {
      errors[i] = static_cast<float>(std::sqrt(*squared));
    }
  }
  return errors;
}

}  // namespace rt
