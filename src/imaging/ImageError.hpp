// Errors of renders measured where users see them: in display space, i.e.
// the value a PNG gets (exposure, tone curve, clamp to [0, 1], sRGB encoding
// if the scene asks for it) before 8-bit quantization, averaged over the
// three colour channels of every pixel of a region. `raytracer converge`,
// --target-rmse and the progress display all use these definitions.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "imaging/PixelRegion.hpp"
#include "io/Image.hpp"

namespace rt {

// Root mean square difference of two same-sized images of linear radiance,
// both mapped with `mapping`, over `region` (empty: the whole image).
// Throws rt::Error if the sizes differ or the region does not fit.
double displayRmse(const ImageF& image, const ImageF& reference, const ToneMapping& mapping,
                   const PixelRegion& region = {});

// Per-pixel accumulation sums as the render kernel keeps them (rgb: radiance
// sum, a: sample count), for all samples and for the odd-indexed ones alone.
struct SampleSums {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::vec4> all;
  std::vector<glm::vec4> odd;
};

// The renderer's own estimate of displayRmse(mean of all samples, the
// converged image). Even and odd sample indices are independently
// randomised replicates (shaders/rng.glsl), so their means A and B are
// independent and unbiased, and with nA + nB = n samples
//   E[(A - B)^2] * nA * nB / n^2 = Var(mean of all n).
// The difference is taken after display mapping (a first-order estimate
// where the tone curve bends). It measures noise only: a biased renderer
// would look better than it is. nullopt while some pixel of the region has
// no sample in one of the halves.
std::optional<double> estimateDisplayRmse(const SampleSums& sums, const ToneMapping& mapping,
                                          const PixelRegion& region = {});

// The same estimate for one pixel (index y * width + x): its expected
// squared display error, averaged over the colour channels; nullopt while
// one half has no sample. One pixel's estimate is noisy (few degrees of
// freedom); averages over many pixels are not.
std::optional<double> estimatePixelSquaredError(const SampleSums& sums, size_t pixel,
                                                const ToneMapping& mapping);

// sqrt(estimatePixelSquaredError) for every pixel, row-major; -1 where a
// pixel has no estimate (outside the rendered region, or too few samples).
std::vector<float> estimatedErrorImage(const SampleSums& sums, const ToneMapping& mapping);

}  // namespace rt
