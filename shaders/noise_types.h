// The noise measurement from the even/odd replicate sums (imaging/ImageError.hpp
// explains the estimate), shared by the host and shaders/tile_noise.comp.
// The kernel reduces every adaptive tile's pixels on the device, so a round
// of adaptive sampling reads back a few numbers per tile instead of the two
// accumulation buffers. Same layout rules as gpu_types.h.
#ifndef RT_NOISE_TYPES_H
#define RT_NOISE_TYPES_H

#include "tone_mapping.h"

#ifdef __cplusplus
namespace rt::gpu {
#endif

// Descriptor set 0 of tile_noise.comp.
#define RT_NOISE_BINDING_ACCUMULATION 0      // vec4 per pixel: rgb sum, a = sample count
#define RT_NOISE_BINDING_ACCUMULATION_ODD 1  // the same over the odd sample indices
#define RT_NOISE_BINDING_TILES 2             // GpuTileNoise per tile, row-major
#define RT_NOISE_BINDING_PIXEL_EXTRAS 3      // uint per pixel: its edge-round samples
#define RT_NOISE_BINDING_TILE_LIST 4         // uint per listed tile: the tiles to measure

#define RT_NOISE_WORKGROUP_SIZE 64  // tiles a workgroup measures, one an invocation

// One tile of RT_ADAPTIVE_TILE_SIZE^2 pixels, over its pixels in the region.
// The pixels the edge round picked are measured apart: they were picked for
// their contrast, so pooled with the others they would raise the noise that
// the tile's pixels of one sample take from the pool.
struct GpuTileNoise {
  float varianceSum;      // sum of pixelSquaredError * samples: one sample's variance,
                          // over the pooled pixels (both halves, no edge samples)
  float squaredSum;       // sum of pixelSquaredError over all pixels with both halves
  float inverseCountSum;  // sum of 1 / samples over pixels with samples but one half empty
  uint measured;          // pixels with both halves
  uint unsampled;         // pixels without any sample
  uint pooled;            // pixels in varianceSum
  float edgeVarianceSum;  // varianceSum's sum over the measured pixels with edge samples
  uint pad0;
};
RT_ASSERT_STD430_SIZE(GpuTileNoise, 32);

// Push constants of one tile_noise.comp dispatch (one invocation per tile).
struct GpuTileNoiseParams {
  uvec2 size;         // image size in pixels
  uvec2 regionStart;  // first pixel of the measured region
  uvec2 regionEnd;    // one past its last pixel
  float exposure;     // the display mapping (tone_mapping.h)
  uint toneCurve;
  uint srgbEncode;
  // 1: a pixel extras buffer is bound (an adaptive render's: zero until its
  // edge round, and after a reset), 0: none, unread
  uint hasPixelExtras;
  uint listedTiles;  // 0: every tile, one an invocation; else the tile list's first this many
  uint pad0;
};
RT_ASSERT_STD430_SIZE(GpuTileNoiseParams, 48);

// The squared error of a pixel's displayed mean, mean over r, g, b, estimated
// from its even and odd halves (sums `total` of all samples and `odd` of the
// odd-indexed ones, a = sample count): the halves' squared difference
// weighted by nEven nOdd / n^2. -1 when a half has no sample.
RT_SHARED_FUNCTION float pixelSquaredError(vec4 total, vec4 odd, float exposure, uint toneCurve,
                                           uint srgbEncode) {
  vec4 even = total - odd;
  if (!(odd.w > 0.0f && even.w > 0.0f)) return -1.0f;
  float n = even.w + odd.w;
  float weight = even.w * odd.w / (n * n);
  float sum = 0.0f;
  for (int c = 0; c < 3; ++c) {
    float d = displayChannel(even[c] / even.w, exposure, toneCurve, srgbEncode) -
              displayChannel(odd[c] / odd.w, exposure, toneCurve, srgbEncode);
    sum += d * d;
  }
  return sum * weight / 3.0f;
}

#ifdef __cplusplus
}  // namespace rt::gpu
#endif

#endif  // RT_NOISE_TYPES_H
