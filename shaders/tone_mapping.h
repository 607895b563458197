// How linear radiance becomes a display value: one definition for the image
// writers (src/io/Image.cpp), the viewer's display pass (display.comp) and
// the noise measurement (noise_types.h), so all three see the same values.
#ifndef RT_TONE_MAPPING_H
#define RT_TONE_MAPPING_H

#include "gpu_types.h"

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
namespace rt::gpu {
using std::min;
using std::pow;
#endif

// The tone curves: rt::ToneCurve's values.
#define RT_TONE_CURVE_CLAMP 0u
#define RT_TONE_CURVE_REINHARD 1u
#define RT_TONE_CURVE_ACES 2u

// One linear channel value as displayed, in [0, 1]: exposure, the curve (NaN
// and negatives go to 0), then the sRGB transfer function when srgbEncode is 1.
RT_SHARED_FUNCTION float displayChannel(float linear, float exposure, uint toneCurve,
                                        uint srgbEncode) {
  float exposed = linear * exposure;
  if (!(exposed > 0.0f)) exposed = 0.0f;
  if (toneCurve == RT_TONE_CURVE_REINHARD) {
    exposed = exposed / (1.0f + exposed);
  } else if (toneCurve == RT_TONE_CURVE_ACES) {
    exposed = exposed * (2.51f * exposed + 0.03f) / (exposed * (2.43f * exposed + 0.59f) + 0.14f);
  }
  float unit = min(exposed, 1.0f);
  if (srgbEncode != 0u) {
    unit = unit <= 0.0031308f ? 12.92f * unit : 1.055f * pow(unit, 1.0f / 2.4f) - 0.055f;
  }
  return unit;
}

// The inverse of the sRGB transfer function: an encoded value in [0, 1] (a
// texel, a mesh file's vertex colour) as linear.
RT_SHARED_FUNCTION float linearFromSrgb(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : pow((encoded + 0.055f) / 1.055f, 2.4f);
}

#ifdef __cplusplus
}  // namespace rt::gpu
#endif

#endif  // RT_TONE_MAPPING_H
